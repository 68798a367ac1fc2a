// chore::EnvState: what a policy that reads the simulator's state, beside or
// instead of the observations, sees of one env: read-only, and nothing that
// steps or resets it. The scripted expert acts through it
// (VectorEnv::state(i); an Env is one).
#pragma once

#include <vector>

#include "env/primitive_actions.hpp"
#include "env/types.hpp"

namespace chore {

struct EnvConfig;

class EnvState {
 public:
  virtual ~EnvState() = default;
  virtual const EnvConfig& config() const = 0;
  virtual const World& world() const = 0;
  virtual const Activity* activity() const = 0;  // nullptr without one
  // The primitive action space's actions, in action order (empty for low_level).
  virtual const std::vector<PrimitiveAction>& primitive_actions() const = 0;
};

}  // namespace chore
