// One activity solved: planned over the primitives' symbolic models and the
// world's steps (planner/task_planner.hpp), then the plan executed by the
// planned expert (policies/planned_expert.hpp) in an Env with the primitive
// action space, in one execution mode, from one seed's instance. A plan
// counts only when executing it ends with chore's own success (Q = 1).
// `chore activity solve` runs it on a file or on every file of a folder,
// each in a child process, through the coverage runner (activity_coverage.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include <opencv2/core.hpp>

#include <cstdint>

#include "env/env.hpp"

namespace chore {

// {"built" (an instance with everything the action space acts on within the
// robot's reach, EnvConfig::reachable_instances), "found", "expansions",
// "planning_seconds", "plan" (its steps; the world's in brackets),
// "primitives" (the plan's), "solved", "q", "steps_taken" (actions the env
// ran, retries included), "replans" (plans from the world after a failure),
// "reason" (why not solved)}. The env is `config`
// with the primitive action space in `mode`. With `final_state`, a solved
// activity's last state is drawn into it (the head camera beside the scene
// from above, instance_picture, each `picture_size` pixels square), for
// `activity solve --sheet`.
nlohmann::json solve_activity(EnvConfig config, uint64_t seed, ExecutionMode mode, cv::Mat* final_state = nullptr,
                              int picture_size = 0);

}  // namespace chore
