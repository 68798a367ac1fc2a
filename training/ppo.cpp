// PPO for the primitive baselines (RL-Prim., RL-Prim.Hist.; appendix F.3,
// Table A.12), after CleanRL's ppo.py and the "37 implementation details":
// a vector env collects a rollout of `buffer` transitions with the current
// policy; GAE(gamma, lambda) gives advantages and returns; `epochs` passes of
// shuffled minibatches optimise the clipped surrogate, the value loss and the
// entropy bonus (training/ppo_loss.hpp) with Adam (eps 1e-5) and global gradient clipping, optionally
// stopping an update early on approx-KL (SB3's target_kl). Episode ends
// by truncation bootstrap from the value of the final observation
// (training/gae.hpp). RL-Prim.Hist.'s policy sees its last K observations
// (FrameStack); rl-prim-action-hist's its last K primitives (History).
// Over several ranks (TrainConfig::rank) it is DD-PPO (Wijmans et al. 2020):
// each rank collects its share of the rollout with envs of its own, and the
// ranks average each minibatch's gradients (training/distributed.hpp) before
// the step, so that their parameters stay the same (checked after each update);
// with ppo.sync_fraction, a straggler stops its rollout early (DD-PPO's
// preemption).
#include <chrono>
#include <cmath>
#include <numeric>
#include <optional>

#include "base/error.hpp"
#include "base/memory.hpp"
#include "policies/networks.hpp"
#include "training/checkpoint.hpp"
#include "training/distributed.hpp"
#include "training/gae.hpp"
#include "training/ppo_loss.hpp"
#include "training/torch_support.hpp"
#include "training/trainer.hpp"

