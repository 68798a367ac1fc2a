#include "policies/networks.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/error.hpp"

namespace chore {
namespace nn = torch::nn;

namespace {

constexpr int kStateEncoding = 32;  // the state encoder's width

// Max pooling over 2x2 windows, stride 2 (nn::MaxPool2d(2)), as torch 1.13's
// CPU kernel computes it: each window's first maximum in row order wins (a
// NaN always), and the backward pass routes the gradient there alone. That
// kernel branches on every comparison and took a third of an encoder pass at
// batch 64 (~5.7 of ~16.5 ms); these loops compile branch-free and vectorised.

// One row of outputs from two input rows; `argmax` (the window position 0-3)
// when kArgmax.
template <bool kArgmax>
void max_pool_row(const float* __restrict top, const float* __restrict bottom, float* __restrict out,
                  uint8_t* __restrict argmax, int64_t width) {
  for (int64_t j = 0; j < width; ++j) {
    const float a = top[2 * j], b = top[2 * j + 1], c = bottom[2 * j], d = bottom[2 * j + 1];
    float best = a;
    int at = 0;
    bool take = b > best || b != b;
    best = take ? b : best, at = take ? 1 : at;
    take = c > best || c != c;
    best = take ? c : best, at = take ? 2 : at;
    take = d > best || d != d;
    best = take ? d : best, at = take ? 3 : at;
    out[j] = best;
    if constexpr (kArgmax) argmax[j] = static_cast<uint8_t>(at);
  }
}

// (B, C, H, W) float -> (B, C, H/2, W/2); `argmax` (uint8, the window
// position of each output) when not null.
torch::Tensor max_pool_2x2(const torch::Tensor& input, torch::Tensor* argmax) {
  TORCH_CHECK(input.scalar_type() == torch::kFloat32 && input.dim() == 4, "max_pool_2x2: expected float (B, C, H, W)");
  const torch::Tensor x = input.contiguous();
  const int64_t w = x.size(3), oh = x.size(2) / 2, ow = w / 2, rows = x.size(0) * x.size(1) * oh;
  torch::Tensor out = torch::empty({x.size(0), x.size(1), oh, ow});
  if (argmax) *argmax = torch::empty(out.sizes(), torch::kUInt8);
  const float* in = x.data_ptr<float>();
  float* o = out.data_ptr<float>();
  uint8_t* at = argmax ? argmax->data_ptr<uint8_t>() : nullptr;
  for (int64_t r = 0; r < rows; ++r) {
    // Output row r reads input rows 2r and 2r + 1 of its plane (an odd last row is dropped).
    const float* top = in + (r / oh * x.size(2) + 2 * (r % oh)) * w;
    if (at) {
      max_pool_row<true>(top, top + w, o + r * ow, at + r * ow, ow);
    } else {
      max_pool_row<false>(top, top + w, o + r * ow, nullptr, ow);
    }
  }
  return out;
}

// RunningNorm::forward's operations on one byte at a time: (x - mean) / std,
// clamped to +-clip, for `planes` planes of `plane` bytes whose channel is
// plane % channels. IEEE subtraction, division, min and max give the same bits
// at any vector width, so each CPU gets its widest loop: an SAC update's three
// batch-64 passes cost ~4 ms less than with a table of each channel's 256
// values looked up per byte (docs/benchmarks.md, One SAC update).
__attribute__((target_clones("avx512f", "avx2", "default"))) void normalise_bytes(const uint8_t* __restrict src,
                                                                                  float* __restrict dst,
                                                                                  const float* mean, const float* std,
                                                                                  float clip, int64_t channels,
                                                                                  int64_t planes, int64_t plane) {
  for (int64_t p = 0; p < planes; ++p, src += plane, dst += plane) {
    const float m = mean[p % channels], s = std[p % channels];
    for (int64_t i = 0; i < plane; ++i) dst[i] = std::min(std::max((static_cast<float>(src[i]) - m) / s, -clip), clip);
  }
}

// The gradient of max_pool_2x2: zero but at each window's maximum, where
// the output's gradient is added to the zero (as torch does: -0 lands as +0).
struct MaxPool2x2Function : public torch::autograd::Function<MaxPool2x2Function> {
  static torch::Tensor forward(torch::autograd::AutogradContext* ctx, const torch::Tensor& input) {
    torch::Tensor argmax;
    torch::Tensor out = max_pool_2x2(input, &argmax);
    ctx->save_for_backward({argmax});
    ctx->saved_data["sizes"] = input.sizes();
    return out;
  }

