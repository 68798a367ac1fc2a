// The task planner as an expert for any activity (planner/task_planner.hpp):
// it plans once from the activity's :init over the symbolic models of the
// primitives the env's action space offers and the world's steps, then gives
// the plan's primitives in order as actions of the primitive action space. A primitive that fails is tried
// again (up to kRetries times: the physical ones sample their base poses and
// grasps anew) before the expert gives up, saying which step failed and why.
// Open loop: it does not plan again from the world as it finds it.
#pragma once

#include <optional>
#include <string>

#include "env/state.hpp"
#include "planner/task_planner.hpp"

namespace chore {

class PlannedExpert {
 public:
  static constexpr int kRetries = 2;
  // `env` must use the primitive action space and have an activity;
  // chore::Error otherwise.
  explicit PlannedExpert(const EnvState& env, const PlanOptions& options = {});
  const Plan& plan() const { return plan_; }

  // From the plan's first step again (after the env's reset).
  void restart();
  // The next action index; nullopt when the plan is done, there is none,
  // or a step failed for good (failure() says which). `last` is the status of
  // the primitive the previous action ran (ignored on the first call). A
  // navigate to what is within reach already is passed over.
  std::optional<int> act(const EnvState& env, PrimitiveStatus last, const std::string& last_reason);
  const std::string& failure() const { return unusable_.empty() ? failure_ : unusable_; }

 private:
  Plan plan_;
  std::vector<int> actions_;   // per plan step: its action index, -1 for the world's steps
  std::vector<size_t> steps_;  // the plan's primitive steps, in order
  size_t next_ = 0;            // into steps_
  int tries_ = 0;              // of steps_[next_ - 1]
  std::string unusable_;       // why there is no plan to follow
  std::string failure_;        // why this episode's stopped short
};

}  // namespace chore
