// The baselines (Figure A.11): a new one is a line here. Apart from the
// algorithms (algorithms.cpp) because it needs no LibTorch: the command line's
// parser names them, and its fuzz target is built by clang, which cannot
// compile LibTorch's headers in C++20.
#include "training/trainer.hpp"

namespace chore {

const std::vector<Baseline>& baselines() {
  static const std::vector<Baseline> list = {
      // Figure A.11 (a): egocentric RGB and proprioception, joint-level control.
      {"rl-vmc", "sac",
       [](TrainConfig& c) {
         c.env.observations = {"rgb", "proprio", "is_grasping"};
         c.env.action_space = "low_level";
       }},
      // Figure A.11 (b), appendix F.1: RGB and is-grasping, physical primitives;
      // with history, the policy also sees the last K steps.
      {"rl-prim", "ppo",
       [](TrainConfig& c) {
         c.env.observations = {"rgb", "is_grasping"};
         c.env.action_space = "primitives";
         c.env.primitive_mode = ExecutionMode::physical;
         c.ppo.history = 0;
       }},
      {"rl-prim-hist", "ppo",
       [](TrainConfig& c) {
         c.env.observations = {"rgb", "is_grasping"};
         c.env.action_space = "primitives";
         c.env.primitive_mode = ExecutionMode::physical;
       }},
  };
  return list;
}

}  // namespace chore
