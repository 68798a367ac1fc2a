// Generalised advantage estimation over one PPO rollout (Schulman et al.,
// 2016), with episode ends as Stable-Baselines3 and CleanRL treat them: a
// terminated episode is worth nothing after its last step; a truncated one
// (the time limit) is bootstrapped from the value of its final observation,
// added to its last reward. Either way the next row of that env starts a
// new episode, so no advantage flows back across the end.
#pragma once

#include <torch/torch.h>

#include <vector>

namespace chore {

// T steps of N envs, one (N) float tensor per step each.
struct RolloutSteps {
  std::vector<torch::Tensor> rewards, values;  // r_t, V(s_t)
  std::vector<torch::Tensor> terminated, truncated;  // 1 where the step ended the episode so
  std::vector<torch::Tensor> final_values;  // V(final observation) where truncated, else 0
};

struct Advantages {
  torch::Tensor advantages, returns;  // (T, N); returns = advantages + values
};

// `next_value`: V of each env's observation after the rollout's last step.
Advantages estimate_advantages(const RolloutSteps& steps, const torch::Tensor& next_value, double gamma,
                               double gae_lambda);

}  // namespace chore
