// A plan for an activity's goal: which primitives, on which objects, in
// which order, over the primitives' symbolic models and the world's steps
// (planner/symbolic_problem.hpp: the same models the primitives' files state
// beside their execution). Greedy best-first search with deferred
// evaluation over the goal's options (tasks/goal.hpp: or, exists, forall,
// forn expanded), as Fast Downward's lazy greedy search: the FF heuristic
// (the relaxed plan read back from the additive heuristic's cheapest steps,
// Bonet and Geffner 2001, Hoffmann and Nebel 2001) with what steps need
// absent kept in the relaxation, the goal's literals that must go again on
// the way counted as missing, and a second open list of the children by
// helpful steps, taking turns with the first; the way found without the
// steps it can do without (greedy action elimination). Bounded by a number
// of expansions: running out of it is an outcome, never a hang.
//
//   const Plan p = plan_task(symbolic_problem(problem, kb, rules), ground_goal(problem));
//   for (const PlanStep& s : p.steps) if (s.primitive) ... s.name ("pick(apple.n.01_1)")
#pragma once

#include <cstddef>
#include <set>
#include <string>
#include <vector>

#include "planner/reachability.hpp"
#include "planner/symbolic_problem.hpp"
#include "tasks/goal.hpp"

namespace chore {

struct PlanStep {
  // A primitive's: its action's name in the primitive action space
  // ("pick(apple.n.01_1)"); the world's: what it makes happen by itself
  // once its conditions hold (a transition rule's name, "heated(...)").
  std::string name;
  bool primitive = true;
};

struct Plan {
  bool found = false;
  std::vector<PlanStep> steps;
  size_t option = 0;  // the goal option the plan makes hold
  size_t expansions = 0;
  double seconds = 0;
  std::string reason;  // why there is none
  // The primitive steps of the relaxed plan from the start to the goal
  // option it finds cheapest (the heuristic's, read back before any search):
  // what a plan would act on, known without searching; empty where no
  // option is reachable even relaxed.
  std::vector<std::string> relaxed;
  size_t primitives() const;  // steps that are primitives
};

struct PlanOptions {
  size_t max_expansions = 20000;
  // The primitive steps it may use, by name (an env's primitive action
  // space: to_string(PrimitiveAction)); all of them when empty.
  std::set<std::string> actions;
};

Plan plan_task(const SymbolicProblem& problem, const GroundGoal& goal, const PlanOptions& options = {});
// The same over `steps`, ground_steps(problem) computed once: they depend on
// the problem's objects and world steps, not on its :init, so a caller that
// plans again from another state keeps them.
Plan plan_task(const SymbolicProblem& problem, const GroundSteps& steps, const GroundGoal& goal,
               const PlanOptions& options = {});

}  // namespace chore
