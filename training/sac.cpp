// SAC for the visuomotor baseline (RL-VMC; appendix F.3, Table A.11), after
// CleanRL's sac_continuous_action.py with DrQ's shared image encoder:
//
// - The critic owns the encoder; both Q heads read its feature. The actor reads
//   the same feature detached: only the critic loss trains the encoder (the
//   actor's gradient stops at the feature, as in SAC-AE/DrQ).
// - The target critic is a copy of the critic (encoder included), moved towards
//   it by tau after every update; its normaliser statistics are copied.
// - The temperature alpha is learned towards the target entropy -|A|.
// - The replay buffer holds the last `buffer` transitions (Table A.11's
//   "buffer size": 300 by default, a FIFO over all envs); images are kept as uint8.
// - After `learning_starts` uniform random steps, each env step is followed by
//   one gradient update (N per vector step of N envs).
#include <chrono>
#include <optional>

#include "base/error.hpp"
#include "base/memory.hpp"
#include "policies/networks.hpp"
#include "training/checkpoint.hpp"
#include "training/torch_support.hpp"
#include "training/trainer.hpp"

namespace chore {
namespace {

using Clock = std::chrono::steady_clock;

// Transitions in a ring of `capacity` rows.
struct ReplayBuffer {
  ObsTensors obs, next_obs;
  torch::Tensor actions, rewards, terminated;
  int64_t capacity = 0, size = 0, next = 0;

  ReplayBuffer(const NetworkSpec& spec, int64_t capacity) : capacity(capacity) {
    auto make_obs = [&] {
      return ObsTensors{
          spec.has_rgb() ? torch::zeros({capacity, 3, spec.height, spec.width}, torch::kUInt8) : torch::Tensor(),
          torch::zeros({capacity, spec.state_size})};
    };
    obs = make_obs();
    next_obs = make_obs();
    actions = torch::zeros({capacity, spec.action_size});
    rewards = torch::zeros({capacity});
    terminated = torch::zeros({capacity});
  }

  void add(const ObsTensors& o, const torch::Tensor& a, const torch::Tensor& r, const ObsTensors& o2,
           const torch::Tensor& done) {
    for (int64_t i = 0; i < a.size(0); ++i) {
      if (o.rgb.defined()) {
        obs.rgb[next].copy_(o.rgb[i]);
        next_obs.rgb[next].copy_(o2.rgb[i]);
      }
      obs.state[next].copy_(o.state[i]);
      next_obs.state[next].copy_(o2.state[i]);
      actions[next].copy_(a[i]);
      rewards[next].copy_(r[i]);
      terminated[next].copy_(done[i]);
      next = (next + 1) % capacity;
      size = std::min(size + 1, capacity);
    }
  }

  void save(TensorRecords& tensors) const {
    for (const auto& [name, t] : named())
      if (t.defined()) put_tensor(tensors, "replay." + name, t);
    put_tensor(tensors, "replay.cursor", torch::tensor({size, next}));
  }

  void load(const CheckpointFile& file) {
    for (const auto& [name, t] : named())
      if (t.defined()) t.copy_(get_tensor(file, "replay." + name, t));
    const torch::Tensor cursor = get_tensor(file, "replay.cursor", torch::tensor({size, next}));
    size = cursor[0].item<int64_t>(), next = cursor[1].item<int64_t>();
    if (size < 0 || size > capacity || next < 0 || next >= capacity) {
      throw Error("checkpoint " + file.path + ": replay buffer cursor out of range");
    }
  }