  static torch::autograd::variable_list backward(torch::autograd::AutogradContext* ctx,
                                                 torch::autograd::variable_list grads) {
    const torch::Tensor argmax = ctx->get_saved_variables()[0];
    const torch::Tensor grad = grads[0].contiguous();
    const std::vector<int64_t> sizes = ctx->saved_data["sizes"].toIntVector();
    torch::Tensor input_grad = torch::zeros(sizes, grad.options());
    const int64_t h = sizes[2], w = sizes[3], oh = h / 2, ow = w / 2, rows = sizes[0] * sizes[1] * oh;
    const float* g = grad.data_ptr<float>();
    const uint8_t* at = argmax.data_ptr<uint8_t>();
    float* out = input_grad.data_ptr<float>();
    for (int64_t r = 0; r < rows; ++r, g += ow, at += ow) {
      float* top = out + (r / oh * h + 2 * (r % oh)) * w;
      for (int64_t j = 0; j < ow; ++j) top[(at[j] >> 1) * w + 2 * j + (at[j] & 1)] += g[j];
    }
    return {input_grad};
  }
};

// Conv-ReLU-MaxPool blocks (Figure A.11). The first convolution is
// Nature-CNN's 8x8 stride 4 and each block halves again by pooling:
// 128 -> 32 -> 16 -> 8 -> 4 with 16/32/32 channels, ~5 M multiply-adds per
// image, so a batch-64 update stays under 100 ms on this 2-core CPU
// (docs/training.md has the measurements).
nn::Sequential make_trunk(int64_t channels) {
  return nn::Sequential(nn::Conv2d(nn::Conv2dOptions(channels, 16, 8).stride(4).padding(2)), nn::ReLU(), MaxPool2x2(),
                        nn::Conv2d(nn::Conv2dOptions(16, 32, 3).padding(1)), nn::ReLU(), MaxPool2x2(),
                        nn::Conv2d(nn::Conv2dOptions(32, 32, 3).padding(1)), nn::ReLU(), MaxPool2x2(), nn::Flatten());
}

nn::Sequential mlp(int64_t in, int64_t hidden, int64_t out) {
  return nn::Sequential(nn::Linear(in, hidden), nn::ReLU(), nn::Linear(hidden, hidden), nn::ReLU(),
                        nn::Linear(hidden, out));
}

}  // namespace

ObsTensors ObsTensors::index(const torch::Tensor& rows) const {
  return {rgb.defined() ? rgb.index_select(0, rows) : rgb, state.index_select(0, rows)};
}

ObsTensors obs_tensors(const ArrayDict& obs, const NetworkSpec& spec) {
  const int64_t batch = obs.batch();
  ObsTensors t;
  if (spec.has_rgb()) {
    const Array& rgb = obs["rgb"];
    t.rgb = torch::from_blob(const_cast<unsigned char*>(rgb.bytes.data()), {batch, spec.height, spec.width, 3},
                             torch::kUInt8)
                .permute({0, 3, 1, 2})
                .contiguous();
  }
  t.state = torch::zeros({batch, spec.state_size});
  int64_t column = 0;
  for (const char* name : {"is_grasping", "proprio"}) {
    if (!obs.contains(name)) continue;
    const Array& a = obs[name];
    const int64_t width = static_cast<int64_t>(a.item_bytes() / sizeof(float));
    t.state.narrow(1, column, width)
        .copy_(torch::from_blob(const_cast<float*>(a.data<float>()), {batch, width}, torch::kFloat32));
    column += width;
  }
  if (column != spec.state_size) {
    throw Error("observations hold " + std::to_string(column) + " state values, the network expects " +
                std::to_string(spec.state_size));
  }
  return t;
}

RunningNormImpl::RunningNormImpl(int64_t dims, double clip) : clip_(clip) {
  mean_ = register_buffer("mean", torch::zeros({dims}, torch::kFloat64));
  var_ = register_buffer("var", torch::ones({dims}, torch::kFloat64));
  count_ = register_buffer("count", torch::zeros({1}, torch::kFloat64));
}

void RunningNormImpl::update(const torch::Tensor& samples) {
  torch::NoGradGuard no_grad;
  const torch::Tensor x = samples.to(torch::kFloat64);
  const double n = static_cast<double>(x.size(0)), count = count_.item<double>();
  const torch::Tensor batch_mean = x.mean(0), batch_var = x.var(0, /*unbiased=*/false);
  const torch::Tensor delta = batch_mean - mean_;
  const double total = count + n;
  mean_.add_(delta * (n / total));
  var_.copy_((var_ * count + batch_var * n + delta * delta * (count * n / total)) / total);
  count_.fill_(total);
}

torch::Tensor RunningNormImpl::forward(const torch::Tensor& x, int64_t dim) const {
  std::vector<int64_t> shape(x.dim(), 1);
  shape[dim] = -1;
  const torch::Tensor mean = mean_.to(torch::kFloat32).view(shape);
  const torch::Tensor std = (var_.to(torch::kFloat32) + 1e-8f).sqrt().view(shape);
  return ((x - mean) / std).clamp(-clip_, clip_);
}

torch::Tensor RunningNormImpl::forward_bytes(const torch::Tensor& images) const {
  const int64_t channels = mean_.size(0);
  TORCH_CHECK(images.scalar_type() == torch::kUInt8 && images.dim() == 4 && images.size(1) == channels,
              "forward_bytes: expected uint8 images (B, ", channels, ", H, W)");
  const torch::Tensor mean = mean_.to(torch::kFloat32).contiguous();
  const torch::Tensor std = (var_.to(torch::kFloat32) + 1e-8f).sqrt().contiguous();
  const torch::Tensor in = images.contiguous();
  torch::Tensor out = torch::empty(in.sizes(), torch::kFloat32);
  normalise_bytes(in.data_ptr<uint8_t>(), out.data_ptr<float>(), mean.data_ptr<float>(), std.data_ptr<float>(),
                  static_cast<float>(clip_), channels, in.size(0) * channels, in.size(2) * in.size(3));
  return out;
}

torch::Tensor MaxPool2x2Impl::forward(const torch::Tensor& x) {
  if (torch::GradMode::is_enabled() && x.requires_grad()) return MaxPool2x2Function::apply(x);
  return max_pool_2x2(x, nullptr);
}

int64_t trunk_output_size(int height, int width) {
  torch::NoGradGuard no_grad;
  return make_trunk(3)->forward(torch::zeros({1, 3, height, width})).size(1);
}

EncoderImpl::EncoderImpl(const NetworkSpec& spec) : frames_(spec.frames) {
  int64_t width = 0;
  if (spec.has_rgb()) {
    trunk_ = register_module("trunk", make_trunk(3 * frames_));
    rgb_norm_ = register_module("rgb_norm", RunningNorm(3, 5.0));
    width += trunk_output_size(spec.height, spec.width);
  }
  if (spec.state_size > 0) {
    state_net_ = register_module("state_net",
                                 nn::Sequential(nn::Linear(frames_ * spec.state_size, kStateEncoding), nn::ReLU()));
    if (spec.normalize_state) state_norm_ = register_module("state_norm", RunningNorm(spec.state_size, 5.0));
    width += kStateEncoding;
  }
  if (width == 0) throw Error("network: the observation has neither rgb nor a state field");
  mlp_ = register_module("mlp", nn::Sequential(nn::Linear(width, spec.feature_size), nn::ReLU()));
}

// Each frame is normalised by the same statistics: those of one observation.
torch::Tensor EncoderImpl::forward(const ObsTensors& obs) {
  std::vector<torch::Tensor> parts;
  if (trunk_) {
    const int64_t b = obs.rgb.size(0), h = obs.rgb.size(2), w = obs.rgb.size(3);
    const torch::Tensor frames = rgb_norm_->forward_bytes(obs.rgb.reshape({b * frames_, 3, h, w}));
    parts.push_back(trunk_->forward(frames.reshape({b, 3 * frames_, h, w})));
  }
  if (state_net_) {
    const int64_t b = obs.state.size(0);
    const torch::Tensor state = obs.state.reshape({b * frames_, -1});
    const torch::Tensor frames = state_norm_ ? state_norm_->forward(state, 1) : state;
    parts.push_back(state_net_->forward(frames.reshape({b, -1})));
  }
  return mlp_->forward(torch::cat(parts, 1));
}

// From the newest frame alone: the statistics of one observation, whatever
// the stack (its older frames are the same observations again, or zeros).
void EncoderImpl::update_normalizers(const ObsTensors& obs) {
  if (trunk_) rgb_norm_->update(obs.rgb.narrow(1, 0, 3).permute({0, 2, 3, 1}).reshape({-1, 3}));
  if (state_norm_) state_norm_->update(obs.state.narrow(1, 0, obs.state.size(1) / frames_));
}

ActorCriticImpl::ActorCriticImpl(const NetworkSpec& spec) {
  encoder = register_module("encoder", Encoder(spec));
  if (spec.history > 0) {
    history_net_ = register_module(
        "history_net",
        nn::Sequential(nn::Linear(History::width(spec.history, spec.num_actions), spec.feature_size), nn::ReLU()));
    combine_ =
        register_module("combine", nn::Sequential(nn::Linear(2 * spec.feature_size, spec.feature_size), nn::ReLU()));
  }
  policy_head_ = register_module("policy_head", nn::Linear(spec.feature_size, spec.num_actions));
  value_head_ = register_module("value_head", nn::Linear(spec.feature_size, 1));
  // The 37 PPO details: orthogonal weights, gain sqrt(2) in the body, 0.01 for
  // the policy head (near-uniform first policy), 1 for the value head.
  orthogonal_init(*this, std::sqrt(2.0));
  orthogonal_init(*policy_head_, 0.01);
  orthogonal_init(*value_head_, 1.0);
}

ActorCriticOutput ActorCriticImpl::forward(const ObsTensors& obs, const torch::Tensor& history) {
  const torch::Tensor feature = encoder->forward(obs);
  torch::Tensor x = feature;
  if (history_net_) x = combine_->forward(torch::cat({feature, history_net_->forward(history)}, 1));
  return {policy_head_->forward(x), value_head_->forward(x).squeeze(1)};
}

History::History(int steps, int64_t num_actions)
    : steps_(steps), num_actions_(num_actions), memory_(torch::zeros({0, steps, num_actions + kPrimitiveStatuses})) {}

int64_t History::width(int steps, int64_t num_actions) {
  return steps * (num_actions + kPrimitiveStatuses);
}

void History::ensure(int env_id) {
  if (env_id < memory_.size(0)) return;
  memory_ = torch::cat({memory_, torch::zeros({env_id + 1 - memory_.size(0), steps_, memory_.size(2)})});
}

torch::Tensor History::rows(std::span<const int> env_ids) {
  for (int id : env_ids) ensure(id);
  const torch::Tensor ids = torch::tensor(std::vector<int64_t>(env_ids.begin(), env_ids.end()));
  return memory_.index_select(0, ids).reshape({ids.size(0), -1});
}

void History::push(std::span<const int> env_ids, const torch::Tensor& actions, std::span<const Info> results) {
  const auto action = actions.to(torch::kInt64).contiguous();
  for (size_t i = 0; i < env_ids.size(); ++i) {
    ensure(env_ids[i]);
    torch::Tensor m = memory_[env_ids[i]];
    if (steps_ > 1) m.narrow(0, 1, steps_ - 1).copy_(m.narrow(0, 0, steps_ - 1).clone());
    m[0].zero_();
    m[0][action[static_cast<int64_t>(i)].item<int64_t>()] = 1.0f;
    const int status = results[i].primitive_status;
    if (status >= 0) m[0][num_actions_ + status] = 1.0f;
  }
}

void History::reset(std::span<const int> env_ids) {
  for (int id : env_ids) {
    ensure(id);
    memory_[id].zero_();
  }
}

FrameStack::FrameStack(int frames) : frames_(frames) {}

ObsTensors FrameStack::stacked(std::span<const int> env_ids, const ObsTensors& newest) {
  if (!memory_.state.defined()) {  // the sizes come with the first observation
    const auto zeros = [&](const torch::Tensor& t) {
      if (!t.defined()) return t;
      std::vector<int64_t> shape = t.sizes().vec();
      shape[0] = 0;
      shape[1] *= frames_;
      return torch::zeros(shape, t.options());
    };
    memory_ = {zeros(newest.rgb), zeros(newest.state)};
  }
  for (int id : env_ids) {
    if (id < memory_.state.size(0)) continue;
    const auto grow = [&](const torch::Tensor& t) {
      if (!t.defined()) return t;
      std::vector<int64_t> shape = t.sizes().vec();
      shape[0] = id + 1 - t.size(0);
      return torch::cat({t, torch::zeros(shape, t.options())});
    };
    memory_ = {grow(memory_.rgb), grow(memory_.state)};
  }
  const torch::Tensor ids = torch::tensor(std::vector<int64_t>(env_ids.begin(), env_ids.end()));
  // Newest first: the new frame, then all but the oldest of the stack.
  const auto shift = [&](const torch::Tensor& stack, const torch::Tensor& frame) {
    if (!stack.defined()) return stack;
    const int64_t width = frame.size(1);
    return torch::cat({frame, stack.index_select(0, ids).narrow(1, 0, (frames_ - 1) * width)}, 1);
  };
  return {shift(memory_.rgb, newest.rgb), shift(memory_.state, newest.state)};
}

ObsTensors FrameStack::push(std::span<const int> env_ids, const ObsTensors& newest) {
  ObsTensors s = stacked(env_ids, newest);
  const torch::Tensor ids = torch::tensor(std::vector<int64_t>(env_ids.begin(), env_ids.end()));
  if (s.rgb.defined()) memory_.rgb.index_copy_(0, ids, s.rgb);
  memory_.state.index_copy_(0, ids, s.state);
  return s;
}

void FrameStack::reset(std::span<const int> env_ids) {
  for (int id : env_ids) {
    if (!memory_.state.defined() || id >= memory_.state.size(0)) continue;  // zeros when first used
    if (memory_.rgb.defined()) memory_.rgb[id].zero_();
    memory_.state[id].zero_();
  }
}

SacActorImpl::SacActorImpl(const NetworkSpec& spec) {
  mlp_ = register_module("mlp", nn::Sequential(nn::Linear(spec.feature_size, spec.hidden), nn::ReLU(),
                                               nn::Linear(spec.hidden, spec.hidden), nn::ReLU()));
  mean_ = register_module("mean", nn::Linear(spec.hidden, spec.action_size));
  log_std_ = register_module("log_std", nn::Linear(spec.hidden, spec.action_size));
}

std::pair<torch::Tensor, torch::Tensor> SacActorImpl::mean_log_std(const torch::Tensor& feature) {
  const torch::Tensor h = mlp_->forward(feature);
  // log std squashed into [-5, 2] (CleanRL): smooth, unlike a hard clamp.
  constexpr double kMin = -5, kMax = 2;
  const torch::Tensor log_std = kMin + 0.5 * (kMax - kMin) * (torch::tanh(log_std_->forward(h)) + 1);
  return {mean_->forward(h), log_std};
}

SacSample SacActorImpl::sample(const torch::Tensor& feature, at::Generator& generator) {
  const auto [mean, log_std] = mean_log_std(feature);
  const torch::Tensor std = log_std.exp();
  const torch::Tensor noise = torch::randn(mean.sizes(), generator);
  const torch::Tensor pre_tanh = mean + std * noise;
  const torch::Tensor action = torch::tanh(pre_tanh);
  // log N(pre_tanh) minus log |d tanh/dx| = log(1 - tanh^2).
  const torch::Tensor log_normal = -0.5 * noise.pow(2) - log_std - 0.5 * std::log(2 * M_PI);
  const torch::Tensor log_prob = (log_normal - torch::log(1 - action.pow(2) + 1e-6)).sum(1);
  return {action, log_prob};
}

torch::Tensor SacActorImpl::deterministic(const torch::Tensor& feature) {
  return torch::tanh(mean_log_std(feature).first);
}

SacCriticImpl::SacCriticImpl(const NetworkSpec& spec) {
  encoder = register_module("encoder", Encoder(spec));
  q1_ = register_module("q1", mlp(spec.feature_size + spec.action_size, spec.hidden, 1));
  q2_ = register_module("q2", mlp(spec.feature_size + spec.action_size, spec.hidden, 1));
}

std::pair<torch::Tensor, torch::Tensor> SacCriticImpl::q(const torch::Tensor& feature, const torch::Tensor& action) {
  const torch::Tensor x = torch::cat({feature, action}, 1);
  return {q1_->forward(x).squeeze(1), q2_->forward(x).squeeze(1)};
}

namespace {

// One generator per env row for sampled acting (ActingMode), seeded afresh
// at each episode's first step from its episode seed: an episode's draws are
// the same whichever env row or thread plays it.
class RowGenerators {
 public:
  explicit RowGenerators(ActingMode mode) : mode_(mode) {}
  bool sample() const { return mode_.sample; }
  at::Generator& of(int row, const Info& info) {
    if (static_cast<int>(generators_.size()) <= row) generators_.resize(static_cast<size_t>(row) + 1);
    at::Generator& g = generators_[static_cast<size_t>(row)];
    if (!g.defined() || info.elapsed_steps == 0) {
      g = at::detail::createCPUGenerator(mode_.seed ^ (info.episode_seed * 0x9E3779B97F4A7C15ull));
    }
    return g;
  }