namespace chore {
namespace {

using Clock = std::chrono::steady_clock;

// Apart from rank 0's, each rank's seeds (envs, actions, minibatches) start
// this far from the previous rank's: streams that never meet in a run.
constexpr uint64_t kRankStreams = uint64_t{1} << 40;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One rollout: T steps of N envs, flattened to T * N rows at update time.
struct Rollout {
  std::vector<ObsTensors> obs;
  std::vector<torch::Tensor> history, actions, log_probs;
  RolloutSteps steps;  // rewards, values, episode ends
  void clear() { *this = Rollout(); }
};

struct UpdateStats {
  double policy_loss = 0, value_loss = 0, entropy = 0, approx_kl = 0, clip_fraction = 0;
  double update_ms = 0;  // per minibatch update
};

// The image normalised, the state as observed (appendix F.1: "The image input
// is normalized using a per-channel moving average"); a resumed run keeps its
// checkpoint's choice.
NetworkSpec ppo_network_spec(const VectorEnv& env, const TrainConfig& config, const CheckpointFile* resume) {
  NetworkSpec spec =
      network_spec(env.single_observation_space(), env.single_action_space(), config.ppo.frames, config.ppo.history);
  spec.normalize_state = resume ? read_checkpoint_meta(*resume).network.normalize_state : false;
  return spec;
}

class PpoTrainer : public Trainer {
 public:
  PpoTrainer(const TrainConfig& config, const CheckpointFile* resume)
      : config_(config),
        env_(vector_env_config(config)),
        spec_(ppo_network_spec(env_, config, resume)),
        stats_(config.num_envs) {
    const PpoConfig& p = config_.ppo;
    if (env_.single_action_space().kind != Space::Kind::discrete) {
      throw Error("ppo: needs the primitive (Discrete) action space, got " + env_.single_action_space().to_string());
    }
    if (p.buffer < 1 || p.batch < 1 || p.epochs < 1) throw Error("ppo: buffer, batch and epochs must be positive");
    const int ranks = config_.rank.world_size;
    if (p.buffer % ranks != 0 || p.batch % ranks != 0) {
      throw Error("ppo: over " + std::to_string(ranks) + " ranks, ppo.buffer (" + std::to_string(p.buffer) +
                  ") and ppo.batch (" + std::to_string(p.batch) +
                  ") must be multiples of it: each rank collects and learns from its share");
    }
    if (p.frames < 1 || p.frames > 64) throw Error("ppo: frames must be 1..64, got " + std::to_string(p.frames));
    if (p.history < 0 || p.history > 64) throw Error("ppo: history must be 0..64, got " + std::to_string(p.history));
    check_fits_in_memory(p.buffer * spec_.observation_bytes(),
                         "ppo.buffer = " + std::to_string(p.buffer) + ": a rollout of its observations");
    if (!(p.target_kl >= 0))
      throw Error("ppo: target_kl must be 0 (off) or positive, got " + std::to_string(p.target_kl));
    generator_ = seed_torch(config_.seed, config_.threads);
    net_ = ActorCritic(spec_);  // drawn from the seed alone: the same on every rank
    optimizer_.emplace(net_->parameters(), torch::optim::AdamOptions(p.lr).eps(1e-5));
    if (spec_.history > 0) history_.emplace(spec_.history, spec_.num_actions);
    if (spec_.frames > 1) frames_.emplace(spec_.frames);
    env_ids_.resize(config_.num_envs);
    std::iota(env_ids_.begin(), env_ids_.end(), 0);
    steps_per_rollout_ = (p.buffer / ranks + config_.num_envs - 1) / config_.num_envs;
    // DD-PPO: a straggler collects at least a quarter of its share, and a
    // row for each minibatch.
    const int64_t full_rows = int64_t{steps_per_rollout_} * config_.num_envs, batch = p.batch / ranks;
    minibatches_ = (full_rows + batch - 1) / batch;
    least_steps_ =
        std::max<int64_t>((steps_per_rollout_ + 3) / 4, (minibatches_ + config_.num_envs - 1) / config_.num_envs);
    if (resume) load(*resume);
    // Another rank's envs, actions and minibatches follow streams of its own
    // (rank 0's are the single-process run's).
    const uint64_t stream = config_.seed + static_cast<uint64_t>(config_.rank.rank) * kRankStreams;
    if (config_.rank.rank > 0) generator_ = at::detail::createCPUGenerator(stream + static_cast<uint64_t>(steps_));
    // A resumed run restarts its envs; seed + steps keeps it reproducible.
    obs_ = observe(*env_.reset(stream + static_cast<uint64_t>(steps_)).obs);
    if (!resume) net_->encoder->update_normalizers(obs_);
    if (ranks > 1) {
      ranks_.emplace(config_.rank);
      ranks_->broadcast(state());  // rank 0's parameters and normalisers everywhere
    }
  }

  void train(int64_t until, const Report& report) override {
    while (steps_ < until) {
      const auto start = Clock::now();
      const int64_t before = steps_;
      collect();
      const double collect_s = seconds_since(start);
      const UpdateStats u = update();
      const double period_s = seconds_since(start);
      wall_s_ += period_s;
      MetricsRow row = stats_.row(steps_, wall_s_);
      const double steps = static_cast<double>(steps_ - before);
      row.extras = {steps / period_s, steps / collect_s, u.update_ms, u.policy_loss,
                    u.value_loss,     u.entropy,         u.approx_kl, u.clip_fraction};
      report(row);
    }
  }

  std::vector<std::string> extra_metric_names() const override {
    return {"steps_per_s", "env_steps_per_s", "update_ms", "policy_loss",
            "value_loss",  "entropy",         "approx_kl", "clip_fraction"};
  }

  int64_t env_steps() const override { return steps_; }
  const TrainConfig& config() const override { return config_; }
  std::vector<float> parameters() const override { return flat_parameters(*net_); }

  void save(const std::string& path) const override {
    TensorRecords tensors;
    save_module(tensors, "net", *net_);
    save_adam(tensors, "optimizer", *optimizer_);
    save_rng(tensors, generator_);
    write_checkpoint(path, {run_meta(config_, to_json(spec_), {steps_, wall_s_}, stats_), std::move(tensors), path});
  }

