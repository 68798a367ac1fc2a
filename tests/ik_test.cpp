#include <gtest/gtest.h>
#include <mujoco/mujoco.h>
#include <algorithm>

#include "primitives/ik.hpp"
#include "primitives/motion.hpp"
#include "test_util.hpp"
#include "world/world.hpp"

namespace chore {
namespace {

// Applies an IK solution (torso, arm) to the world and returns the site position.
Eigen::Vector3d set_arm(World& w, const ArmConfiguration& joints) {
  const Robot& r = *w.robot();
  w.data()->qpos[r.torso.qpos] = joints[0];
  for (int i = 0; i < Robot::kArmJoints; ++i) w.data()->qpos[r.arm[i].qpos] = joints[1 + i];
  mj_forward(w.model(), w.data());
  const double* p = w.data()->site_xpos + 3 * r.gripper_site;
  return {p[0], p[1], p[2]};
}

TEST(Ik, ReachesAPoseInFrontFromTheTuckedArm) {
  auto scene = Scene::load(test::box_room());
  World world(scene);  // robot at the origin, facing +x, arm tucked
  const Eigen::Vector3d before = set_arm(world, arm_configuration(world));
  IkTarget target{Eigen::Vector3d(0.6, 0.0, 0.8), Eigen::Vector3d(1, 0, 0)};
  const IkResult r = solve_ik(world, target);
  ASSERT_TRUE(r.success) << r.reason;
  EXPECT_LT(r.position_error, 0.005);
  EXPECT_LT(r.angle_error, 0.05);
  // The world is untouched by solving; applying the solution gets there.
  const double* now = world.data()->site_xpos + 3 * world.robot()->gripper_site;
  EXPECT_NEAR(now[0], before.x(), 1e-9);
  EXPECT_LT((set_arm(world, r.joints) - target.position).norm(), 0.005);
  // Within the joint limits.
  const Robot& robot = *world.robot();
  EXPECT_GE(r.joints[0], robot.torso.low);
  EXPECT_LE(r.joints[0], robot.torso.high);
  for (int i = 0; i < Robot::kArmJoints; ++i) {
    EXPECT_GE(r.joints[1 + i], robot.arm[i].low);
    EXPECT_LE(r.joints[1 + i], robot.arm[i].high);
  }
}

TEST(Ik, APointAboveATableWithTheGripperPointingDown) {
  World world(Scene::load(test::box_room()));
  const IkResult r = solve_ik(world, {Eigen::Vector3d(0.55, -0.1, 0.9), Eigen::Vector3d(0, 0, -1)});
  ASSERT_TRUE(r.success) << r.reason;
  EXPECT_LT((set_arm(world, r.joints) - Eigen::Vector3d(0.55, -0.1, 0.9)).norm(), 0.005);
}

// The arm's envelope, what reach checks of BEHAVIOR-1K's activities meet
// (docs/activities.md). From the untucked start alone, damped least squares
// points the hand down from 0.2 m to 1.0 m above the floor only: lower and
// higher it stops in a local minimum (at 1.15 m with the torso all the way
// up), where the arm reaches from one of reach()'s other starts: pointing
// down, 0.1 m above the floor (what lies on it) and 1.15 m (what stands on a
// 0.9 m counter, from above).
TEST(Ik, ThreeStartsReachFromTheFloorToAboveACounter) {
  World world(Scene::load(test::box_room()));
  const auto from = [&](const ArmConfiguration& start, const Eigen::Vector3d& at) {
    IkOptions options;
    options.start = start;
    options.iterations = 100;  // as reach() solves
    return solve_ik(world, {at, Eigen::Vector3d(0, 0, -1)}, options);
  };
  const auto from_any = [&](const Eigen::Vector3d& at) {
    return std::any_of(kReachStarts.begin(), kReachStarts.end(),
                       [&](const ArmConfiguration& s) { return from(s, at).success; });
  };
  ASSERT_EQ(kReachStarts[0], kUntuckedConfiguration);
  EXPECT_TRUE(from(kUntuckedConfiguration, {0.6, 0, 1.0}).success);
  const IkResult high = from(kUntuckedConfiguration, {0.6, 0, 1.15});
  EXPECT_FALSE(high.success);
  EXPECT_GT(high.position_error, 0.05);
  EXPECT_NEAR(high.joints[0], world.robot()->torso.high, 1e-6) << "the torso as high as it goes";
  EXPECT_FALSE(from(kUntuckedConfiguration, {0.45, 0, 0.1}).success);
  EXPECT_TRUE(from_any({0.6, 0, 1.15}));
  EXPECT_TRUE(from_any({0.45, 0, 0.1}));
  EXPECT_FALSE(from_any({0.6, 0, 1.4})) << "above the envelope";
  EXPECT_FALSE(from_any({0.45, 0, 0.0})) << "the hand's centre on the floor";
}

// Why pick also approaches from the side: the hand pointing forward reaches
// farther out at counter height than pointing down.
TEST(Ik, SideReachesFartherThanFromAbove) {
  World world(Scene::load(test::box_room()));
  const auto from_any = [&](const Eigen::Vector3d& at, const Eigen::Vector3d& approach) {
    return std::any_of(kReachStarts.begin(), kReachStarts.end(), [&](const ArmConfiguration& s) {
      IkOptions options;
      options.start = s;
      options.iterations = 100;  // as reach() solves
      return solve_ik(world, {at, approach}, options).success;
    });
  };
  const Eigen::Vector3d down(0, 0, -1), forward(1, 0, 0);
  EXPECT_TRUE(from_any({0.6, 0, 1.0}, down));
  EXPECT_FALSE(from_any({0.9, 0, 1.0}, down));
  EXPECT_TRUE(from_any({0.9, 0, 1.0}, forward));
  EXPECT_TRUE(from_any({0.9, 0, 0.7}, forward));
  EXPECT_FALSE(from_any({1.2, 0, 1.0}, forward)) << "beyond the arm's length";
}

TEST(Ik, UnreachableTargetsFailWithAReason) {
  World world(Scene::load(test::box_room()));
  const IkResult r = solve_ik(world, {Eigen::Vector3d(2.5, 0, 0.8), std::nullopt});
  EXPECT_FALSE(r.success);
  EXPECT_GT(r.position_error, 1.0);
  EXPECT_NE(r.reason.find("no arm configuration reaches the target"), std::string::npos);
}

TEST(Ik, AClosingAxisTargetTurnsTheFingersLine) {
  World world(Scene::load(test::box_room()));
  // Hand forward at the untucked point, fingers closing vertically (a drawer handle's grip).
  const IkTarget target{Eigen::Vector3d(0.6, 0.0, 0.8), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1)};
  const IkResult r = solve_ik(world, target);
  ASSERT_TRUE(r.success) << r.reason;
  set_arm(world, r.joints);
  const double* m = world.data()->site_xmat + 9 * world.robot()->gripper_site;
  EXPECT_GT(m[0], 0.99);            // x axis (approach) along world x
  EXPECT_GT(std::abs(m[7]), 0.99);  // y axis (closing) along world z
}

TEST(Ik, ASolverSolvesFromAnotherBasePoseWithoutMovingTheWorld) {
  World world(Scene::load(test::box_room()));
  IkSolver solver(world);
  IkOptions options;
  options.base = Pose2{1.0, 0.0, 0.0};
  // 0.6 m ahead of a base standing at x = 1: reachable from there, not from the origin.
  const IkTarget target{Eigen::Vector3d(1.6, 0.0, 0.8), Eigen::Vector3d(1, 0, 0)};
  EXPECT_TRUE(solver.solve(target, options).success);
  EXPECT_FALSE(solver.solve(target).success);
  EXPECT_EQ(world.base_pose().x, 0.0);
}

}  // namespace
}  // namespace chore