 private:
  std::vector<std::pair<std::string, torch::Tensor>> named() const {
    return {{"obs_rgb", obs.rgb}, {"obs_state", obs.state}, {"next_rgb", next_obs.rgb}, {"next_state", next_obs.state},
            {"actions", actions}, {"rewards", rewards},     {"terminated", terminated}};
  }
};

struct UpdateStats {
  double q_loss = 0, policy_loss = 0, alpha = 0, entropy = 0, mean_q = 0, update_ms = 0;
  int updates = 0;
};

class SacTrainer : public Trainer {
 public:
  SacTrainer(const TrainConfig& config, const CheckpointFile* resume)
      : config_(config),
        env_(vector_env_config(config)),
        spec_(with_hidden(network_spec(env_.single_observation_space(), env_.single_action_space(), 1, 0),
                          config.sac.hidden)),
        stats_(config.num_envs),
        replay_(checked_capacity(spec_, config.sac.buffer)) {
    const SacConfig& s = config_.sac;
    // Data-parallel training is PPO's (DD-PPO averages on-policy gradients);
    // SAC's replay and its one update per step would need a design of their
    // own (a shared replay, or DDP over the critics), not chosen yet.
    if (config_.rank.world_size > 1)
      throw Error("sac: trains on one rank; " + std::to_string(config_.rank.world_size) +
                  " ranks are for PPO's baselines (rl-prim, rl-prim-hist, rl-prim-action-hist)");
    if (env_.single_action_space().kind != Space::Kind::box || spec_.action_size == 0) {
      throw Error("sac: needs the low-level (Box) action space, got " + env_.single_action_space().to_string());
    }
    if (s.buffer < s.batch || s.batch < 1) throw Error("sac: the buffer must hold at least one batch");
    generator_ = seed_torch(config_.seed, config_.threads);
    critic_ = SacCritic(spec_);
    target_ = SacCritic(spec_);
    actor_ = SacActor(spec_);
    copy_into(*target_, *critic_, 1.0);
    log_alpha_ = torch::full({1}, std::log(s.initial_alpha), torch::requires_grad());
    critic_opt_.emplace(critic_->parameters(), torch::optim::AdamOptions(s.lr));
    actor_opt_.emplace(actor_->parameters(), torch::optim::AdamOptions(s.lr));
    alpha_opt_.emplace(std::vector<torch::Tensor>{log_alpha_}, torch::optim::AdamOptions(s.lr));
    if (resume) load(*resume);
    // A resumed run restarts its envs; seed + steps keeps it reproducible.
    obs_ = obs_tensors(*env_.reset(config_.seed + static_cast<uint64_t>(steps_)).obs, spec_);
  }

  void train(int64_t until, const Report& report) override {
    const SacConfig& s = config_.sac;
    UpdateStats u;
    auto period_start = Clock::now();
    int64_t period_steps = 0;
    while (steps_ < until) {
      step();
      period_steps += config_.num_envs;
      if (steps_ >= s.learning_starts) {
        for (int i = 0; i < config_.num_envs; ++i) update(u);
      }
      if (period_steps >= s.report_every || steps_ >= until) {
        const double period_s = std::chrono::duration<double>(Clock::now() - period_start).count();
        wall_s_ += period_s;
        MetricsRow row = stats_.row(steps_, wall_s_);
        const double n = std::max(u.updates, 1);
        row.extras = {period_steps / period_s, u.update_ms / n, u.q_loss / n, u.policy_loss / n, u.alpha / n,
                      u.entropy / n,           u.mean_q / n};
        report(row);
        u = UpdateStats();
        period_start = Clock::now();
        period_steps = 0;
      }
    }
  }

  std::vector<std::string> extra_metric_names() const override {
    return {"steps_per_s", "update_ms", "q_loss", "policy_loss", "alpha", "entropy", "q_value"};
  }

  int64_t env_steps() const override { return steps_; }
  const TrainConfig& config() const override { return config_; }

  std::vector<float> parameters() const override {
    std::vector<float> all = flat_parameters(*critic_);
    for (const auto* m :
         {static_cast<const torch::nn::Module*>(target_.get()), static_cast<const torch::nn::Module*>(actor_.get())}) {
      const std::vector<float> p = flat_parameters(*m);
      all.insert(all.end(), p.begin(), p.end());
    }
    all.push_back(log_alpha_.item<float>());
    return all;
  }

