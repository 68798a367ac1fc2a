#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <random>

#include "base/error.hpp"
#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "test_util.hpp"
#include "world/sampling.hpp"

namespace chore {
namespace {

// With the seeded start jitter: different seeds, different episodes.
EnvConfig box_room_config() {
  EnvConfig c = test::box_room_config();
  c.start_jitter = EnvConfig().start_jitter;
  return c;
}

std::vector<float> random_action(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1, 1);
  std::vector<float> a(kLowLevelActionSize);
  for (float& x : a) x = u(rng);
  return a;
}

TEST(Env, SpacesDescribeObservationsAndActions) {
  Env env(box_room_config());
  EXPECT_EQ(env.observation_space().to_string(),
            "Dict(rgb: Box(0, 255, (128, 128, 3), uint8), depth: Box(0, inf, (128, 128), float32), "
            "proprio: Box(-inf, inf, (30,), float32), is_grasping: Box(0, 1, (1,), float32))");
  EXPECT_EQ(env.action_space().to_string(), "Box(-1, 1, (14,), float32)");
  auto r = env.reset(3);
  EXPECT_EQ(r.obs["rgb"].shape, (std::vector<int>{1, 128, 128, 3}));
  EXPECT_EQ(r.obs["depth"].shape, (std::vector<int>{1, 128, 128}));
  EXPECT_EQ(r.info.elapsed_steps, 0);
}

TEST(Env, ObservationsAreOptInAndUnknownOnesAreRejected) {
  EnvConfig c = box_room_config();
  c.observations = {"depth"};
  c.width = 64;
  c.height = 48;
  Env env(c);
  EXPECT_EQ(env.observation_space().to_string(), "Dict(depth: Box(0, inf, (48, 64), float32))");
  EXPECT_EQ(env.reset(0).obs["depth"].shape, (std::vector<int>{1, 48, 64}));
  c.observations = {"rgb", "smell"};
  try {
    Env bad(c);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("unknown observation 'smell'"), std::string::npos);
  }
}

TEST(Env, EpisodesAreTruncatedAtTheTimeLimitWithZeroReward) {
  EnvConfig c = box_room_config();
  c.max_episode_steps = 5;
  c.observations = {"proprio"};
  Env env(c);
  env.reset(0);
  std::vector<float> zero(kLowLevelActionSize, 0.f);
  for (int i = 1; i <= 5; ++i) {
    auto s = env.step(zero);
    EXPECT_EQ(s.reward, 0.0);
    EXPECT_FALSE(s.terminated);
    EXPECT_EQ(s.truncated, i == 5);
    EXPECT_EQ(s.info.elapsed_steps, i);
  }
  EXPECT_THROW(env.step(zero), Error);
}

TEST(Env, BadActionsAreClearErrors) {
  Env env(box_room_config());
  env.reset(0);
  std::vector<float> short_action(3, 0.f);
  try {
    env.step(short_action);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("action has 3 values, expected 14"), std::string::npos);
  }
  std::vector<float> nan_action(kLowLevelActionSize, 0.f);
  nan_action[5] = std::nanf("");
  try {
    env.step(nan_action);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("action[5]"), std::string::npos);
  }
  // Nothing was stepped by the rejected actions.
  std::vector<float> zero(kLowLevelActionSize, 0.f);
  EXPECT_EQ(env.step(zero).info.elapsed_steps, 1);
}

TEST(Env, OneSeedFixesAnEpisodeBitForBit) {
  Env a(box_room_config()), b(box_room_config()), c(box_room_config());
  std::mt19937 rng_a(7), rng_b(7), rng_c(7);
  a.reset(11);
  b.reset(11);
  auto first_c = c.reset(12).obs["rgb"].bytes;
  EXPECT_NE(a.reset(11).obs["rgb"].bytes, first_c);  // another seed, another start
  for (int i = 0; i < 20; ++i) {
    auto sa = a.step(random_action(rng_a));
    auto obs_a = sa.obs.arrays();
    auto sb = b.step(random_action(rng_b));
    for (size_t k = 0; k < obs_a.size(); ++k) {
      EXPECT_EQ(obs_a[k].bytes, sb.obs.arrays()[k].bytes) << obs_a[k].name << " step " << i;
    }
    EXPECT_EQ(sa.reward, sb.reward);
    EXPECT_EQ(sa.truncated, sb.truncated);
  }
}

TEST(Env, CloseIsIdempotentAndLaterUseIsAnError) {
  Env env(box_room_config());
  env.reset(0);
  env.close();
  env.close();
  EXPECT_TRUE(env.closed());
  EXPECT_THROW(env.reset(0), Error);
}

}  // namespace
}  // namespace chore

