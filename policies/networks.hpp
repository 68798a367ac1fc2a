// The baselines' networks (BEHAVIOR-1K appendix F.1, Figure A.11), in LibTorch.
// Only torch translation units include this header (policies/networks.cpp,
// training/ppo.cpp, training/sac.cpp, training/checkpoint_tensors.cpp): <torch/torch.h>
// costs ~20 s and 1 GB per file to compile.
//
//   Encoder      128x128x3 RGB, normalised by a per-channel running mean/std,
//                -> Conv-ReLU-MaxPool x3 -> Flatten;  state (is_grasping,
//                proprio), normalised per dimension where the spec says
//                (NetworkSpec::normalize_state), -> Linear-ReLU;  both
//                -> Linear-ReLU to a 128-d feature. With K frames
//                (RL-Prim.Hist.), the K observations' RGB as 3K channels
//                and their states side by side, each frame normalised alike.
//   ActorCritic  (PPO) feature [+ history of the K past primitives and how
//                each ended: rl-prim-action-hist] -> action logits over
//                primitives, value.
//   SacActor     feature -> tanh-squashed Gaussian over the low-level action.
//   SacCritic    its own Encoder + twin Q heads on (feature, action).
#pragma once

#include <torch/torch.h>

#include <nlohmann/json.hpp>

#include <memory>
#include <span>

#include "env/spaces.hpp"
#include "policies/network_spec.hpp"
#include "policies/policy.hpp"

namespace chore {

// A batch of observations as tensors: rgb (B, 3, H, W) uint8 (undefined when
// not observed), state (B, S) float32 (S may be 0); stacked K frames (FrameStack):
// rgb (B, 3K, H, W), state (B, K * S), newest frame first.
struct ObsTensors {
  torch::Tensor rgb, state;
  ObsTensors index(const torch::Tensor& rows) const;
};
ObsTensors obs_tensors(const ArrayDict& obs, const NetworkSpec& spec);

// Running mean and variance over samples of `dims` channels (Chan et al.'s
// parallel update), kept as module buffers so checkpoints hold them.
class RunningNormImpl : public torch::nn::Module {
 public:
  RunningNormImpl(int64_t dims, double clip);
  // `samples` is (N, dims).
  void update(const torch::Tensor& samples);
  // Normalises `x` whose dimension `dim` holds the channels; clipped to +-clip.
  torch::Tensor forward(const torch::Tensor& x, int64_t dim) const;
  // forward(images.to(kFloat32), 1) bit for bit, for uint8 images (B, C, H, W)
  // in one vectorised pass, without the float copy of the images.
  torch::Tensor forward_bytes(const torch::Tensor& images) const;

 private:
  torch::Tensor mean_, var_, count_;
  double clip_;
};
TORCH_MODULE(RunningNorm);

// nn::MaxPool2d(2) bit for bit, values and gradients, at a fraction of torch
// 1.13's CPU cost (the trunk's pooling; networks.cpp says why).
class MaxPool2x2Impl : public torch::nn::Module {
 public:
  torch::Tensor forward(const torch::Tensor& x);  // (B, C, H, W) float -> (B, C, H/2, W/2)
};
TORCH_MODULE(MaxPool2x2);

class EncoderImpl : public torch::nn::Module {
 public:
  explicit EncoderImpl(const NetworkSpec& spec);
  torch::Tensor forward(const ObsTensors& obs);  // (B, feature_size)
  // Moves the normalisers' statistics towards this batch (acting time only).
  void update_normalizers(const ObsTensors& obs);

 private:
  int64_t frames_;
  torch::nn::Sequential trunk_{nullptr}, state_net_{nullptr}, mlp_{nullptr};
  RunningNorm rgb_norm_{nullptr}, state_norm_{nullptr};
};
TORCH_MODULE(Encoder);

// The visual trunk's output size for an image, for tests and the benchmark.
int64_t trunk_output_size(int height, int width);

struct ActorCriticOutput {
  torch::Tensor logits, value;  // (B, num_actions), (B)
};

class ActorCriticImpl : public torch::nn::Module {
 public:
  explicit ActorCriticImpl(const NetworkSpec& spec);
  // `history` is (B, K * (num_actions + kPrimitiveStatuses)), from
  // History::rows; undefined without history.
  ActorCriticOutput forward(const ObsTensors& obs, const torch::Tensor& history);
  Encoder encoder{nullptr};

