// The baselines (Figure A.11): a new one is a line here. Apart from the
// algorithms (algorithms.cpp) because it needs no LibTorch: the command line's
// parser names them, and its fuzz target is built by clang, which cannot
// compile LibTorch's headers in C++20.
#include "training/trainer.hpp"

namespace chore {
namespace {

// The protocol of appendix F for the primitive baselines, as docs/baselines.md
// declares it: one pre-sampled instance per activity (OmniGibson's default),
// episodes ended by success or the time limit only (the real-robot policy
// failure rule of appendix G is EnvConfig::policy_failure_rule's option).
void primitive_setup(TrainConfig& c) {
  c.env.observations = {"rgb", "is_grasping"};
  c.env.action_space = "primitives";
  c.env.primitive_mode = ExecutionMode::physical;
  c.env.instances = "fixed";
}

}  // namespace

const std::vector<Baseline>& baselines() {
  static const std::vector<Baseline> list = {
      // Figure A.11 (a): egocentric RGB and proprioception, joint-level control.
      {"rl-vmc", "sac",
       [](TrainConfig& c) {
         c.env.observations = {"rgb", "proprio", "is_grasping"};
         c.env.action_space = "low_level";
         c.env.instances = "fixed";
       }},
      // Figure A.11 (b), appendix F.1: RGB and is-grasping, physical primitives.
      {"rl-prim", "ppo", [](TrainConfig& c) { primitive_setup(c); }},
      // "with the history of observations" (appendix F): the encoder's inputs
      // of the last K = 4 steps (docs/baselines.md: why 4).
      {"rl-prim-hist", "ppo",
       [](TrainConfig& c) {
         primitive_setup(c);
         c.ppo.frames = 4;
       }},
      // chore's own variant: the last K = 4 primitives and how each ended.
      {"rl-prim-action-hist", "ppo",
       [](TrainConfig& c) {
         primitive_setup(c);
         c.ppo.history = 4;
       }},
  };
  return list;
}

}  // namespace chore
