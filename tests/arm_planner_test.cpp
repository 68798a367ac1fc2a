#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include "primitives/arm_planner.hpp"
#include "test_util.hpp"
#include "world/world.hpp"

namespace chore {
namespace {

// The reaching pose of assets/robots/tiago.xml: the gripper 0.6 m ahead at 0.8 m.
const ArmConfiguration kUntucked = {0.15, 0.74, -0.61, -0.28, 2.06, -0.63, -1.29, -0.07};

TEST(ArmPlanner, PlansFromTuckedToReachingWithoutTouchingAnything) {
  World world(Scene::load(test::box_room()));
  ASSERT_FALSE(arm_in_collision(world, kUntucked));
  const ArmPath path = plan_arm_path(world, kUntucked, 7);
  ASSERT_TRUE(path.success) << path.reason;
  ASSERT_GE(path.waypoints.size(), 2u);
  EXPECT_EQ(path.waypoints.back(), kUntucked);
  EXPECT_NEAR(path.waypoints.front()[1], Robot::kTuckedArm[0], 1e-9);
  // Interpolated densely, the whole path is collision-free.
  for (size_t k = 0; k + 1 < path.waypoints.size(); ++k) {
    for (double t = 0; t <= 1.0; t += 0.05) {
      ArmConfiguration q;
      for (size_t i = 0; i < q.size(); ++i) {
        q[i] = (1 - t) * path.waypoints[k][i] + t * path.waypoints[k + 1][i];
      }
      EXPECT_FALSE(arm_in_collision(world, q)) << "segment " << k << " t " << t;
    }
  }
}

TEST(ArmPlanner, AGoalInsideAnObstacleIsRefused) {
  World world(Scene::load(test::box_room()));
  // Base 0.45 m from the red panel's face (x = 2.45): the reaching arm goes through it.
  Pose2 base = world.scene().robot_start();
  base.x = 2.0;
  world.reset(base);
  EXPECT_TRUE(arm_in_collision(world, kUntucked));
  const ArmPath path = plan_arm_path(world, kUntucked, 7);
  EXPECT_FALSE(path.success);
  EXPECT_EQ(path.reason, "the arm's goal configuration is in collision");
}

}  // namespace
}  // namespace chore
