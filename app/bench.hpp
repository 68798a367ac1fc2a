// `chore bench`: the idle benchmark of the seed's Table A.10. The robot stands
// still with a zero action; each step runs physics (4 x 1/120 s), the
// extended-state update (when the scene's activity has one) and renders the
// egocentric camera. Reports env steps per second. Then the primitive action
// space: primitive steps per second for each primitive and activity in both
// modes, with planning and execution time per primitive. Then the cost of each
// observation modality (and noise model) per frame, over a state-only step.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace chore {

struct BenchOptions {
  std::vector<std::string> scenes = {"apartment", "studio", "restaurant"};
  int steps = 600;  // measured steps per repetition
  int repeats = 3;  // the median is reported
  int width = 128, height = 128;
  int vector_envs = 16;  // vector-env rows: several envs per thread shorten the idle tail of a round
  // Primitive rows: the scripted expert's episodes (seeds 0 ..) on each scene's
  // activity, in both execution modes; 0 skips them.
  int primitive_episodes = 3;
  // What to run, of "table", "vector", "primitives", "modalities" (the first
  // scene's activity, one env), "memory" (resident MB of a vector env of
  // vector_envs envs on the first scene, per env, for both action spaces; not
  // run by default).
  std::vector<std::string> sections = {"table", "vector", "primitives", "modalities"};
};

// Runs the benchmark and returns its results; `log` gets progress lines.
nlohmann::json run_bench(const BenchOptions& options, std::ostream& log);
// The Table A.10-shaped text table of run_bench's results.
std::string format_bench(const nlohmann::json& results);

}  // namespace chore