  void save(const std::string& path) const override {
    TensorRecords tensors;
    save_module(tensors, "critic", *critic_);
    save_module(tensors, "critic_target", *target_);
    save_module(tensors, "actor", *actor_);
    save_adam(tensors, "critic_optimizer", *critic_opt_);
    save_adam(tensors, "actor_optimizer", *actor_opt_);
    save_adam(tensors, "alpha_optimizer", *alpha_opt_);
    put_tensor(tensors, "log_alpha", log_alpha_);
    replay_.save(tensors);
    save_rng(tensors, generator_);
    write_checkpoint(path, {run_meta(config_, to_json(spec_), {steps_, wall_s_}, stats_), std::move(tensors), path});
  }

 private:
  // The replay buffer's rows, checked to fit in memory before they are allocated.
  static ReplayBuffer checked_capacity(const NetworkSpec& spec, int buffer) {
    const double bytes = buffer * (2 * spec.observation_bytes() + 4.0 * (spec.action_size + 2));
    check_fits_in_memory(bytes, "sac.buffer = " + std::to_string(buffer) + ": its replay buffer");
    return ReplayBuffer(spec, std::max(buffer, 1));
  }

  static NetworkSpec with_hidden(NetworkSpec spec, int hidden) {
    spec.hidden = hidden;
    return spec;
  }

  void load(const CheckpointFile& file) {
    load_module(*critic_, file, "critic");
    load_module(*target_, file, "critic_target");
    load_module(*actor_, file, "actor");
    load_adam(*critic_opt_, file, "critic_optimizer");
    load_adam(*actor_opt_, file, "actor_optimizer");
    load_adam(*alpha_opt_, file, "alpha_optimizer");
    {
      torch::NoGradGuard no_grad;
      log_alpha_.copy_(get_tensor(file, "log_alpha", log_alpha_));
    }
    replay_.load(file);
    load_rng(generator_, file);
    const RunProgress progress = load_run_meta(file.meta, stats_);
    steps_ = progress.steps;
    wall_s_ = progress.wall_s;
  }

  // One vector step: act, store the transitions, move on.
  void step() {
    torch::NoGradGuard no_grad;
    const int n = config_.num_envs;
    critic_->encoder->update_normalizers(obs_);
    torch::Tensor actions;
    if (steps_ < config_.sac.learning_starts) {
      actions = torch::rand({n, spec_.action_size}, generator_) * 2 - 1;
    } else {
      actions = actor_->sample(critic_->encoder->forward(obs_), generator_).action;
    }
    actions = actions.contiguous();
    const Batch batch = env_.step({actions.data_ptr<float>(), static_cast<size_t>(actions.numel())});
    const ObsTensors next_obs = obs_tensors(*batch.obs, spec_);
    // An ended episode's next observation is its last one, not the reset's.
    ObsTensors stored_next{next_obs.rgb.defined() ? next_obs.rgb.clone() : next_obs.rgb, next_obs.state.clone()};
    torch::Tensor terminated = torch::zeros({n});
    std::optional<ObsTensors> final_obs;
    for (int i = 0; i < n; ++i) {
      if (!batch.terminated[i] && !batch.truncated[i]) continue;
      if (!final_obs) final_obs = obs_tensors(*batch.final_obs, spec_);
      if (stored_next.rgb.defined()) stored_next.rgb[i].copy_(final_obs->rgb[i]);
      stored_next.state[i].copy_(final_obs->state[i]);
      terminated[i] = batch.terminated[i] ? 1.0f : 0.0f;  // truncation bootstraps
    }
    const torch::Tensor rewards = torch::from_blob(const_cast<float*>(batch.rewards.data()), {n}).clone();
    replay_.add(obs_, actions, rewards, stored_next, terminated);
    stats_.record(batch);
    obs_ = next_obs;
    steps_ += n;
  }