 private:
  void load(const CheckpointFile& file) {
    load_module(*net_, file, "net");
    load_adam(*optimizer_, file, "optimizer");
    load_rng(generator_, file);
    const RunProgress progress = load_run_meta(file.meta, stats_);
    steps_ = progress.steps;
    wall_s_ = progress.wall_s;
  }

  // The info of the step each row ran: an ended row's infos hold its next
  // episode's start, its final_infos the step.
  static std::vector<Info> step_results(const Batch& batch) {
    std::vector<Info> results(batch.infos.begin(), batch.infos.end());
    for (int i = 0; i < batch.size(); ++i) {
      if (batch.terminated[i] || batch.truncated[i]) results[i] = batch.final_infos[i];
    }
    return results;
  }

  torch::Tensor history_rows(std::span<const int> env_ids) {
    return history_ ? history_->rows(env_ids) : torch::Tensor();
  }

  // The envs' observations as the policy sees them: with frames, stacked
  // onto each env's earlier ones.
  ObsTensors observe(const ArrayDict& obs) {
    ObsTensors now = obs_tensors(obs, spec_);
    return frames_ ? frames_->push(env_ids_, now) : now;
  }

  // Runs the policy for steps_per_rollout_ vector steps, filling rollout_;
  // with DD-PPO's preemption, until enough ranks have collected their whole
  // share (counted in the ranks' store under a key the ranks share: the
  // run's steps so far).
  void collect() {
    torch::NoGradGuard no_grad;
    rollout_.clear();
    const int n = config_.num_envs, ranks = config_.rank.world_size;
    const bool preempting = ranks_ && config_.ppo.sync_fraction > 0;
    const std::string collected = "collected@" + std::to_string(steps_);
    const auto enough = static_cast<int64_t>(std::ceil(config_.ppo.sync_fraction * ranks));
    std::vector<float> action_values(n);
    int t = 0;
    for (; t < steps_per_rollout_; ++t) {
      if (preempting && t >= least_steps_ && ranks_->add(collected, 0) >= enough) break;
      const torch::Tensor history = history_rows(env_ids_);
      const ActorCriticOutput out = net_->forward(obs_, history);
      const torch::Tensor log_probs = torch::log_softmax(out.logits, 1);
      const torch::Tensor actions = torch::multinomial(log_probs.exp(), 1, false, generator_).squeeze(1);
      rollout_.obs.push_back(obs_);
      rollout_.history.push_back(history);
      rollout_.actions.push_back(actions);
      rollout_.log_probs.push_back(log_probs.gather(1, actions.unsqueeze(1)).squeeze(1));
      rollout_.steps.values.push_back(out.value);

      for (int i = 0; i < n; ++i) action_values[i] = static_cast<float>(actions[i].item<int64_t>());
      const Batch batch = env_.step(action_values);
      // Rows are in env order; an ended row's memories are cleared below,
      // after its bootstrap value has seen them.
      if (history_) history_->push(batch.env_ids, actions, step_results(batch));
      torch::Tensor terminated = torch::zeros({n}), truncated = torch::zeros({n}), final_values = torch::zeros({n});
      std::vector<int> ended;
      std::optional<ObsTensors> final_obs;
      for (int i = 0; i < n; ++i) {
        if (!batch.terminated[i] && !batch.truncated[i]) continue;
        ended.push_back(batch.env_ids[i]);
        if (batch.terminated[i]) {
          terminated[i] = 1.0f;
          continue;
        }
        // Cut off by the time limit, not ended by the task: bootstrapped.
        truncated[i] = 1.0f;
        if (!final_obs) final_obs = obs_tensors(*batch.final_obs, spec_);
        const int id[] = {batch.env_ids[i]};
        ObsTensors last = final_obs->index(torch::tensor({static_cast<int64_t>(i)}));
        if (frames_) last = frames_->stacked(id, last);
        final_values[i] = net_->forward(last, history_rows(id)).value[0];
      }
      rollout_.steps.rewards.push_back(torch::from_blob(const_cast<float*>(batch.rewards.data()), {n}).clone());
      rollout_.steps.terminated.push_back(terminated);
      rollout_.steps.truncated.push_back(truncated);
      rollout_.steps.final_values.push_back(final_values);
      stats_.record(batch);
      if (history_) history_->reset(ended);
      if (frames_) frames_->reset(ended);
      obs_ = observe(*batch.obs);
    }
    if (!preempting) {
      steps_ += int64_t{t} * n * ranks;  // the run's steps: every rank steps alike
      return;
    }
    if (t == steps_per_rollout_) ranks_->add(collected, 1);
    const torch::Tensor steps = torch::tensor({static_cast<double>(t)}, torch::kFloat64);
    ranks_->mean({steps});
    steps_ += std::llround(steps.item<double>() * ranks) * n;
  }

