// `chore activity coverage DIR`: how much of an activity corpus chore runs.
// Each .bddl problem file under DIR (domain files skipped) is parsed and
// grounded against its dialect, then instantiated at one seed in an Env (its
// scene: tasks/activities/scenes.json, else the analog of a BEHAVIOR-1K
// scene); the report gives the share at each stage, the seconds each took,
// how many have what a plan for the goal acts on (env/task_plan.hpp) within
// the robot's reach, how many ran in a VectorEnv (CoverageOptions::steps) and ran random primitives
// (CoverageOptions::primitive_steps), and the failures grouped by
// cause (the error with its names and numbers blanked), each with an example.
// For every parsed activity it also judges which ground goal literals some
// sequence of primitives and transition rules could make hold (the planner's
// relaxed reachability, planner/reachability.hpp), totals them and groups
// those none can by predicate, and names future objects no rule makes. With
// CoverageOptions::solve, it plans and executes each (`chore activity solve`).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "primitives/primitive_types.hpp"

namespace chore {

struct CoverageOptions {
  std::string dir;
  uint64_t seed = 0;
  int threads = 1;  // files instantiated at once, each in a child process (a crash is reported, not shared)
  // After instantiating, run each in a VectorEnv for this many random
  // low-level steps (0: not run), checking it starts as the Env did.
  int steps = 0;
  // Then this many random actions of the primitive action space, executed
  // physically, from the same seed (0: none).
  int primitive_steps = 0;
  // Stop after the goal's reach: no world is built (the other options must be off).
  bool goals_only = false;
  // A PNG of every instantiated activity's head camera and top-down view ("": none).
  std::string sheet;
  // Then plan and execute each in this mode (app/activity_solve.hpp): `chore
  // activity solve`, from the instances of seeds `seed` to `last_seed`
  // (solved: at every one of them).
  std::optional<ExecutionMode> solve;
  uint64_t last_seed = 0;
};

// `options.dir` is a folder, or one .bddl file.
nlohmann::json activity_coverage(const CoverageOptions& options, std::ostream& log);
std::string format_coverage(const nlohmann::json& coverage);
// activity_coverage's report with `solve`, as `chore activity solve` prints it.
std::string format_solve(const nlohmann::json& coverage);

// An error message with its location, synsets, names with a '.' or '/', and
// numbers blanked, so that failures of one cause read alike:
// "f.bddl:3:4: unknown synset 'x.n.01'" -> "unknown synset '_'". The cause
// is the blanked message's first kMaxCauseChars characters (blanked first:
// names of other lengths would end it elsewhere); only the message's first
// kMaxCauseReadChars are read.
inline constexpr size_t kMaxCauseChars = 300;
inline constexpr size_t kMaxCauseReadChars = 4 * kMaxCauseChars;
std::string failure_cause(const std::string& error);

}  // namespace chore
