// `chore expert`: the scripted expert (policies/expert.hpp) run over seeded
// episodes of an activity in the primitive action space; success rate, mean Q,
// mean episode length and the failure breakdown.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>
#include <string>

#include "primitives/primitive.hpp"

namespace chore {

struct ExpertOptions {
  std::string activity;
  int episodes = 100;
  uint64_t seed = 0;  // episode i uses seed + i
  ExecutionMode mode = ExecutionMode::physical;
  int max_steps = 60;  // primitive steps per episode
  int threads = 1;     // episodes run in parallel; results do not depend on it
  // The task planner's expert (policies/planned_expert.hpp: any activity)
  // in place of the scripted one (policies/expert.hpp) where the script
  // knows the goal (the paper's three); where it does not, the planner acts
  // whatever this says.
  bool planner = false;
};

// Runs the episodes; progress goes to `log`. Throws chore::Error on bad options.
nlohmann::json run_expert(const ExpertOptions& options, std::ostream& log);
std::string format_expert(const nlohmann::json& results);

}  // namespace chore