  void update(UpdateStats& u) {
    const SacConfig& s = config_.sac;
    const auto start = Clock::now();
    const torch::Tensor idx = torch::randint(replay_.size, {s.batch}, generator_, torch::kInt64);
    const ObsTensors obs = replay_.obs.index(idx), next_obs = replay_.next_obs.index(idx);
    const torch::Tensor actions = replay_.actions.index_select(0, idx);
    const torch::Tensor alpha = log_alpha_.exp().detach();

    // Critic: soft Bellman target from the target critic.
    torch::Tensor target;
    {
      torch::NoGradGuard no_grad;
      const SacSample next = actor_->sample(critic_->encoder->forward(next_obs), generator_);
      const auto [q1, q2] = target_->q(target_->encoder->forward(next_obs), next.action);
      const torch::Tensor soft_value = torch::min(q1, q2) - alpha * next.log_prob;
      target =
          replay_.rewards.index_select(0, idx) + s.gamma * (1 - replay_.terminated.index_select(0, idx)) * soft_value;
    }
    const torch::Tensor feature = critic_->encoder->forward(obs);
    const auto [q1, q2] = critic_->q(feature, actions);
    const torch::Tensor q_loss = (q1 - target).pow(2).mean() + (q2 - target).pow(2).mean();
    critic_opt_->zero_grad();
    q_loss.backward();
    critic_opt_->step();

    // Actor: on the detached feature, through the Q heads to the actor alone
    // (backward's inputs: no gradients for the Q heads' weights are computed).
    const SacSample sample = actor_->sample(feature.detach(), generator_);
    const auto [pq1, pq2] = critic_->q(feature.detach(), sample.action);
    const torch::Tensor policy_loss = (alpha * sample.log_prob - torch::min(pq1, pq2)).mean();
    actor_opt_->zero_grad();
    policy_loss.backward({}, c10::nullopt, false, actor_->parameters());
    actor_opt_->step();

    // Temperature towards the target entropy -|A|.
    const double target_entropy = -static_cast<double>(spec_.action_size);
    const torch::Tensor alpha_loss = -(log_alpha_ * (sample.log_prob.detach() + target_entropy)).mean();
    alpha_opt_->zero_grad();
    alpha_loss.backward();
    alpha_opt_->step();

    copy_into(*target_, *critic_, s.tau);

    u.update_ms += 1000 * std::chrono::duration<double>(Clock::now() - start).count();
    u.q_loss += q_loss.item<double>();
    u.policy_loss += policy_loss.item<double>();
    u.alpha += alpha.item<double>();
    u.entropy += -sample.log_prob.mean().item<double>();
    u.mean_q += q1.mean().item<double>();
    ++u.updates;
  }

  // target = tau * source + (1 - tau) * target for parameters; buffers (the
  // normaliser statistics) are copied.
  static void copy_into(torch::nn::Module& target, const torch::nn::Module& source, double tau) {
    torch::NoGradGuard no_grad;
    const auto from = source.parameters();
    auto to = target.parameters();
    for (size_t i = 0; i < to.size(); ++i) to[i].mul_(1 - tau).add_(from[i], tau);
    const auto from_buffers = source.buffers();
    auto to_buffers = target.buffers();
    for (size_t i = 0; i < to_buffers.size(); ++i) to_buffers[i].copy_(from_buffers[i]);
  }

  TrainConfig config_;
  VectorEnv env_;
  NetworkSpec spec_;
  EpisodeStats stats_;
  ReplayBuffer replay_;
  SacCritic critic_{nullptr}, target_{nullptr};
  SacActor actor_{nullptr};
  torch::Tensor log_alpha_;
  std::optional<torch::optim::Adam> critic_opt_, actor_opt_, alpha_opt_;
  ObsTensors obs_;
  at::Generator generator_;
  int64_t steps_ = 0;
  double wall_s_ = 0;
};

std::unique_ptr<Policy> load_sac_policy(const CheckpointFile& file, bool sample) {
  const NetworkSpec spec = read_checkpoint_meta(file).network;
  SacCritic critic(spec);
  SacActor actor(spec);
  load_module(*critic, file, "critic");
  load_module(*actor, file, "actor");
  return make_sac_policy(critic, actor, spec, {.sample = sample});
}

}  // namespace

Algorithm sac_algorithm() {
  return {"sac",
          [](const TrainConfig& config, const CheckpointFile* resume) -> std::unique_ptr<Trainer> {
            return std::make_unique<SacTrainer>(config, resume);
          },
          load_sac_policy};
}

}  // namespace chore
