// The README's quick tour of the C++ API, compiled and run by ctest so that
// it stays true.
#include <cstdio>
#include <vector>

#include "env/env.hpp"
#include "env/vector_env.hpp"

int main() {
  chore::Env env({.activity = "store_decoration"});  // its scene, 128x128 RGB-D, proprio, is_grasping
  auto [obs, info] = env.reset(42);
  std::vector<float> action(chore::kLowLevelActionSize, 0.f);  // RL-VMC action, [-1, 1]
  auto step = env.step(action);  // step.obs, step.reward, step.terminated, step.truncated, step.info
  std::printf("Q %.2f after one step, reward %.2f, %s\n", step.info.q, step.reward,
              env.observation_space().to_string().c_str());

  chore::VectorEnv vec({.env = {.scene = "apartment"}, .num_envs = 4, .num_threads = 2});
  chore::Batch batch = vec.reset(0);  // env i seeded 0 + i
  std::vector<float> actions(4 * chore::kLowLevelActionSize, 0.f);
  batch = vec.step(actions);  // (*batch.obs)["rgb"] is (4, 128, 128, 3) uint8
  const auto& shape = (*batch.obs)["rgb"].shape;
  std::printf("batch of %d: rgb (%d, %d, %d, %d)\n", batch.size(), shape[0], shape[1], shape[2], shape[3]);
  return 0;
}