  // GAE over the rollout, then minibatch epochs; the normalisers then take in
  // the rollout's observations (constant while one rollout is acted and learned).
  UpdateStats update() {
    const PpoConfig& p = config_.ppo;
    const torch::Tensor next_value = [&] {
      torch::NoGradGuard no_grad;
      return net_->forward(obs_, history_rows(env_ids_)).value;
    }();
    const Advantages estimate = estimate_advantages(rollout_.steps, next_value, p.gamma, p.gae_lambda);
    // Flatten (T, N) to rows.
    const torch::Tensor rgb = spec_.has_rgb() ? cat_field(&ObsTensors::rgb) : torch::Tensor();
    const ObsTensors obs{rgb, cat_field(&ObsTensors::state)};
    const torch::Tensor history = history_ ? torch::cat(rollout_.history) : torch::Tensor();
    const torch::Tensor actions = torch::cat(rollout_.actions);
    const torch::Tensor old_log_probs = torch::cat(rollout_.log_probs);
    const torch::Tensor advantages = estimate.advantages.reshape({-1});
    const torch::Tensor returns = estimate.returns.reshape({-1});
    const int64_t rows = actions.size(0);

    UpdateStats s;
    int updates = 0;
    bool stopped_early = false;  // by target_kl
    const auto start = Clock::now();
    const int64_t batch = p.batch / config_.rank.world_size;  // this rank's share of a minibatch
    const bool whole = rows == int64_t{steps_per_rollout_} * config_.num_envs;
    for (int epoch = 0; epoch < p.epochs && !stopped_early; ++epoch) {
      const torch::Tensor order = torch::randperm(rows, generator_, torch::kInt64);
      for (int64_t k = 0; k < minibatches_; ++k) {
        // A preempted rollout is cut into as many minibatches as a whole
        // one: every rank steps, and all-reduces, as often.
        const int64_t begin = whole ? k * batch : k * rows / minibatches_;
        const int64_t end = whole ? std::min(begin + batch, rows) : (k + 1) * rows / minibatches_;
        const torch::Tensor idx = order.narrow(0, begin, end - begin);
        const ActorCriticOutput out = net_->forward(obs.index(idx), history_ ? history.index_select(0, idx) : history);
        const PpoLoss l =
            ppo_loss(out.logits, out.value, actions.index_select(0, idx), old_log_probs.index_select(0, idx),
                     advantages.index_select(0, idx), returns.index_select(0, idx), p.clip, p.value_coef,
                     p.entropy_coef, p.normalize_advantage);
        // As SB3: the policy has moved far enough from the rollout's; this
        // minibatch and the rest of the update are skipped (over ranks, by
        // their mean, so that all stop together).
        const double approx_kl = ranks_ ? mean_over_ranks(l.approx_kl) : l.approx_kl;
        if (p.target_kl > 0 && approx_kl > 1.5 * p.target_kl) {
          stopped_early = true;
          break;
        }
        optimizer_->zero_grad();
        l.total.backward();
        if (ranks_) ranks_->mean(gradients());
        torch::nn::utils::clip_grad_norm_(net_->parameters(), p.max_grad_norm);
        optimizer_->step();

        torch::NoGradGuard no_grad;
        s.policy_loss += l.policy.item<double>();
        s.value_loss += l.value.item<double>();
        s.entropy += l.entropy.item<double>();
        s.approx_kl += l.approx_kl;
        s.clip_fraction += l.clip_fraction;
        ++updates;
      }
    }
    // Means over the minibatches stepped (none when target_kl stopped the first).
    const double stepped = std::max(updates, 1);
    s.update_ms = 1000 * seconds_since(start) / stepped;
    for (double* v : {&s.policy_loss, &s.value_loss, &s.entropy, &s.approx_kl, &s.clip_fraction}) *v /= stepped;
    net_->encoder->update_normalizers(obs);
    if (ranks_) {
      // Each rank's normalisers took in its own rollout: their mean everywhere.
      ranks_->mean(net_->buffers());
      if (!ranks_->same(state()))
        throw Error("ppo: rank " + std::to_string(config_.rank.rank) +
                    "'s parameters differ from another rank's after an update");
    }
    return s;
  }

