// The task planner as an expert for any activity (planner/task_planner.hpp):
// it plans from the activity's :init over the symbolic models of the
// primitives the env's action space offers and the world's steps, then gives
// the plan's primitives in order as actions of the primitive action space. A
// primitive that fails is tried again (up to kRetries times: the physical
// ones sample their base poses and grasps anew); when one still fails, or the
// plan is done and the goal does not hold (a wipe left dirt behind), it plans
// again from the world as it finds it (each literal the planner knows read
// from the world: the activity's predicates, the hand, the arm's reach), up
// to kReplans times an episode, then gives up saying which step failed and why.
// A step that has failed so in kBarAfter plans, with the hand as it was (what
// it held, or empty), is left out of the plans that follow while the hand is
// so: they look for another way (another place for the load, another order),
// and where there is none, try it again. Where the plan is done and what its
// world steps still have to make takes time (an egg set on a lit stove cooks
// as time passes), it waits first (the wait primitive, on their objects, the
// last first; up to kWaits times an episode), and plans again when the world
// no longer changes.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "env/state.hpp"
#include "planner/task_planner.hpp"

namespace chore {

class PlannedExpert {
 public:
  static constexpr int kRetries = 2;
  static constexpr int kReplans = 8;
  static constexpr int kBarAfter = 2;
  static constexpr int kWaits = 16;
  // `env` must use the primitive action space and have an activity;
  // chore::Error otherwise.
  explicit PlannedExpert(const EnvState& env, const PlanOptions& options = {});
  const Plan& initial_plan() const { return initial_; }  // from :init
  const Plan& plan() const { return plan_; }             // the one it follows now
  int replans() const { return replans_; }

  // From :init's plan again (after the env's reset).
  void restart(const EnvState& env);
  // The next action index; nullopt when the goal holds, there is no plan,
  // or it gave up (failure() says why). `last` is the status of the
  // primitive the previous action ran (ignored on the first call). A
  // navigate to what is within reach already is passed over.
  std::optional<int> act(const EnvState& env, PrimitiveStatus last, const std::string& last_reason);
  const std::string& failure() const { return unusable_.empty() ? failure_ : unusable_; }

 private:
  // Follows `plan` from its first step; false (failure_ set) where one of its
  // primitives is not in the action space.
  bool follow(const EnvState& env, Plan plan);
  // Plans again from the world as it is; false (failure_ set) without a plan.
  bool replan(const EnvState& env, const std::string& why);
  // At the plan's end: a wait on an object of its world steps that have not
  // made what they make yet, the last first, that has not failed since the
  // plan began; nullopt for none.
  std::optional<int> wait_for_world(const EnvState& env) const;

  SymbolicProblem problem_;
  GroundSteps steps_of_problem_;  // its ground steps, the same whatever :init
  const GroundGoal* goal_ = nullptr;
  PlanOptions options_;
  std::vector<SymbolicLiteral> literals_;  // what the planner knows of: read from the world to plan again
  Plan initial_;
  Plan plan_;
  std::vector<int> actions_;   // per plan step: its action index, -1 for the world's steps
  std::vector<size_t> steps_;  // the plan's primitive steps, in order
  size_t next_ = 0;            // into steps_
  int tries_ = 0;              // of steps_[next_ - 1]
  int replans_ = 0;            // this episode
  int waits_ = 0;              // this episode
  int waiting_ = -1;           // the wait action just given, else -1
  std::set<int> still_;        // wait actions that failed since this plan began (nothing changes)
  // Per primitive step and the hand's literal when it failed (grasped X, or
  // handempty): the plans it failed in this episode.
  std::map<std::pair<std::string, SymbolicLiteral>, int> failed_;
  std::string unusable_;  // why there is no plan from :init
  std::string failure_;   // why this episode's stopped short
};

}  // namespace chore
