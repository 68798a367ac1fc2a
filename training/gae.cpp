#include "training/gae.hpp"

namespace chore {

Advantages estimate_advantages(const RolloutSteps& steps, const torch::Tensor& next_value, double gamma,
                               double gae_lambda) {
  torch::NoGradGuard no_grad;
  const int64_t t_steps = static_cast<int64_t>(steps.rewards.size());
  torch::Tensor advantages = torch::zeros({t_steps, next_value.size(0)});
  torch::Tensor following_value = next_value, following_advantage = torch::zeros_like(next_value);
  for (int64_t t = t_steps - 1; t >= 0; --t) {
    const torch::Tensor live = 1.0 - torch::clamp_max(steps.terminated[t] + steps.truncated[t], 1.0);
    const torch::Tensor reward = steps.rewards[t] + gamma * steps.truncated[t] * steps.final_values[t];
    const torch::Tensor delta = reward + gamma * following_value * live - steps.values[t];
    following_advantage = delta + gamma * gae_lambda * live * following_advantage;
    advantages[t] = following_advantage;
    following_value = steps.values[t];
  }
  return {advantages, advantages + torch::stack(steps.values)};
}

}  // namespace chore
