// PPO's loss on one minibatch, as Schulman et al. (2017, Eq. 9) write the
// objective and Table A.12 parameterises it: maximise L^CLIP - c2 L^VF + c1 S,
// where L^VF is the squared error (V(s_t) - V^targ_t)^2 and c2 is "VF Coeff"
// (0.5), c1 the entropy coefficient (0). Stable-Baselines3, the library
// OmniGibson's RL examples train with, computes the same (its value loss is
// the mean squared error times vf_coef); CleanRL halves the squared error.
#pragma once

#include <torch/torch.h>

namespace chore {

struct PpoLoss {
  torch::Tensor total;                            // what the optimiser minimises
  torch::Tensor policy, value, entropy;           // -L^CLIP, L^VF, S: means over the minibatch
  double approx_kl = 0, clip_fraction = 0;        // of the minibatch, before the step
};

// `logits` (B, A) and `values` (B) of the network now; `actions`, the rollout's
// `old_log_probs`, `advantages` and `returns` (B). Advantages are normalised
// over the minibatch when `normalize_advantage` (and B > 1).
PpoLoss ppo_loss(const torch::Tensor& logits, const torch::Tensor& values, const torch::Tensor& actions,
                 const torch::Tensor& old_log_probs, torch::Tensor advantages, const torch::Tensor& returns,
                 double clip, double value_coef, double entropy_coef, bool normalize_advantage);

}  // namespace chore
