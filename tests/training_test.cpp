// The trainers learn (a return rising past what random actions get), are
// deterministic on one thread, and checkpoint, resume and load; bad checkpoints
// are clear errors. State observations keep these fast.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <thread>

#include "policies/evaluate.hpp"
#include "policies/networks.hpp"
#include "test_util.hpp"
#include "training/checkpoint.hpp"
#include "training/gae.hpp"
#include "training/ppo_loss.hpp"
#include "training/trainer.hpp"

namespace chore {
namespace {
namespace fs = std::filesystem;

// SAC's dense task: the gripper to a point 0.3 m away, 50 steps, proprioception.
TrainConfig reach_config() {
  TrainConfig c = baseline_config("rl-vmc", "");
  c.env.scene = test::box_room();
  c.env.observations = {"proprio"};
  c.env.reward = "reach";
  c.env.max_episode_steps = 50;
  c.sac.buffer = 10000;
  c.sac.learning_starts = 250;
  c.sac.hidden = 64;
  c.sac.report_every = 500;
  return c;
}

// PPO's task: CollectTrash's symbolic primitives, 16-step episodes; each
// bottle or cup in the bin is worth 0.25 (BEHAVIOR's potential).
TrainConfig collect_trash_config(const std::string& baseline = "rl-prim") {
  TrainConfig c = baseline_config(baseline, "collect_trash");
  c.env.observations = {"proprio", "is_grasping"};
  c.env.primitive_mode = ExecutionMode::symbolic;
  c.env.max_episode_steps = 16;
  return c;
}

// PPO's learning task: one bottle from the coffee table into the bin (four
// primitives), symbolic, 12-step episodes; the goal is worth 1 (BEHAVIOR's potential).
TrainConfig one_bottle_config(const std::string& baseline = "rl-prim") {
  TrainConfig c = baseline_config(baseline, std::string(CHORE_TEST_DATA) + "/bddl/collect_one_bottle.bddl");
  c.env.scene = "studio";
  c.env.observations = {"proprio", "is_grasping"};
  c.env.primitive_mode = ExecutionMode::symbolic;
  c.env.max_episode_steps = 12;
  return c;
}

// The mean return of uniformly random actions: the bar a learner must clear.
double random_return(const EnvConfig& config, int episodes, uint64_t seed) {
  Env env(config);
  std::mt19937 rng(seed);
  double total = 0;
  for (int e = 0; e < episodes; ++e) {
    env.reset(seed + e);
    for (bool done = false; !done;) {
      std::vector<float> action(env.action_space().element_count());
      if (env.action_space().kind == Space::Kind::discrete) {
        action[0] = static_cast<float>(std::uniform_int_distribution<int64_t>(0, env.action_space().n - 1)(rng));
      } else {
        for (float& a : action) a = std::uniform_real_distribution<float>(-1, 1)(rng);
      }
      const Env::StepResult r = env.step(action);
      total += r.reward;
      done = r.terminated || r.truncated;
    }
  }
  return total / episodes;
}

std::vector<MetricsRow> train(Trainer& trainer, int64_t steps) {
  std::vector<MetricsRow> rows;
  trainer.train(steps, [&](const MetricsRow& row) { rows.push_back(row); });
  return rows;
}

TEST(Training, SacLearnsToReach) {
  TrainConfig config = reach_config();
  const double random = random_return(config.env, 10, 1000);
  // Rewards of ~0.3 a step: a smaller first temperature than 1, a faster learning rate.
  config.sac.initial_alpha = 0.1;
  config.sac.lr = 1e-3;
  auto trainer = make_trainer(config);
  const std::vector<MetricsRow> rows = train(*trainer, 5000);
  const MetricsRow& last = rows.back();
  // Random actions hold the gripper ~0.3 m away (return ~ -15); the learner
  // must at least halve the mean distance over its last 20 episodes.
  EXPECT_LT(random, -12);
  EXPECT_GT(last.mean_return, random / 2) << "random " << random;
  EXPECT_GT(last.mean_return, rows.front().mean_return + 5);
}

class PpoLearns : public ::testing::TestWithParam<std::string> {};

// RL-Prim.'s policy, and RL-Prim.Hist.'s over its last four observations.
TEST_P(PpoLearns, ToPutABottleInTheBin) {
  TrainConfig config = one_bottle_config(GetParam());
  config.ppo.lr = 1e-3;
  const double random = random_return(config.env, 40, 1000);
  auto trainer = make_trainer(config);
  const std::vector<MetricsRow> rows = train(*trainer, 4000);
  // Random primitives finish about one episode in six; the learner (measured:
  // 0.2 -> 0.8 success over 3000 steps) must finish most of its last ones.
  EXPECT_LT(random, 0.25);
  EXPECT_GT(rows.back().mean_return, random + 0.4) << "random " << random;
  EXPECT_GT(rows.back().success_rate, 0.6);
}

INSTANTIATE_TEST_SUITE_P(Baselines, PpoLearns, ::testing::Values("rl-prim", "rl-prim-hist"));

// DD-PPO: two ranks (threads of this process, over loopback) of one env each
// learn the bottle task as one rank does (the same steps in all, each rank
// collecting and learning from half of every rollout and minibatch), their
// parameters the same bit for bit after every update (the trainer checks
// it) and at the end.
TEST(Training, TwoRanksOfPpoLearnToPutABottleInTheBin) {
  TrainConfig config = one_bottle_config();
  config.ppo.lr = 1e-3;
  const double random = random_return(config.env, 40, 1000);
  const int port = test::free_port();
  std::vector<MetricsRow> rows[2];
  std::vector<float> parameters[2];
  int64_t steps[2];
  const auto rank = [&](int r) {
    TrainConfig mine = config;
    mine.rank = {r, 2, "127.0.0.1", port, "torchrun"};
    auto trainer = make_trainer(mine);
    rows[r] = train(*trainer, 4000);
    parameters[r] = trainer->parameters();
    steps[r] = trainer->env_steps();
  };
  std::thread one(rank, 1);
  rank(0);
  one.join();
  EXPECT_EQ(steps[0], steps[1]);
  EXPECT_GE(steps[0], 4000);
  EXPECT_EQ(parameters[0], parameters[1]);
  for (const auto& r : rows) {
    EXPECT_GT(r.back().mean_return, random + 0.4) << "random " << random;
    EXPECT_GT(r.back().success_rate, 0.6);
  }
}

// DD-PPO's preemption: rank 1 steps the bottle task physically, far slower
// than rank 0 symbolically; with ppo.sync_fraction = 0.5 it stops its rollout
// as soon as rank 0 has its whole share (after a quarter of its own), and
// the update still steps both ranks alike (their parameters checked the
// same after each). Without it, every update adds the whole buffer.
TEST(Training, PpoPreemptsAStragglingRank) {
  for (const double sync_fraction : {0.5, 0.0}) {
    TrainConfig config = one_bottle_config();
    config.ppo.epochs = 2;
    config.ppo.sync_fraction = sync_fraction;
    const int port = test::free_port();
    std::vector<MetricsRow> rows[2];
    std::vector<float> parameters[2];
    const auto rank = [&](int r) {
      TrainConfig mine = config;
      mine.rank = {r, 2, "127.0.0.1", port, "torchrun"};
      if (r == 1) mine.env.primitive_mode = ExecutionMode::physical;
      auto trainer = make_trainer(mine);
      rows[r] = train(*trainer, 3 * config.ppo.buffer);
      parameters[r] = trainer->parameters();
    };
    std::thread one(rank, 1);
    rank(0);
    one.join();
    EXPECT_EQ(parameters[0], parameters[1]);
    ASSERT_EQ(rows[0].size(), rows[1].size());
    int64_t last = 0;
    for (const MetricsRow& row : rows[0]) {
      const int64_t added = row.env_steps - last;
      last = row.env_steps;
      // Rank 0's half, and at least a quarter of rank 1's.
      if (sync_fraction > 0) {
        EXPECT_LT(added, config.ppo.buffer) << "update ending at " << row.env_steps;
        EXPECT_GE(added, config.ppo.buffer / 2 + config.ppo.buffer / 8);
      } else {
        EXPECT_EQ(added, config.ppo.buffer);
      }
    }
  }
}

// Over ranks: a rollout and minibatch that do not split evenly, and SAC, are
// errors saying why.
TEST(Training, RanksNeedEvenSharesAndPpo) {
  TrainConfig config = one_bottle_config();
  config.rank = {0, 7, "127.0.0.1", 1, "torchrun"};
  EXPECT_THROW(
      {
        try {
          make_trainer(config);
        } catch (const Error& e) {
          EXPECT_STREQ(e.what(),
                       "ppo: over 7 ranks, ppo.buffer (300) and ppo.batch (64) must be multiples of it: each rank "
                       "collects and learns from its share");
          throw;
        }
      },
      Error);
  TrainConfig sac = reach_config();
  sac.rank = {0, 2, "127.0.0.1", 1, "torchrun"};
  EXPECT_THROW(make_trainer(sac), Error);
}

// GAE by hand: two envs, three steps, a value network that answers 0.5
// everywhere (final observations and the one after the rollout included),
// gamma 0.9, lambda 0.8. Env 0 terminates at step 1; env 1 is truncated at
// steps 0 and 2 (bootstrapped: its reward gains 0.9 x 0.5 = 0.45).
// PPO's loss on a hand-computed minibatch of two: the clipped surrogate
// clips the second sample (ratio 0.5 < 0.8), the value loss is the squared
// error of Schulman's Eq. 9 (Table A.12's c2 weighs it; CleanRL's half of it
// would read 0.5), approx-KL is the k3 estimator.
TEST(Training, PpoLossOfAHandComputedMinibatch) {
  const torch::Tensor logits = torch::tensor({{0.0f, 0.0f}, {std::log(3.0f), 0.0f}});  // probs (.5, .5), (.75, .25)
  const torch::Tensor actions = torch::tensor({0, 1}, torch::kInt64);
  const torch::Tensor old_log_probs = torch::full({2}, std::log(0.5f));  // ratios 1 and 0.5
  const torch::Tensor values = torch::tensor({0.5f, 0.0f}), returns = torch::tensor({1.5f, -1.0f});
  const PpoLoss l = ppo_loss(logits, values, actions, old_log_probs, torch::tensor({1.0f, -1.0f}), returns,
                             /*clip=*/0.2, /*value_coef=*/0.5, /*entropy_coef=*/0.01, /*normalize_advantage=*/false);
  EXPECT_NEAR(l.policy.item<double>(), (-1.0 + 0.8) / 2, 1e-6);  // max(-A r, -A clip(r)) per sample
  EXPECT_NEAR(l.value.item<double>(), 1.0, 1e-6);
  const double entropy = (std::log(2.0) - 0.75 * std::log(0.75) - 0.25 * std::log(0.25)) / 2;
  EXPECT_NEAR(l.entropy.item<double>(), entropy, 1e-6);
  EXPECT_NEAR(l.total.item<double>(), -0.1 + 0.5 * 1.0 - 0.01 * entropy, 1e-6);
  EXPECT_NEAR(l.approx_kl, (0.0 + (0.5 - 1 - std::log(0.5))) / 2, 1e-6);
  EXPECT_DOUBLE_EQ(l.clip_fraction, 0.5);
  // Normalised over the minibatch: advantages +-1/sqrt(2) (torch's unbiased std of +-1 is sqrt(2)).
  const PpoLoss n =
      ppo_loss(logits, values, actions, old_log_probs, torch::tensor({1.0f, -1.0f}), returns, 0.2, 0.5, 0.01, true);
  EXPECT_NEAR(n.policy.item<double>(), (-1.0 + 0.8) / 2 / std::sqrt(2.0), 1e-6);
}

TEST(Training, AdvantagesOfAHandComputedRolloutWithBothEnds) {
  RolloutSteps steps;
  const torch::Tensor v = torch::full({2}, 0.5f);
  steps.rewards = {torch::tensor({1.0f, 0.0f}), torch::tensor({0.0f, 1.0f}), torch::tensor({2.0f, 0.0f})};
  steps.values = {v, v, v};
  steps.terminated = {torch::tensor({0.0f, 0.0f}), torch::tensor({1.0f, 0.0f}), torch::tensor({0.0f, 0.0f})};
  steps.truncated = {torch::tensor({0.0f, 1.0f}), torch::tensor({0.0f, 0.0f}), torch::tensor({0.0f, 1.0f})};
  steps.final_values = {torch::tensor({0.0f, 0.5f}), torch::zeros({2}), torch::tensor({0.0f, 0.5f})};
  const Advantages a = estimate_advantages(steps, v, 0.9, 0.8);
  // Env 0: delta_2 = 2 + 0.9 x 0.5 - 0.5 = 1.95; step 1 ends the episode:
  // delta_1 = 0 - 0.5, nothing flows back from step 2; A_0 = (1 + 0.45 -
  // 0.5) + 0.9 x 0.8 x (-0.5) = 0.59. Env 1: each truncated step's delta is
  // 0.45 - 0.5 = -0.05, with nothing after it; A_1 = 0.95 + 0.72 x (-0.05).
  const torch::Tensor advantages = torch::tensor({{0.59f, -0.05f}, {-0.5f, 0.914f}, {1.95f, -0.05f}});
  EXPECT_TRUE(torch::allclose(a.advantages, advantages, 1e-6, 1e-6)) << a.advantages;
  EXPECT_TRUE(torch::allclose(a.returns, advantages + 0.5f, 1e-6, 1e-6)) << a.returns;
}

// RL-Prim.Hist.'s observation history: newest first, zeros before the
// episode's first step, per env; stacked() looks without remembering.
TEST(Training, FrameStackKeepsTheLastKObservationsNewestFirst) {
  FrameStack stack(3);
  const auto frame = [](uint8_t pixel, float state) {
    return ObsTensors{torch::full({1, 3, 2, 2}, pixel, torch::kUInt8), torch::full({1, 2}, state)};
  };
  const int env1[] = {1}, env0[] = {0};
  stack.push(env1, frame(10, 1.0f));
  const ObsTensors two = stack.push(env1, frame(20, 2.0f));
  EXPECT_TRUE(torch::equal(two.state, torch::tensor({{2.0f, 2.0f, 1.0f, 1.0f, 0.0f, 0.0f}})));
  ASSERT_EQ(two.rgb.sizes(), (std::vector<int64_t>{1, 9, 2, 2}));
  EXPECT_EQ(two.rgb[0][0][0][0].item<int>(), 20);
  EXPECT_EQ(two.rgb[0][3][1][1].item<int>(), 10);
  EXPECT_EQ(two.rgb[0][6][0][1].item<int>(), 0);
  const ObsTensors peek = stack.stacked(env1, frame(30, 3.0f));
  EXPECT_TRUE(torch::equal(peek.state, torch::tensor({{3.0f, 3.0f, 2.0f, 2.0f, 1.0f, 1.0f}})));
  const ObsTensors three = stack.push(env1, frame(40, 4.0f));  // the peek was not remembered
  EXPECT_TRUE(torch::equal(three.state, torch::tensor({{4.0f, 4.0f, 2.0f, 2.0f, 1.0f, 1.0f}})));
  const ObsTensors four = stack.push(env1, frame(50, 5.0f));  // the oldest falls out
  EXPECT_TRUE(torch::equal(four.state, torch::tensor({{5.0f, 5.0f, 4.0f, 4.0f, 2.0f, 2.0f}})));
  EXPECT_TRUE(
      torch::equal(stack.push(env0, frame(7, 7.0f)).state, torch::tensor({{7.0f, 7.0f, 0.0f, 0.0f, 0.0f, 0.0f}})));
  stack.reset(env1);
  const ObsTensors fresh = stack.push(env1, frame(60, 6.0f));
  EXPECT_TRUE(torch::equal(fresh.state, torch::tensor({{6.0f, 6.0f, 0.0f, 0.0f, 0.0f, 0.0f}})));
  EXPECT_EQ(fresh.rgb.narrow(1, 3, 6).sum().item<int64_t>(), 0);
}

// Everything but timings.
std::vector<double> comparable(const std::vector<MetricsRow>& rows, const std::vector<std::string>& extras) {
  std::vector<double> out;
  for (const MetricsRow& r : rows) {
    out.insert(out.end(), {static_cast<double>(r.env_steps), static_cast<double>(r.episodes), r.success_rate, r.mean_q,
                           r.mean_return, r.mean_length});
    for (size_t i = 0; i < extras.size(); ++i) {
      if (extras[i].find("_s") == std::string::npos && extras[i] != "update_ms") out.push_back(r.extras[i]);
    }
  }
  return out;
}

void expect_deterministic(const TrainConfig& config, int64_t steps) {
  auto a = make_trainer(config);
  auto b = make_trainer(config);
  const std::vector<MetricsRow> rows_a = train(*a, steps), rows_b = train(*b, steps);
  ASSERT_FALSE(rows_a.empty());
  EXPECT_EQ(comparable(rows_a, a->extra_metric_names()), comparable(rows_b, b->extra_metric_names()));
  EXPECT_EQ(a->parameters(), b->parameters());
  // And the seed matters.
  TrainConfig other = config;
  other.seed += 1;
  auto c = make_trainer(other);
  train(*c, steps);
  EXPECT_NE(a->parameters(), c->parameters());
}

TEST(Training, PpoWithObservationHistoryIsDeterministicOnOneThread) {
  expect_deterministic(collect_trash_config("rl-prim-hist"), 600);
}

// PPO's encoder normalises the image alone ("The image input is normalized
// using a per-channel moving average", appendix F.1): its state reaches the
// state encoder as observed. A checkpoint of before, which normalised the
// state too, says so by lacking the field, and is rebuilt as it was.
TEST(Training, PpoNormalisesTheImageNotTheState) {
  TrainConfig config = collect_trash_config();
  config.ppo.buffer = 32;
  config.ppo.batch = 16;
  auto trainer = make_trainer(config);
  train(*trainer, 32);
  const std::string path = (test::scratch_dir("ppo_state_norm") / "checkpoint.pt").string();
  trainer->save(path);
  const CheckpointFile file = read_checkpoint(path);
  EXPECT_FALSE(read_checkpoint_meta(file).network.normalize_state);
  for (const auto& [name, tensor] : file.tensors) EXPECT_EQ(name.find("state_norm"), std::string::npos) << name;
  nlohmann::json before = file.meta["network"];
  before.erase("normalize_state");
  EXPECT_TRUE(network_spec_from_json(before).normalize_state);
  EXPECT_EQ(ActorCritic(network_spec_from_json(before))->named_buffers().contains("encoder.state_norm.mean"), true);
}

TEST(Training, PpoWithActionHistoryIsDeterministicOnOneThread) {
  expect_deterministic(collect_trash_config("rl-prim-action-hist"), 600);
}

// --set's overrides: one field by its JSON path, of the field's own type.
TEST(Training, SettingReplacesOneFieldOfItsType) {
  const TrainConfig base = collect_trash_config();
  EXPECT_TRUE(base.ppo.normalize_advantage);  // SB3's and CleanRL's default
  TrainConfig c = with_setting(base, "ppo.entropy_coef=0.01");
  c = with_setting(c, "ppo.normalize_advantage=false");
  c = with_setting(c, "ppo.epochs=4");
  c = with_setting(c, "ppo.target_kl=0.01");
  c = with_setting(c, "ppo.sync_fraction=0.6");
  c = with_setting(c, "env.max_episode_steps=30");
  EXPECT_EQ(c.ppo.entropy_coef, 0.01);
  EXPECT_FALSE(c.ppo.normalize_advantage);
  EXPECT_EQ(c.ppo.epochs, 4);
  EXPECT_EQ(c.env.max_episode_steps, 30);
  EXPECT_EQ(with_setting(base, "sac.lr=1").sac.lr, 1.0);  // an integer is a number
  EXPECT_EQ(with_setting(base, "baseline=rl-prim-hist").baseline, "rl-prim-hist");
  // Everything else as it was.
  nlohmann::json expected = to_json(base);
  expected["ppo"]["entropy_coef"] = 0.01;
  expected["ppo"]["normalize_advantage"] = false;
  expected["ppo"]["epochs"] = 4;
  expected["ppo"]["target_kl"] = 0.01;
  expected["ppo"]["sync_fraction"] = 0.6;
  expected["env"]["max_episode_steps"] = 30;
  EXPECT_EQ(to_json(c), expected);
  for (const auto& [bad, message] : std::vector<std::pair<std::string, std::string>>{
           {"ppo.epochs", "expected KEY=VALUE"},
           {"ppo.nope=1", "ppo.nope: no such setting"},
           {"ppo.lr.x=1", "ppo.lr.x: no such setting"},
           {"ppo=1", "a group of settings"},
           {"ppo.epochs=1.5", "'1.5' is not a number like 10"},
           {"ppo.normalize_advantage=1", "is not a boolean"},
           {"seed=-1", "is not a number"},
           // Ranges, and numbers that would not fit their field.
           {"ppo.lr=-1", "--set ppo.lr=-1: ppo.lr = -1 is outside [1e-12, 1]"},
           {"ppo.lr=1e308", "ppo.lr = 1e+308 is outside [1e-12, 1]"},
           {"ppo.sync_fraction=1.5", "ppo.sync_fraction = 1.5 is outside [0, 1]"},
           {"seed=1000000000001", "seed = 1000000000001 is outside"},
           {"sac.buffer=4294967297",
            "sac.buffer = 4294967297 does not fit the setting (it would "
            "read as 1)"}}) {
    EXPECT_NE(test::error_of([&] { with_setting(base, bad); }).find(message), std::string::npos) << bad;
  }
  // A run saved before the fields existed normalised its advantages and never stopped early.
  nlohmann::json old = to_json(c);
  old["ppo"].erase("normalize_advantage");
  old["ppo"].erase("target_kl");
  old["ppo"].erase("sync_fraction");
  EXPECT_TRUE(train_config_from_json(old).ppo.normalize_advantage);
  EXPECT_EQ(train_config_from_json(old).ppo.target_kl, 0.0);
  EXPECT_EQ(train_config_from_json(old).ppo.sync_fraction, 0.0);
  // Any activity trains on instances as drawn with this; runs from before
  // it was a setting had everything within reach.
  EXPECT_TRUE(base.env.reachable_instances);
  EXPECT_FALSE(with_setting(base, "env.reachable_instances=false").env.reachable_instances);
  old["env"].erase("reachable_instances");
  EXPECT_TRUE(train_config_from_json(old).env.reachable_instances);
}

// Without the normalisation the same rollout gives another update.
TEST(Training, PpoAdvantageNormalisationChangesTheUpdate) {
  TrainConfig config = collect_trash_config();
  auto normalised = make_trainer(config);
  config.ppo.normalize_advantage = false;
  auto raw = make_trainer(config);
  const std::vector<MetricsRow> a = train(*normalised, 300), b = train(*raw, 300);
  EXPECT_EQ(a.front().mean_return, b.front().mean_return);  // the same first rollout
  EXPECT_NE(normalised->parameters(), raw->parameters());
}

// SB3's target_kl: an update stops before the first minibatch past 1.5x the
// target, so every minibatch stepped was within it; a target never reached
// changes nothing.
TEST(Training, PpoTargetKlStopsTheUpdateEarly) {
  TrainConfig config = collect_trash_config();
  auto unbounded = make_trainer(config);
  config.ppo.target_kl = 1e6;
  auto never_reached = make_trainer(config);
  config.ppo.target_kl = 1e-3;
  auto bounded = make_trainer(config);
  const std::vector<std::string> names = unbounded->extra_metric_names();
  const size_t kl = std::find(names.begin(), names.end(), "approx_kl") - names.begin();
  ASSERT_LT(kl, names.size());
  const std::vector<MetricsRow> a = train(*unbounded, 600), b = train(*never_reached, 600), c = train(*bounded, 600);
  EXPECT_EQ(unbounded->parameters(), never_reached->parameters());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_GT(a[i].extras[kl], 1.5e-3) << "update " << i;  // ten epochs go past the target...
    EXPECT_LE(c[i].extras[kl], 1.5e-3) << "update " << i;  // ...and stop within it
    EXPECT_GT(c[i].extras[kl], 0) << "update " << i;       // after at least one step
  }
  EXPECT_NE(unbounded->parameters(), bounded->parameters());
  config.ppo.target_kl = -1;
  EXPECT_NE(test::error_of([&] { make_trainer(config); }).find("target_kl must be 0 (off) or positive"),
            std::string::npos);
}

// With 32x32 RGB: the conv trunk and the image normaliser.
TEST(Training, SacWithImagesIsDeterministicOnOneThread) {
  TrainConfig config = reach_config();
  config.env.observations = {"rgb", "proprio"};
  config.env.width = config.env.height = 32;
  config.sac.learning_starts = 100;
  config.sac.report_every = 100;
  expect_deterministic(config, 300);
}

TEST(Training, HistoryKeepsTheLastKPrimitivesAndResultsNewestFirst) {
  History history(2, 4);  // K = 2 steps of 4 actions + 5 statuses
  const int ids[] = {1};
  Info result;
  result.primitive_status = static_cast<int>(PrimitiveStatus::success);
  history.push(ids, torch::tensor({2}), std::span(&result, 1));
  result.primitive_status = static_cast<int>(PrimitiveStatus::precondition_failure);
  history.push(ids, torch::tensor({0}), std::span(&result, 1));
  const torch::Tensor row = history.rows(ids)[0];
  const std::vector<float> expected = {1, 0, 0, 0, /* status */ 0, 0, 0, 0, 1,   // newest
                                       0, 0, 1, 0, /* status */ 1, 0, 0, 0, 0};  // before
  EXPECT_TRUE(torch::equal(row, torch::tensor(expected)));
  EXPECT_EQ(History::width(2, 4), 18);
  const int env0[] = {0};
  EXPECT_EQ(history.rows(env0).abs().sum().item<float>(), 0.0f);  // untouched env: zeros
  history.reset(ids);
  EXPECT_EQ(history.rows(ids).abs().sum().item<float>(), 0.0f);
}

// The bits of a float tensor (NaN and -0 included), for exact comparisons.
torch::Tensor bits(const torch::Tensor& t) {
  return t.contiguous().view(torch::kInt32);
}

// The trunk's own pooling computes what nn::MaxPool2d(2) does, bit for bit:
// ties (a flat region, all-zero windows after a ReLU) go to the first
// maximum, a NaN wins, an odd size drops its last row and column, and a -0
// gradient lands as +0.
TEST(Training, MaxPool2x2IsTorchsMaxPoolBitForBit) {
  torch::manual_seed(0);
  torch::Tensor x = torch::relu(torch::randn({2, 3, 9, 7}));
  x[0][0].narrow(0, 0, 4).fill_(0.5f);
  x[1][2][3][3] = std::numeric_limits<float>::quiet_NaN();
  x[1][1].narrow(0, 0, 2).narrow(1, 0, 2).fill_(-std::numeric_limits<float>::infinity());
  torch::Tensor grad = torch::randn({2, 3, 4, 3});
  grad[0][1][1][1] = -0.0f;
  auto run = [&](const std::function<torch::Tensor(const torch::Tensor&)>& pool) {
    const torch::Tensor input = x.clone().requires_grad_();
    const torch::Tensor out = pool(input);
    out.backward(grad);
    torch::NoGradGuard no_grad;
    return std::make_tuple(out.detach(), input.grad(), pool(x));
  };
  const auto [out, input_grad, no_grad_out] = run([](const torch::Tensor& t) { return torch::max_pool2d(t, 2); });
  MaxPool2x2 pool;
  const auto [own, own_grad, own_no_grad] = run([&](const torch::Tensor& t) { return pool(t); });
  EXPECT_TRUE(torch::equal(bits(own), bits(out)));
  EXPECT_TRUE(torch::equal(bits(own_grad), bits(input_grad)));
  EXPECT_TRUE(torch::equal(bits(own_no_grad), bits(no_grad_out)));
}

// Images normalise in one vectorised pass over their bytes, bit for bit
// as the float path.
TEST(Training, ByteNormalisationIsTheFloatOneBitForBit) {
  torch::manual_seed(0);
  RunningNorm norm(3, 5.0);
  norm->update(torch::rand({100, 3}) * 255);
  norm->update(torch::rand({50, 3}) * 40 + 200);
  const torch::Tensor images = torch::randint(0, 256, {4, 3, 16, 12}, torch::kUInt8);
  EXPECT_TRUE(torch::equal(bits(norm->forward_bytes(images)), bits(norm->forward(images.to(torch::kFloat32), 1))));
  // Narrow statistics: most bytes clamp to -5 or +5, and byte 128 is a
  // channel's mean exactly (0 / std); odd sizes leave vector tails.
  RunningNorm narrow(3, 5.0);
  narrow->update(torch::tensor({{127.0f, 128.0f, 120.0f}, {129.0f, 128.0f, 140.0f}}));
  const torch::Tensor all = torch::arange(256, torch::kUInt8).repeat({27}).view({3, 3, 16, 48}).narrow(3, 0, 47);
  const torch::Tensor normalised = narrow->forward_bytes(all);
  EXPECT_TRUE(torch::equal(bits(normalised), bits(narrow->forward(all.to(torch::kFloat32), 1))));
  EXPECT_EQ(normalised.max().item<float>(), 5.0f);
  EXPECT_EQ(normalised.min().item<float>(), -5.0f);
}

TEST(Training, ImageTrunkPoolsTo4x4) {
  EXPECT_EQ(trunk_output_size(128, 128), 32 * 4 * 4);
}

// A short PPO run's checkpoint: save, resume, load the policy.
TEST(Checkpoint, ResumesTheRunAndLoadsAGreedyPolicy) {
  const fs::path dir = test::scratch_dir("checkpoint_resume");
  const std::string path = (dir / "checkpoint.pt").string();
  auto trainer = make_trainer(collect_trash_config("rl-prim-hist"));
  train(*trainer, 300);
  trainer->save(path);
  for (const auto& file : fs::directory_iterator(dir)) {
    EXPECT_EQ(file.path().filename().string().find(".tmp."), std::string::npos) << file.path() << " left behind";
  }

  auto resumed = resume_trainer(path);
  EXPECT_EQ(resumed->env_steps(), 300);
  EXPECT_EQ(resumed->parameters(), trainer->parameters());
  EXPECT_EQ(resumed->config().baseline, "rl-prim-hist");
  const std::vector<MetricsRow> rows = train(*resumed, 600);
  EXPECT_EQ(rows.back().env_steps, 600);
  EXPECT_GE(rows.back().episodes, 2 * (300 / 16));  // the envs restart on resume

  LoadedPolicy loaded = load_policy(path);
  EXPECT_EQ(loaded.baseline, "rl-prim-hist");
  EXPECT_EQ(loaded.steps, 300);
  EXPECT_EQ(loaded.env.max_episode_steps, 16);
  VectorEnv env({.env = loaded.env, .num_envs = 2, .autoreset = AutoReset::same_step});
  Batch batch = env.reset(7);
  std::vector<float> actions(2);
  const int64_t n = env.single_action_space().n;
  for (int t = 0; t < 20; ++t) {
    loaded.policy->act(batch, actions);
    for (float a : actions) EXPECT_TRUE(a >= 0 && a < n && a == std::floor(a)) << a;
    batch = env.step(actions);
    std::vector<int> ended;
    for (int i = 0; i < batch.size(); ++i) {
      if (batch.terminated[i] || batch.truncated[i]) ended.push_back(batch.env_ids[i]);
    }
    loaded.policy->reset(ended);
  }
}

// A sampled policy draws anew at every step of an episode (greedy repeats
// itself on the same observation), and its draws are seeded by the episode:
// evaluation gives the same episodes on one thread and on two.
TEST(Checkpoint, SampledPolicyDrawsAndIsSeededByTheEpisode) {
  const fs::path dir = test::scratch_dir("checkpoint_sampled");
  const std::string path = (dir / "checkpoint.pt").string();
  auto trainer = make_trainer(collect_trash_config());
  train(*trainer, 300);
  trainer->save(path);

  auto distinct_actions = [&](bool sample) {
    LoadedPolicy loaded = load_policy(path, sample);
    VectorEnv env({.env = loaded.env, .num_envs = 1});
    Batch batch = env.reset(3);
    std::vector<float> action(1), first(1);
    loaded.policy->act(batch, first);
    loaded.policy->act(batch, action);
    EXPECT_EQ(action, first) << "an episode's first step draws from its own seed";
    batch = env.step(action);
    std::set<float> seen;
    for (int i = 0; i < 50; ++i) {
      loaded.policy->act(batch, action);  // the same observation, mid-episode
      seen.insert(action[0]);
    }
    return seen.size();
  };
  EXPECT_EQ(distinct_actions(false), 1u);
  EXPECT_GE(distinct_actions(true), 3u);  // an untrained policy is near uniform over 16 actions

  auto episodes = [&](int threads) {
    auto loaded = std::make_shared<LoadedPolicy>(load_policy(path, true));
    const PolicySource source{"sampled", loaded->env, [loaded](const VectorEnv&) { return std::move(loaded->policy); }};
    std::ostringstream log;
    return evaluate(source, {.first_seed = 0, .last_seed = 1, .episodes = 3, .threads = threads}, log)["per_episode"];
  };
  EXPECT_EQ(episodes(1), episodes(2));
}

TEST(Checkpoint, EnvConfigKeepsSensorSettingsAndOlderFilesGetDefaults) {
  EnvConfig c;
  c.observations = {"rgb", "lidar"};
  c.lidar.beams = 90;
  c.lidar.range = 5.5;
  c.noise.depth_noise_quadratic = 0.0019;
  c.noise.lidar_dropout = 0.05;
  c.randomization.surface_color = 0.25;
  nlohmann::json j = to_json(c);
  const EnvConfig back = env_config_from_json(j);
  EXPECT_EQ(back.lidar.beams, 90);
  EXPECT_EQ(back.lidar.range, 5.5);
  EXPECT_EQ(back.noise.depth_noise_quadratic, 0.0019);
  EXPECT_EQ(back.noise.lidar_dropout, 0.05);
  EXPECT_EQ(back.randomization.surface_color, 0.25);
  EXPECT_EQ(to_json(back), j);
  // A checkpoint written before the sensor settings existed: the defaults.
  for (const char* group : {"lidar", "noise", "randomization"}) j.erase(group);
  const EnvConfig old = env_config_from_json(j);
  EXPECT_EQ(old.lidar.beams, LidarConfig{}.beams);
  EXPECT_EQ(old.noise.lidar_dropout, 0.0);
  EXPECT_FALSE(old.randomization.any());
}

TEST(Checkpoint, PolicyThreadsArePinned) {
  set_policy_threads(1);
  EXPECT_EQ(torch::get_num_threads(), 1);
  set_policy_threads(2);
  EXPECT_EQ(torch::get_num_threads(), 2);
  EXPECT_NE(test::error_of([] { set_policy_threads(0); }).find("at least 1"), std::string::npos);
}

TEST(Checkpoint, SacPolicyActsWithTanhMean) {
  const fs::path dir = test::scratch_dir("checkpoint_sac");
  const std::string path = (dir / "checkpoint.pt").string();
  TrainConfig config = reach_config();
  config.sac.learning_starts = 64;
  auto trainer = make_trainer(config);
  train(*trainer, 100);
  trainer->save(path);
  EXPECT_EQ(resume_trainer(path)->parameters(), trainer->parameters());
  LoadedPolicy loaded = load_policy(path);
  EXPECT_EQ(loaded.baseline, "rl-vmc");
  VectorEnv env({.env = loaded.env, .num_envs = 1});
  const Batch batch = env.reset(3);
  std::vector<float> a(kLowLevelActionSize), b(kLowLevelActionSize);
  loaded.policy->act(batch, a);
  loaded.policy->act(batch, b);
  EXPECT_EQ(a, b);  // greedy: the same observation, the same action
  for (float x : a) EXPECT_TRUE(x > -1 && x < 1) << x;
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(Checkpoint, CorruptTruncatedAndIncompatibleFilesAreErrors) {
  const fs::path dir = test::scratch_dir("checkpoint_bad");
  const fs::path good = dir / "good.pt";
  auto trainer = make_trainer(collect_trash_config());
  trainer->save(good.string());
  const std::string bytes = read_bytes(good);
  auto write = [&](const std::string& name, const std::string& content) {
    const fs::path p = dir / name;
    std::ofstream(p, std::ios::binary) << content;
    return p.string();
  };
  auto load_error = [](const std::string& path) { return test::error_of([&] { load_policy(path); }); };
  auto resume_error = [](const std::string& path) { return test::error_of([&] { resume_trainer(path); }); };

  // A byte of the last tensor's data (the generator's state, ~5 KB, before
  // the 8-byte checksum): framing intact, contents changed.
  std::string corrupt = bytes;
  corrupt[bytes.size() - 8 - 16] ^= 0x5a;
  const std::string corrupt_path = write("corrupt.pt", corrupt);
  EXPECT_NE(load_error(corrupt_path).find("corrupt (checksum mismatch)"), std::string::npos)
      << load_error(corrupt_path);
  // A byte of the framing (a tensor's shape) is named as such.
  std::string reshaped = bytes;
  reshaped[bytes.size() / 2] ^= 0x5a;
  EXPECT_NE(load_error(write("reshaped.pt", reshaped)).find("checkpoint"), std::string::npos);
  EXPECT_NE(resume_error(corrupt_path).find("corrupt"), std::string::npos);

  for (size_t size : {size_t{3}, size_t{20}, bytes.size() / 2, bytes.size() - 1}) {
    const std::string path = write("truncated.pt", bytes.substr(0, size));
    const std::string error = load_error(path);
    EXPECT_TRUE(error.find("truncated") != std::string::npos || error.find("bad magic") != std::string::npos)
        << size << ": " << error;
  }
  EXPECT_NE(load_error(write("text.pt", "hello")).find("not a chore checkpoint"), std::string::npos);
  EXPECT_NE(load_error((dir / "missing.pt").string()).find("cannot open"), std::string::npos);
  // Not read at all: a device that never ends, a directory, a file over the bound (sparse: no disk used).
  EXPECT_NE(load_error("/dev/zero").find("not a regular file"), std::string::npos);
  EXPECT_NE(load_error(dir.string()).find("not a regular file"), std::string::npos);
  const std::string oversized = write("oversized.pt", "");
  std::filesystem::resize_file(oversized, kMaxCheckpointBytes + 1);
  EXPECT_NE(load_error(oversized).find("more than " + std::to_string(kMaxCheckpointBytes)), std::string::npos);
  std::filesystem::remove(oversized);

  std::string future = bytes;
  future[8] = 99;  // the version field
  EXPECT_NE(load_error(write("future.pt", future)).find("format version 99, this chore reads version 2"),
            std::string::npos);

  // Well-formed files whose contents do not fit: a network spec that does not
  // match the weights, an unknown baseline, missing metadata.
  CheckpointFile file = read_checkpoint(good.string());
  CheckpointFile wrong_spec = file;
  wrong_spec.meta["network"]["feature_size"] = 64;
  write_checkpoint((dir / "spec.pt").string(), wrong_spec);
  EXPECT_NE(load_error((dir / "spec.pt").string()).find("the network expects [64"), std::string::npos)
      << load_error((dir / "spec.pt").string());
  CheckpointFile wrong_baseline = file;
  wrong_baseline.meta["config"]["baseline"] = "rl-magic";
  write_checkpoint((dir / "baseline.pt").string(), wrong_baseline);
  EXPECT_NE(resume_error((dir / "baseline.pt").string()).find("unknown baseline 'rl-magic'"), std::string::npos);
  CheckpointFile no_steps = file;
  no_steps.meta.erase("steps");
  write_checkpoint((dir / "steps.pt").string(), no_steps);
  EXPECT_NE(load_error((dir / "steps.pt").string()).find("bad metadata"), std::string::npos);
  // Absurd sizes that pass the checksum are errors before any allocation.
  CheckpointFile huge = file;
  huge.meta["network"]["hidden"] = 1000000000;
  write_checkpoint((dir / "huge.pt").string(), huge);
  EXPECT_NE(load_error((dir / "huge.pt").string()).find("network spec: hidden = 1000000000 is outside [1, 100000]"),
            std::string::npos);
  CheckpointFile deep = file;
  nlohmann::json nest = 1;
  for (int i = 0; i < 100; ++i) nest = nlohmann::json::array({nest});
  deep.meta["nest"] = nest;
  write_checkpoint((dir / "deep.pt").string(), deep);
  EXPECT_NE(load_error((dir / "deep.pt").string()).find(": metadata:1:"), std::string::npos);
  // Tensors: each record's bytes must be its shape's, and each tensor the
  // network's own name, type and shape.
  const std::string first = file.tensors.begin()->first;  // a network tensor, "net...."
  ASSERT_EQ(first.rfind("net.", 0), 0u) << first;
  CheckpointFile missing = file;
  missing.tensors.erase(first);
  write_checkpoint((dir / "missing_tensor.pt").string(), missing);
  EXPECT_NE(load_error((dir / "missing_tensor.pt").string()).find("no tensor '" + first + "'"), std::string::npos);
  CheckpointFile wrong_type = file;
  TensorRecord& record = wrong_type.tensors[first];
  record.type = ElementType::float64;
  record.bytes += record.bytes;
  write_checkpoint((dir / "type.pt").string(), wrong_type);
  EXPECT_NE(
      load_error((dir / "type.pt").string()).find("tensor '" + first + "' is float64, the network expects float32"),
      std::string::npos);
  auto framing_error = [&](const std::string& name, TensorRecord t) {
    CheckpointFile bad = file;
    bad.tensors = {{"x", std::move(t)}};
    write_checkpoint((dir / name).string(), bad);
    return load_error((dir / name).string());
  };
  EXPECT_NE(framing_error("short.pt", {ElementType::float32, {2}, "1234"}).find("tensor 'x': 4 bytes for 2 elements"),
            std::string::npos);
  EXPECT_NE(framing_error("rank.pt", {ElementType::uint8, std::vector<int64_t>(9, 1), "1"}).find("rank 9 is over 8"),
            std::string::npos);
  EXPECT_NE(framing_error("huge.pt", {ElementType::uint8, {int64_t{1} << 40, int64_t{1} << 40}, ""})
                .find("tensor 'x': dimension 1099511627776"),
            std::string::npos);
  // The good file still loads.
  EXPECT_EQ(load_policy(good.string()).steps, 0);
}

std::vector<std::vector<std::string>> csv_rows(const fs::path& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream s(line);
    for (std::string cell; std::getline(s, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

// chore train, SIGKILLed after its first checkpoints, resumed to the end; the
// final checkpoint loads as a policy.
TEST(Checkpoint, TrainKilledMidRunResumesAndFinishes) {
  const fs::path dir = test::scratch_dir("train_kill");
  const std::string chore = CHORE_BINARY;
  const std::vector<std::string> args = {chore,
                                         "train",
                                         "--activity",
                                         "collect_trash",
                                         "--baseline",
                                         "rl-prim-hist",
                                         "--mode",
                                         "symbolic",
                                         "--observations",
                                         "proprio",
                                         "is_grasping",
                                         "--episode-steps",
                                         "16",
                                         "--steps",
                                         "1500",
                                         "--checkpoint-every",
                                         "300",
                                         "--seed",
                                         "3",
                                         "--out",
                                         dir.string()};
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    freopen("/dev/null", "w", stderr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(dir / "checkpoint_600.pt") && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the run ended before it was killed";
  const int64_t killed_at = read_checkpoint((dir / "checkpoint.pt").string()).meta["steps"].get<int64_t>();
  EXPECT_GE(killed_at, 600);
  EXPECT_LT(killed_at, 1500);

  const std::string resume = chore + " train --resume " + dir.string() + " 2>/dev/null";
  ASSERT_EQ(std::system(resume.c_str()), 0);
  const auto rows = csv_rows(dir / "metrics.csv");
  ASSERT_GE(rows.size(), 6u);
  EXPECT_EQ(rows[0][0], "env_steps");
  for (size_t i = 1; i < rows.size(); ++i) {
    EXPECT_EQ(std::stoll(rows[i][0]), static_cast<int64_t>(300 * i)) << "row " << i;  // no gap, no repeat
  }
  EXPECT_EQ(rows.back()[0], "1500");
  const LoadedPolicy loaded = load_policy((dir / "checkpoint.pt").string());
  EXPECT_EQ(loaded.steps, 1500);
  EXPECT_TRUE(fs::exists(dir / "checkpoint_1500.pt"));
  // Resuming a finished run with the same --steps does nothing more.
  ASSERT_EQ(std::system(resume.c_str()), 0);
  EXPECT_EQ(csv_rows(dir / "metrics.csv").size(), rows.size());
  // And the resumed run's checkpoint evaluates.
  const fs::path report = dir / "eval.json";
  const std::string eval = chore + " eval --checkpoint " + (dir / "checkpoint.pt").string() +
                           " --seeds 0-1 --episodes 2 --json > " + report.string() + " 2>/dev/null";
  ASSERT_EQ(std::system(eval.c_str()), 0);
  std::ifstream in(report);
  const nlohmann::json result = nlohmann::json::parse(in).at(0);
  EXPECT_EQ(result.at("per_episode").size(), 4u);
  EXPECT_EQ(result.at("policy").get<std::string>(), (dir / "checkpoint.pt").string());
}

}  // namespace
}  // namespace chore