  // Parameters and buffers (the normalisers' statistics).
  std::vector<torch::Tensor> state() const {
    std::vector<torch::Tensor> out = net_->parameters();
    for (const torch::Tensor& b : net_->buffers()) out.push_back(b);
    return out;
  }

  // Every parameter's gradient (zeros where the loss did not reach it).
  std::vector<torch::Tensor> gradients() const {
    std::vector<torch::Tensor> out;
    for (torch::Tensor& w : net_->parameters()) {
      if (!w.grad().defined()) w.mutable_grad() = torch::zeros_like(w);
      out.push_back(w.grad());
    }
    return out;
  }

  double mean_over_ranks(double value) {
    const torch::Tensor t = torch::tensor({value}, torch::kFloat64);
    ranks_->mean({t});
    return t.item<double>();
  }

  torch::Tensor cat_field(torch::Tensor ObsTensors::*field) const {
    std::vector<torch::Tensor> parts;
    for (const ObsTensors& o : rollout_.obs) parts.push_back(o.*field);
    return torch::cat(parts);
  }

  TrainConfig config_;
  VectorEnv env_;
  NetworkSpec spec_;
  ActorCritic net_{nullptr};
  std::optional<torch::optim::Adam> optimizer_;
  std::optional<History> history_;
  std::optional<FrameStack> frames_;
  std::vector<int> env_ids_;  // 0..num_envs - 1: a step's rows are in env order
  EpisodeStats stats_;
  Rollout rollout_;
  ObsTensors obs_;  // the envs' current observations
  int steps_per_rollout_ = 0;
  int64_t minibatches_ = 0, least_steps_ = 0;  // per epoch; the fewest vector steps a preempted rollout has
  at::Generator generator_;
  std::optional<Ranks> ranks_;  // over several ranks
  int64_t steps_ = 0;           // the run's, over all ranks
  double wall_s_ = 0;
};

std::unique_ptr<Policy> load_ppo_policy(const CheckpointFile& file, bool sample) {
  const NetworkSpec spec = read_checkpoint_meta(file).network;
  ActorCritic net(spec);
  load_module(*net, file, "net");
  return make_ppo_policy(net, spec, {.sample = sample});
}

}  // namespace

Algorithm ppo_algorithm() {
  return {"ppo",
          [](const TrainConfig& config, const CheckpointFile* resume) -> std::unique_ptr<Trainer> {
            return std::make_unique<PpoTrainer>(config, resume);
          },
          load_ppo_policy};
}

}  // namespace chore
