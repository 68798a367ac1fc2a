#include "training/ppo_loss.hpp"

namespace chore {

PpoLoss ppo_loss(const torch::Tensor& logits, const torch::Tensor& values, const torch::Tensor& actions,
                 const torch::Tensor& old_log_probs, torch::Tensor advantages, const torch::Tensor& returns,
                 double clip, double value_coef, double entropy_coef, bool normalize_advantage) {
  const torch::Tensor log_probs_all = torch::log_softmax(logits, 1);
  const torch::Tensor log_probs = log_probs_all.gather(1, actions.unsqueeze(1)).squeeze(1);
  const torch::Tensor log_ratio = log_probs - old_log_probs;
  const torch::Tensor ratio = log_ratio.exp();
  if (normalize_advantage && advantages.size(0) > 1) {
    advantages = (advantages - advantages.mean()) / (advantages.std() + 1e-8);
  }
  PpoLoss l;
  l.policy = torch::max(-advantages * ratio, -advantages * torch::clamp(ratio, 1 - clip, 1 + clip)).mean();
  l.value = (values - returns).pow(2).mean();
  l.entropy = -(log_probs_all.exp() * log_probs_all).sum(1).mean();
  l.total = l.policy + value_coef * l.value - entropy_coef * l.entropy;
  torch::NoGradGuard no_grad;
  l.approx_kl = ((ratio - 1) - log_ratio).mean().item<double>();  // Schulman's k3 estimator, as SB3 and CleanRL
  l.clip_fraction = ((ratio - 1).abs() > clip).to(torch::kFloat32).mean().item<double>();
  return l;
}

}  // namespace chore
