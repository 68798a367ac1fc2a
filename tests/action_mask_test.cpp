// The action_mask observation of the primitive action space: 1 exactly where
// an action's precondition holds, batched by VectorEnv, refused elsewhere.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "env/env.hpp"
#include "env/vector_env.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

EnvConfig masked_config() {
  EnvConfig c;
  c.activity = "store_decoration";
  c.action_space = "primitives";
  c.primitive_mode = ExecutionMode::symbolic;
  c.observations = {"is_grasping", "action_mask"};
  c.max_episode_steps = 200;
  c.policy_failure_repeats = 1000;  // keep going through invalid actions
  return c;
}

std::vector<int> mask_of(const ArrayDict& obs, int row = 0) {
  const Array& mask = obs["action_mask"];
  const auto* m = static_cast<const std::uint8_t*>(mask.item(row));
  return std::vector<int>(m, m + mask.shape[1]);
}

struct Stepped {
  int status;
  std::vector<int> mask;
  std::string reason;
};
Stepped step(Env& env, int action) {
  const float a = static_cast<float>(action);
  const Env::StepResult r = env.step({&a, 1});
  return {r.info.primitive_status, mask_of(r.obs), env.last_primitive().reason};
}

constexpr int kPrecondition = static_cast<int>(PrimitiveStatus::precondition_failure);

// Actions of store_decoration, in order (PrimitiveActions.AreDerivedFromEachActivitysBddl).
enum { kNavPumpkin1, kPickPumpkin1, kNavPumpkin2, kPickPumpkin2, kNavCabinet, kPlaceCabinet, kPushCabinet };

TEST(ActionMask, SaysWhichPreconditionsHold) {
  Env env(masked_config());
  EXPECT_EQ(env.observation_space()["action_mask"].to_string(), "Box(0, 1, (7,), uint8)");
  // The hand is empty: place is masked; picks and push (a closed drawer) are
  // allowed; the robot starts within reach of nothing: every navigate is allowed.
  EXPECT_EQ(mask_of(env.reset(1).obs), (std::vector<int>{1, 1, 1, 1, 1, 0, 1}));
  // At the pumpkin, navigating to it again would fail its precondition.
  Stepped s = step(env, kNavPumpkin1);
  ASSERT_EQ(s.status, 0) << s.reason;
  EXPECT_EQ(s.mask, (std::vector<int>{0, 1, 1, 1, 1, 0, 1}));
  // Holding it: no pick (of either pumpkin) and no push; place is allowed.
  s = step(env, kPickPumpkin1);
  ASSERT_EQ(s.status, 0) << s.reason;
  EXPECT_EQ(s.mask[kPickPumpkin1], 0);
  EXPECT_EQ(s.mask[kPickPumpkin2], 0);
  EXPECT_EQ(s.mask[kPushCabinet], 0);
  EXPECT_EQ(s.mask[kPlaceCabinet], 1);
  EXPECT_EQ(s.mask[kNavCabinet], 1);
}

// Along a long random walk, a masked action fails its precondition and an
// allowed one never does: the mask is the primitives' own precondition.
TEST(ActionMask, AgreesWithThePrimitivesOutcomes) {
  Env env(masked_config());
  std::vector<int> mask = mask_of(env.reset(3).obs);
  std::mt19937 rng(7);
  int masked_tried = 0, allowed_tried = 0;
  for (int t = 0; t < 40; ++t) {
    std::vector<int> allowed, masked;
    for (int a = 0; a < static_cast<int>(mask.size()); ++a) (mask[a] ? allowed : masked).push_back(a);
    const bool try_masked = !masked.empty() && (allowed.empty() || rng() % 2 == 0);
    const std::vector<int>& from = try_masked ? masked : allowed;
    const int action = from[rng() % from.size()];
    const Env::StepResult r = [&] {
      const float a = static_cast<float>(action);
      return env.step({&a, 1});
    }();
    EXPECT_EQ(r.info.primitive_status == kPrecondition, try_masked)
        << "step " << t << ": " << to_string(env.primitive_actions()[action]) << ": " << env.last_primitive().reason;
    (try_masked ? masked_tried : allowed_tried)++;
    mask = mask_of(r.obs);
    if (r.terminated || r.truncated) mask = mask_of(env.reset().obs);
  }
  EXPECT_GT(masked_tried, 10);
  EXPECT_GT(allowed_tried, 10);
}

TEST(ActionMask, IsBatchedByVectorEnv) {
  VectorEnvConfig vc;
  vc.env = masked_config();
  vc.num_envs = 2;
  vc.num_threads = 2;
  VectorEnv envs(vc);
  const Batch b = envs.reset(1);
  const Array& mask = (*b.obs)["action_mask"];
  EXPECT_EQ(mask.shape, (std::vector<int>{2, 7}));
  Env single(masked_config());
  EXPECT_EQ(mask_of(*b.obs, 0), mask_of(single.reset(1).obs));
  EXPECT_EQ(mask_of(*b.obs, 1), mask_of(single.reset(2).obs));
  // A step moves env 0 next to pumpkin 1; env 1 pushes from afar (a motion-planning failure).
  const std::vector<float> actions = {kNavPumpkin1, kPickPumpkin1};
  const Batch s = envs.step(actions);
  EXPECT_EQ(mask_of(*s.obs, 0)[kNavPumpkin1], 0);
  EXPECT_EQ(mask_of(*s.obs, 1), mask_of(single.reset(2).obs));
}

TEST(ActionMask, OnlyForThePrimitiveActionSpace) {
  EnvConfig c = test::box_room_config();
  c.observations = {"proprio", "action_mask"};
  EXPECT_EQ(test::error_of([&] { Env e(c); }),
            "env config: observation 'action_mask' needs the primitive action space (action_space is 'low_level')");
}

}  // namespace
}  // namespace chore