namespace chore {
namespace {

TEST(EnvActivity, RewardFollowsTheGoalsPotentialAndSuccessTerminates) {
  EnvConfig c;
  c.activity = "store_decoration";
  c.observations = {"proprio"};
  Env env(c);
  auto r = env.reset(5);
  EXPECT_EQ(r.info.total, 2);
  EXPECT_EQ(r.info.satisfied, 0);
  EXPECT_FALSE(r.info.success);
  const EnvAssets assets = load_assets(c);
  const Activity& activity = *assets.activity;
  World& w = env.impl().world();
  Rng rng(1);
  const int cabinet = activity.object("cabinet.n.01_1");
  std::vector<float> zero(kLowLevelActionSize, 0.f);
  ASSERT_TRUE(sample_inside(w, activity.object("pumpkin.n.02_1"), cabinet, rng));
  auto s = env.step(zero);
  EXPECT_DOUBLE_EQ(s.reward, 0.5);  // one of two goal literals became true
  EXPECT_DOUBLE_EQ(s.info.q, 0.5);
  EXPECT_FALSE(s.terminated);
  // Undone: negative reward.
  ASSERT_TRUE(sample_onfloor(w, activity.object("pumpkin.n.02_1"), activity.binding("floor.n.01_1").index, rng));
  EXPECT_DOUBLE_EQ(env.step(zero).reward, -0.5);
  ASSERT_TRUE(sample_inside(w, activity.object("pumpkin.n.02_1"), cabinet, rng));
  ASSERT_TRUE(sample_inside(w, activity.object("pumpkin.n.02_2"), cabinet, rng));
  const auto done = env.step(zero);
  EXPECT_DOUBLE_EQ(done.reward, 1.0);
  EXPECT_TRUE(done.terminated);
  EXPECT_FALSE(done.truncated);
  EXPECT_TRUE(done.info.success);
  EXPECT_DOUBLE_EQ(done.info.q, 1.0);
}

TEST(EnvActivity, EachResetSamplesAFreshInstanceFixedByTheSeed) {
  EnvConfig c;
  c.activity = "collect_trash";
  c.observations = {"proprio"};
  Env a(c), b(c);
  const EnvAssets assets = load_assets(c);
  const Activity& activity = *assets.activity;
  const int bottle = activity.object("bottle.n.01_1");
  auto position = [&](Env& e) {
    const double* p = e.world().data()->xpos + 3 * e.world().scene().objects()[bottle].body;
    return std::vector<double>(p, p + 3);
  };
  a.reset(7);
  b.reset(7);
  EXPECT_EQ(position(a), position(b));
  const auto first = position(a);
  a.reset(8);
  EXPECT_NE(position(a), first);
}

// A fixed instance (OmniGibson's default): every reset, whatever its seed,
// puts the robot and the activity's objects where instance 0 has them; after
// the reset, the episode's seed rules (its draws, here the physics of a
// random action, are the seed's).
TEST(EnvActivity, FixedInstancesAreTheSameAtEveryReset) {
  EnvConfig c;
  c.activity = "collect_trash";
  c.observations = {"proprio"};
  c.instances = "fixed";
  Env env(c);
  const auto qpos = [&] {
    const mjData* d = env.world().data();
    return std::vector<double>(d->qpos, d->qpos + env.world().model()->nq);
  };
  env.reset(7);
  const std::vector<double> first = qpos();
  std::mt19937 rng(1);
  env.step(random_action(rng));
  env.reset(8);
  EXPECT_EQ(qpos(), first);
  env.reset();  // no seed: the next episode of the stream, the same instance
  EXPECT_EQ(qpos(), first);
  c.instance = 1;
  Env other(c);
  other.reset(7);
  const mjData* d = other.world().data();
  EXPECT_NE(std::vector<double>(d->qpos, d->qpos + other.world().model()->nq), first);
  c.instances = "cached";
  EXPECT_THROW(Env{c}, Error);
}

// The reach reward: minus the gripper's distance to a point carried along in
// the base frame, so driving and turning the base with the arm still keep it.
TEST(Env, ReachRewardIsMinusTheGripperDistanceToATargetInTheBaseFrame) {
  EnvConfig c = test::box_room_config();
  c.observations = {"proprio"};
  c.reward = "reach";
  Env probe(c);
  probe.reset(0);
  const Pose2 base = probe.world().base_pose();
  const double* g = probe.world().data()->site_xpos + 3 * probe.world().robot()->gripper_site;
  ASSERT_NEAR(base.yaw, 0, 1e-6);
  c.reach_target = {g[0] - base.x, g[1] - base.y, g[2] + 0.5};  // 0.5 m above the gripper
  Env env(c);
  env.reset(0);
  std::vector<float> action(kLowLevelActionSize, 0.f);
  EXPECT_NEAR(env.step(action).reward, -0.5, 0.01);
  action[0] = 1.0f;  // forward and turning
  action[2] = 1.0f;
  double reward = 0;
  for (int t = 0; t < 20; ++t) reward = env.step(action).reward;
  EXPECT_GT(std::abs(env.world().base_pose().yaw), 0.3);
  EXPECT_NEAR(reward, -0.5, 0.03);

  c.reward = "applause";
  EXPECT_EQ(test::error_of([&] { Env bad(c); }), "env config: unknown reward 'applause' (known: activity, reach)");
}

}  // namespace
}  // namespace chore