 private:
  ActingMode mode_;
  std::vector<at::Generator> generators_;
};

class PpoPolicy : public Policy {
 public:
  PpoPolicy(ActorCritic net, const NetworkSpec& spec, ActingMode mode)
      : net_(std::move(net)),
        spec_(spec),
        history_(std::max(spec.history, 1), spec.num_actions),
        frames_(spec.frames),
        generators_(mode) {
    net_->eval();
  }

  void act(const Batch& batch, std::span<float> actions) override {
    torch::NoGradGuard no_grad;
    ObsTensors obs = obs_tensors(*batch.obs, spec_);
    if (spec_.frames > 1) {
      for (int i = 0; i < batch.size(); ++i) {
        if (batch.infos[i].elapsed_steps == 0) frames_.reset(batch.env_ids.subspan(i, 1));
      }
      obs = frames_.push(batch.env_ids, obs);
    }
    if (spec_.history > 0) remember_results(batch);
    const torch::Tensor history = spec_.history > 0 ? history_.rows(batch.env_ids) : torch::Tensor();
    const ActorCriticOutput out = net_->forward(obs, history);
    torch::Tensor chosen = out.logits.argmax(1);
    if (generators_.sample()) {
      const torch::Tensor probs = torch::softmax(out.logits, 1);
      for (int64_t i = 0; i < probs.size(0); ++i) {
        chosen[i] = torch::multinomial(probs[i], 1, false, generators_.of(batch.env_ids[i], batch.infos[i]))[0];
      }
    }
    for (int64_t i = 0; i < chosen.size(0); ++i) {
      actions[i] = static_cast<float>(chosen[i].item<int64_t>());
      pending(batch.env_ids[i]) = chosen[i].item<int64_t>();
    }
  }

