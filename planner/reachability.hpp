// Which literals some sequence of the primitives' steps and the world's could
// make hold, under the delete relaxation (what steps undo is ignored, as in
// planners' h_max and h_add heuristics): a literal is reachable when a step
// whose needs are all reachable adds it, and deletable when such a step
// deletes it. It over-approximates: a literal it finds unreachable, no plan
// reaches; one it finds reachable a plan may still not (issue 57's planner
// decides). Steps' needs_not are ignored, as relaxations do.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "planner/symbolic_problem.hpp"
#include "tasks/goal.hpp"

namespace chore {

struct Reachability {
  std::set<SymbolicLiteral> reachable;  // :init and what steps can add
  std::set<SymbolicLiteral> deletable;  // what steps can delete
  // The first step found to add each reachable literal not in :init.
  std::map<SymbolicLiteral, std::string> achiever;
  // Whether a BDDL literal (negated flag included) can be made to hold: a
  // positive one when reachable, a negated one when it does not hold at
  // :init or can be deleted.
  bool achievable(const SymbolicProblem& problem, const Literal& literal) const;
};

// Every primitive's steps on every target (with every object in hand, and
// every substance, where its model takes them), then every world step.
struct GroundSteps {
  std::vector<SymbolicStep> steps;
  size_t primitives = 0;  // steps[0, primitives) are the primitives', the rest the world's
};
GroundSteps ground_steps(const SymbolicProblem& problem);

// Over ground_steps(problem).
Reachability reachability(const SymbolicProblem& problem);

// Of an activity's ground goal literals (GroundGoal::literals: each distinct
// one once), those no sequence can make hold, grouped by predicate (a negated
// one as "not covered").
struct GoalReach {
  size_t literals = 0, achievable = 0;
  std::map<std::string, std::vector<std::string>> unachievable;  // predicate -> the literals, as BDDL text
  // Objects (future X) in :init that no rule of the knowledge base makes (a
  // rule producing their synset or a descendant), and those the relaxed
  // search cannot make real in this activity.
  size_t future = 0;  // objects (future X) in :init
  std::vector<std::string> future_without_rule, future_unreachable;
};
GoalReach goal_reach(const SymbolicProblem& problem, const Reachability& reach, const GroundGoal& goal,
                     const KnowledgeBase& kb, const TransitionRules& rules);

}  // namespace chore
