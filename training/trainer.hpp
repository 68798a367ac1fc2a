// The baselines' trainers behind one torch-free interface (training/ppo.cpp and
// training/sac.cpp hold the algorithms, each readable top to bottom), and the
// two registries, one line each: the algorithms (algorithms.cpp), and the
// baselines of the paper that they train (baselines.cpp):
//
//   rl-vmc        SAC on the 14-d low-level control, RGB + proprio + is-grasping
//   rl-prim       PPO over the primitive action space, RGB + is-grasping
//   rl-prim-hist  rl-prim whose policy sees its last K observations
//   rl-prim-action-hist  rl-prim whose policy also sees its last K
//                 primitives and how each ended (chore's variant)
//
//   auto trainer = chore::make_trainer(config);
//   trainer->train(30000, [](const chore::MetricsRow& row) { ... });
//   trainer->save("run/checkpoint.pt");
//   auto resumed = chore::resume_trainer("run/checkpoint.pt");
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "env/env.hpp"
#include "env/vector_env.hpp"
#include "policies/policy.hpp"
#include "training/rank.hpp"

namespace chore {

// Table A.12 (RL-Prim., RL-Prim.Hist.); the rest from SB3/CleanRL's defaults.
struct PpoConfig {
  double lr = 3e-4;
  int buffer = 300;  // transitions per rollout, over all envs (rounded up to a multiple of them)
  int batch = 64;    // minibatch
  int epochs = 10;
  double gamma = 0.99, gae_lambda = 0.99, clip = 0.2;
  double entropy_coef = 0.0, value_coef = 0.5, max_grad_norm = 0.5;
  // Memory (baselines.cpp sets it): the observations the policy sees, this
  // step's and frames - 1 before it (RL-Prim.Hist.: K = 4); and the past
  // primitives with how each ended (rl-prim-action-hist: K = 4).
  int frames = 1;
  int history = 0;
  // Advantages scaled to mean 0, std 1 per minibatch (SB3's and CleanRL's default).
  bool normalize_advantage = true;
  // SB3's target_kl: an update stops before a minibatch whose approx-KL from
  // the rollout's policy exceeds 1.5x this; 0: never (SB3's None, the default).
  double target_kl = 0;
  // DD-PPO's preemption of stragglers (Wijmans et al. 2020; over several
  // ranks): a rank stops collecting once this fraction of the ranks has
  // collected its whole share (and it has a quarter of its own), so that
  // the fast ones do not wait for the slowest. 0: off (the default); DD-PPO
  // used 0.6. Which rank stops where depends on timing: a run with it is
  // not reproducible bit for bit.
  double sync_fraction = 0;
};

// Table A.11 (RL-VMC); the rest from SB3/CleanRL's defaults.
struct SacConfig {
  double lr = 3e-4;
  int buffer = 300;  // replay capacity in transitions (Table A.11's "buffer size")
  int batch = 64;
  double gamma = 0.99, tau = 0.005;
  int learning_starts = 100;  // env steps of uniform random actions before learning
  double initial_alpha = 1.0;
  int hidden = 256;        // actor/critic MLP width
  int report_every = 300;  // env steps between metrics rows
};

struct TrainConfig {
  std::string baseline = "rl-prim";  // baselines(): rl-vmc, rl-prim, rl-prim-hist, rl-prim-action-hist
  EnvConfig env;
  int num_envs = 1;
  int threads = 1;  // VectorEnv workers (at most num_envs) and torch's intra-op threads
  uint64_t seed = 0;
  int64_t total_steps = 30000;      // env steps (primitive steps for rl-prim), as in the paper
  int64_t checkpoint_every = 3000;  // env steps between the checkpoints chore train writes
  PpoConfig ppo;
  SacConfig sac;
  // This process's place in a data-parallel run (DD-PPO: training/
  // distributed.hpp; chore train reads it from the launcher's environment).
  // Where the run is, not what it is: not among its settings (to_json).
  // The run's steps, buffer and minibatch are over all ranks: each steps
  // num_envs envs of its own and learns from its share.
  RankInfo rank;
};

// The paper's setup for a baseline on an activity: observations, action space
// and primitive mode as in appendix F. Throws chore::Error for an unknown baseline.
TrainConfig baseline_config(const std::string& baseline, const std::string& activity);

nlohmann::json to_json(const TrainConfig& config);
TrainConfig train_config_from_json(const nlohmann::json& j);  // throws chore::Error
// `config` with one field replaced: KEY is its path in to_json's tree
// (ppo.entropy_coef, sac.lr, env.max_episode_steps), VALUE JSON of the same
// type ("0.01", "false", "\"rgb\""); throws chore::Error naming what is wrong.
TrainConfig with_setting(const TrainConfig& config, const std::string& key_equals_value);
nlohmann::json to_json(const EnvConfig& config);
EnvConfig env_config_from_json(const nlohmann::json& j);  // throws chore::Error

// One row of metrics.csv. The first columns are a contract with scripts/plot:
// env_steps,wall_s,episodes,success_rate,mean_q,mean_return,mean_length (means
// over the last EpisodeStats::kWindow finished episodes), then the trainer's extras.
struct MetricsRow {
  int64_t env_steps = 0;
  double wall_s = 0;
  int64_t episodes = 0;
  double success_rate = 0, mean_q = 0, mean_return = 0, mean_length = 0;
  std::vector<double> extras;  // named by Trainer::extra_metric_names()
};
extern const char* const kMetricsHeader;  // "env_steps,wall_s,...,mean_length"

// Episode returns per env, and rolling statistics over finished episodes.
class EpisodeStats {
 public:
  static constexpr int kWindow = 20;
  explicit EpisodeStats(int num_envs) : returns_(num_envs, 0.0) {}
  // After a VectorEnv step with same_step autoreset.
  void record(const Batch& batch);
  int64_t episodes() const { return episodes_; }
  MetricsRow row(int64_t env_steps, double wall_s) const;
  nlohmann::json to_json() const;
  void load(const nlohmann::json& j);