  void reset(std::span<const int> env_ids) override {
    history_.reset(env_ids);
    frames_.reset(env_ids);
    for (int id : env_ids) pending(id) = -1;
  }

 private:
  // An env's action not yet in its history: its result comes with the next
  // batch (the info of the step it ran in); -1 when none.
  int64_t& pending(int env_id) {
    if (static_cast<int>(pending_.size()) <= env_id) pending_.resize(static_cast<size_t>(env_id) + 1, -1);
    return pending_[static_cast<size_t>(env_id)];
  }

  // Each row's info is the result of this env's pending action, or the start
  // of a new episode.
  void remember_results(const Batch& batch) {
    for (int i = 0; i < batch.size(); ++i) {
      const int id[] = {batch.env_ids[i]};
      if (batch.infos[i].elapsed_steps == 0) {
        history_.reset(id);
      } else if (pending(id[0]) >= 0) {
        history_.push(id, torch::tensor({pending(id[0])}), batch.infos.subspan(i, 1));
      }
      pending(id[0]) = -1;
    }
  }

  ActorCritic net_;
  NetworkSpec spec_;
  History history_;
  FrameStack frames_;
  std::vector<int64_t> pending_;
  RowGenerators generators_;
};

class SacPolicy : public Policy {
 public:
  SacPolicy(SacCritic critic, SacActor actor, const NetworkSpec& spec, ActingMode mode)
      : critic_(std::move(critic)), actor_(std::move(actor)), spec_(spec), generators_(mode) {
    critic_->eval();
    actor_->eval();
  }

