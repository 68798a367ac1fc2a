// A scripted expert for the primitive action space: it reads the activity's
// goal and the world state and picks the next (primitive, object) action, as
// a person scripting BEHAVIOR's primitives would. One script serves every
// activity whose goal is made of these literals:
//   (inside a b), (ontop a b)   open b if it has a closed drawer (navigate,
//                               push), then navigate a, pick a, navigate b, place b
//   (not (stained t)), (not (dusty t))
//                               navigate/pick a cleaning tool, soak it first
//                               for stains (navigate/dip a liquid container),
//                               then navigate t, wipe t until clean
// It takes the first unsatisfied literal of the goal's first option.
#pragma once

#include <optional>

#include "env/state.hpp"
#include "env/vector_env.hpp"
#include "policies/planned_expert.hpp"
#include "policies/policy.hpp"

namespace chore {

class ScriptedExpert {
 public:
  // `env` must use the primitive action space; chore::Error otherwise.
  explicit ScriptedExpert(const EnvState& env);
  // The next action index, or nullopt when the goal holds or no literal is one it knows.
  std::optional<int> act(const EnvState& env) const;
  // Whether the script knows every literal of the goal's first option
  // (objects inside or on top of others, surfaces cleaned: the paper's three
  // activities and those like them).
  static bool knows(const Activity& activity);

 private:
  std::optional<int> action(PrimitiveType type, int object) const;
  std::optional<int> go_and(const EnvState& env, PrimitiveType type, int object) const;
  std::optional<int> put(const EnvState& env, int item, int target) const;
  std::optional<int> clean(const EnvState& env, int surface, bool needs_soaked_tool) const;

  const std::vector<PrimitiveAction>* actions_;
};

// The expert as a Policy over a VectorEnv's envs (it reads their state
// through VectorEnv::state, not the observations): the scripted expert where
// it knows the goal (ScriptedExpert::knows), else the task planner's
// (policies/planned_expert.hpp), one per env, planned at its first reset.
// Where the expert has no action (the goal holds, a literal the script does
// not know, a plan given up), it gives up the seed's way: it repeats an action
// whose precondition fails, which changes nothing.
class ExpertPolicy : public Policy {
 public:
  // `envs` must outlive the policy and use the primitive action space.
  explicit ExpertPolicy(const VectorEnv& envs);
  void act(const Batch& batch, std::span<float> actions) override;
  void reset(std::span<const int> env_ids) override;
  bool planned() const { return planned_; }

 private:
  const VectorEnv& envs_;
  ScriptedExpert expert_;
  bool planned_;
  std::vector<std::optional<PlannedExpert>> planners_;  // per env, when planned_
};

}  // namespace chore
