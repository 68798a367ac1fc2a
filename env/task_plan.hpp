// The task planner (planner/) on an env's activity as the env's scene has it:
// the activity's symbolic problem, and which primitive actions a plan for its
// goal acts on (what an instance must keep within the robot's reach for the
// task to be doable at all).
#pragma once

#include <cstddef>
#include <optional>
#include <set>
#include <string>

#include "planner/symbolic_problem.hpp"
#include "tasks/activity.hpp"
#include "world/scene.hpp"

namespace chore {

// The activity's symbolic problem (planner/symbolic_problem.hpp) with what
// the knowledge base calls openable but the scene's object has no joint to
// open (a bin without a lid) open as it stands.
SymbolicProblem symbolic_problem(const Activity& activity, const Scene& scene);

// The primitive actions (by name, "pick(apple.n.01_1)") a plan for the goal
// from :init takes: the plan's when the planner finds one within
// kNeededActionsBudget expansions (three in four of the plans BEHAVIOR-1K's
// activities have take fewer; its cost is paid once per set of envs, by
// load_assets), else its relaxed plan's (the heuristic's, found without
// search); nullopt where no option of the goal is reachable even relaxed
// (nothing says which actions matter).
inline constexpr size_t kNeededActionsBudget = 200;
std::optional<std::set<std::string>> actions_a_plan_needs(const Activity& activity, const Scene& scene);

}  // namespace chore