  void act(const Batch& batch, std::span<float> actions) override {
    torch::NoGradGuard no_grad;
    const torch::Tensor feature = critic_->encoder->forward(obs_tensors(*batch.obs, spec_));
    torch::Tensor a;
    if (generators_.sample()) {
      std::vector<torch::Tensor> rows;
      for (int64_t i = 0; i < feature.size(0); ++i) {
        rows.push_back(
            actor_->sample(feature.narrow(0, i, 1), generators_.of(batch.env_ids[i], batch.infos[i])).action);
      }
      a = torch::cat(rows).contiguous();
    } else {
      a = actor_->deterministic(feature).contiguous();
    }
    std::copy_n(a.data_ptr<float>(), a.numel(), actions.begin());
  }

 private:
  SacCritic critic_;
  SacActor actor_;
  NetworkSpec spec_;
  RowGenerators generators_;
};

}  // namespace

std::unique_ptr<Policy> make_ppo_policy(ActorCritic net, const NetworkSpec& spec, ActingMode mode) {
  return std::make_unique<PpoPolicy>(std::move(net), spec, mode);
}

std::unique_ptr<Policy> make_sac_policy(SacCritic critic, SacActor actor, const NetworkSpec& spec, ActingMode mode) {
  return std::make_unique<SacPolicy>(std::move(critic), std::move(actor), spec, mode);
}

std::vector<float> flat_parameters(const torch::nn::Module& module) {
  std::vector<float> out;
  auto append = [&](const torch::Tensor& t) {
    const torch::Tensor f = t.detach().to(torch::kFloat32).contiguous();
    out.insert(out.end(), f.data_ptr<float>(), f.data_ptr<float>() + f.numel());
  };
  for (const torch::Tensor& p : module.parameters()) append(p);
  for (const torch::Tensor& b : module.buffers()) append(b);
  return out;
}

void orthogonal_init(torch::nn::Module& module, double gain) {
  torch::NoGradGuard no_grad;
  module.apply([gain](torch::nn::Module& m) {
    torch::Tensor weight, bias;
    if (auto* linear = dynamic_cast<nn::LinearImpl*>(&m)) {
      weight = linear->weight, bias = linear->bias;
    } else if (auto* conv = dynamic_cast<nn::Conv2dImpl*>(&m)) {
      weight = conv->weight, bias = conv->bias;
    } else {
      return;
    }
    nn::init::orthogonal_(weight, gain);
    nn::init::zeros_(bias);
  });
}

}  // namespace chore