 private:
  torch::nn::Sequential history_net_{nullptr}, combine_{nullptr};
  torch::nn::Linear policy_head_{nullptr}, value_head_{nullptr};
};
TORCH_MODULE(ActorCritic);

// rl-prim-action-hist's memory (chore's own variant of RL-Prim.Hist.): per
// env, its last K primitives (one-hot) and how each ended (one-hot
// PrimitiveStatus), newest first; zeros before an episode's first step. What
// a memoryless policy cannot know is its own recent failures: the image after
// a failed primitive looks as before it, and the paper's RL-Prim. "tends to
// get stuck in a repetitive action loop because the agent is unaware of its
// action history" (appendix G, on the real robot).
class History {
 public:
  History(int steps, int64_t num_actions);
  static int64_t width(int steps, int64_t num_actions);  // K * (A + kPrimitiveStatuses)
  torch::Tensor rows(std::span<const int> env_ids);      // (B, width)
  // Row i: env env_ids[i] took actions[i], and results[i] is the info of the
  // step it ran in (its primitive_status).
  void push(std::span<const int> env_ids, const torch::Tensor& actions, std::span<const Info> results);
  void reset(std::span<const int> env_ids);

 private:
  void ensure(int env_id);
  int steps_;
  int64_t num_actions_;
  torch::Tensor memory_;  // (envs, K, A + kPrimitiveStatuses)
};

// RL-Prim.Hist.'s memory, "the history of observations" (appendix F): per
// env, the encoder's inputs of its last K steps, newest first, as one
// stacked observation (ObsTensors); zeros before an episode's first step,
// as Stable-Baselines3's VecFrameStack pads.
class FrameStack {
 public:
  explicit FrameStack(int frames);
  // Row i: env env_ids[i]'s observation now (one frame) -> the stack it makes
  // with the env's earlier frames; stacked() leaves the memory as it was.
  ObsTensors push(std::span<const int> env_ids, const ObsTensors& newest);
  ObsTensors stacked(std::span<const int> env_ids, const ObsTensors& newest);
  void reset(std::span<const int> env_ids);  // their next push starts an episode

 private:
  int frames_;
  ObsTensors memory_;  // per env its stack, (envs, 3K, H, W) and (envs, K * S)
};

struct SacSample {
  torch::Tensor action, log_prob;  // (B, A) in [-1, 1], (B)
};

class SacActorImpl : public torch::nn::Module {
 public:
  explicit SacActorImpl(const NetworkSpec& spec);
  // Reparameterised sample of tanh(N(mean, std)) with its log-density; the
  // noise comes from `generator` (each trainer owns one, for determinism).
  SacSample sample(const torch::Tensor& feature, at::Generator& generator);
  torch::Tensor deterministic(const torch::Tensor& feature);  // tanh(mean)

 private:
  std::pair<torch::Tensor, torch::Tensor> mean_log_std(const torch::Tensor& feature);
  torch::nn::Sequential mlp_{nullptr};
  torch::nn::Linear mean_{nullptr}, log_std_{nullptr};
};
TORCH_MODULE(SacActor);

class SacCriticImpl : public torch::nn::Module {
 public:
  explicit SacCriticImpl(const NetworkSpec& spec);
  // Both Q values, (B) each, on features from `encoder`.
  std::pair<torch::Tensor, torch::Tensor> q(const torch::Tensor& feature, const torch::Tensor& action);
  Encoder encoder{nullptr};

 private:
  torch::nn::Sequential q1_{nullptr}, q2_{nullptr};
};
TORCH_MODULE(SacCritic);

// How a trained network acts in chore eval/video: greedy (PPO's argmax
// action, SAC's tanh(mean)) or sampled from its distribution as in training.
// Sampling draws from one generator per env row, seeded from `seed` and the
// episode's seed (Info::episode_seed) at its first step, so an episode's draws
// depend only on its own steps (not on the env row, the rows sharing a batch,
// nor the thread count).
struct ActingMode {
  bool sample = false;
  uint64_t seed = 0;
};
// Not thread-safe; they run without gradients.
std::unique_ptr<Policy> make_ppo_policy(ActorCritic net, const NetworkSpec& spec, ActingMode mode = {});
std::unique_ptr<Policy> make_sac_policy(SacCritic critic, SacActor actor, const NetworkSpec& spec,
                                        ActingMode mode = {});

// Every parameter and buffer of `module`, flattened in registration order
// (determinism tests compare these).
std::vector<float> flat_parameters(const torch::nn::Module& module);
// Orthogonal weights with `gain`, zero biases (PPO's initialisation).
void orthogonal_init(torch::nn::Module& module, double gain);

}  // namespace chore
