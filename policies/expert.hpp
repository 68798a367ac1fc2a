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
#include "policies/policy.hpp"

namespace chore {

class ScriptedExpert {
 public:
  // `env` must use the primitive action space; chore::Error otherwise.
  explicit ScriptedExpert(const EnvState& env);
  // The next action index, or nullopt when the goal holds or no literal is one it knows.
  std::optional<int> act(const EnvState& env) const;

 private:
  std::optional<int> action(PrimitiveType type, int object) const;
  std::optional<int> go_and(const EnvState& env, PrimitiveType type, int object) const;
  std::optional<int> put(const EnvState& env, int item, int target) const;
  std::optional<int> clean(const EnvState& env, int surface, bool needs_soaked_tool) const;

  const std::vector<PrimitiveAction>* actions_;
};

// The scripted expert as a Policy over a VectorEnv's envs (it reads their
// state through VectorEnv::state, not the observations). Where the script has
// no action (a literal it does not know), it gives up the seed's way: it
// repeats an action whose precondition fails, which changes nothing and ends
// the episode as a policy failure.
class ExpertPolicy : public Policy {
 public:
  // `envs` must outlive the policy and use the primitive action space.
  explicit ExpertPolicy(const VectorEnv& envs);
  void act(const Batch& batch, std::span<float> actions) override;

 private:
  const VectorEnv& envs_;
  ScriptedExpert expert_;
};

}  // namespace chore