 private:
  struct Episode {
    double ret, q;
    int64_t length;
    bool success;
  };
  std::vector<double> returns_;
  std::deque<Episode> recent_;
  int64_t episodes_ = 0;
};

// The vector env a trainer steps: same_step autoreset, so an ended episode's
// last observation is in final_obs.
VectorEnvConfig vector_env_config(const TrainConfig& config);

// A run's checkpoint metadata (checkpoint.hpp), and its progress read back.
struct RunProgress {
  int64_t steps = 0;
  double wall_s = 0;
};
nlohmann::json run_meta(const TrainConfig& config, const nlohmann::json& network, const RunProgress& progress,
                        const EpisodeStats& stats);
RunProgress load_run_meta(const nlohmann::json& meta, EpisodeStats& stats);

class Trainer {
 public:
  using Report = std::function<void(const MetricsRow&)>;
  virtual ~Trainer() = default;
  // Trains until env_steps() >= until (PPO: whole rollouts), calling `report`
  // after each PPO update or every SacConfig::report_every env steps.
  virtual void train(int64_t until, const Report& report) = 0;
  virtual int64_t env_steps() const = 0;
  virtual const TrainConfig& config() const = 0;
  virtual std::vector<std::string> extra_metric_names() const = 0;
  // Writes a checkpoint atomically (training/checkpoint.hpp).
  virtual void save(const std::string& path) const = 0;
  // Every network parameter and normaliser statistic, flattened (determinism tests).
  virtual std::vector<float> parameters() const = 0;
};

struct CheckpointFile;
// A learning algorithm behind Trainer. Its `name` is also the group of its
// settings in TrainConfig's JSON (`--set ppo.lr=...`).
struct Algorithm {
  std::string name;
  // A fresh run (resume: nullptr) or one continued from a checkpoint it wrote.
  std::unique_ptr<Trainer> (*make)(const TrainConfig& config, const CheckpointFile* resume);
  // The policy in a checkpoint it wrote (checkpoint.hpp's load_policy), acting
  // as in training with `sample`; throws chore::Error naming the file.
  std::unique_ptr<Policy> (*load_policy)(const CheckpointFile& file, bool sample);
};
// A baseline: the algorithm that trains it and the setup it trains with.
struct Baseline {
  std::string name;                    // "rl-prim-hist"
  std::string algorithm;               // "ppo"
  void (*setup)(TrainConfig& config);  // observations, action space, primitive mode, memory
};
const std::vector<Algorithm>& algorithms();
const std::vector<Baseline>& baselines();
// The algorithm that trains `baseline`; throws chore::Error naming the known baselines.
const Algorithm& algorithm_of(const std::string& baseline);

// A fresh run; throws chore::Error for a bad config.
std::unique_ptr<Trainer> make_trainer(const TrainConfig& config);
// Continues the run saved in `checkpoint`: networks, optimizers, normalisers,
// RNG state, step count and episode statistics. Its envs restart, seeded with
// seed + steps. Throws chore::Error for a bad checkpoint.
std::unique_ptr<Trainer> resume_trainer(const std::string& checkpoint, const RankInfo& rank = {});

}  // namespace chore
