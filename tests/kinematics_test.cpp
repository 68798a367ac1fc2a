// The robot's own kinematics and the collision checker built on it, against
// MuJoCo's answers for the whole scene (mj_kinematics, mj_jacSite, mj_collision).
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <random>

#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "primitives/arm_planner.hpp"
#include "primitives/kinematics.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

// Random configurations within the joint limits, the base near where it starts.
struct Sampler {
  std::mt19937_64 rng{7};
  std::uniform_real_distribution<double> unit{0.0, 1.0};
  ArmConfiguration arm(const Robot& r) {
    ArmConfiguration q;
    const auto joints = r.torso_and_arm();
    for (size_t k = 0; k < joints.size(); ++k) q[k] = joints[k]->low + unit(rng) * (joints[k]->high - joints[k]->low);
    return q;
  }
  Pose2 base(const Pose2& near, double spread) {
    return {near.x + spread * (unit(rng) - 0.5), near.y + spread * (unit(rng) - 0.5), 8 * (unit(rng) - 0.5)};
  }
};

Env make_env(const std::string& activity) {
  EnvConfig config;
  config.activity = activity;
  config.observations = {"is_grasping"};
  config.action_space = "primitives";
  config.primitive_mode = ExecutionMode::symbolic;
  return Env(config);
}

TEST(RobotKinematics, PlacesTheRobotAndItsLoadAsMujocoDoes) {
  Env env = make_env("store_decoration");
  env.reset(1);
  World& w = env.impl().world();
  const Robot& r = *w.robot();
  // Carry a pumpkin: its geoms move with the hand.
  const int pumpkin = env.activity()->object("pumpkin.n.02_1");
  ASSERT_TRUE(w.hold(pumpkin));
  RobotKinematics kinematics(w);
  ASSERT_FALSE(kinematics.load_geoms().empty());
  Sampler sample;
  const Pose2 start = w.base_pose();
  for (int t = 0; t < 20; ++t) {
    const Pose2 base = sample.base(start, 1.0);
    const ArmConfiguration q = sample.arm(r);
    kinematics.set(base, q);
    w.set_robot_configuration(base, q.data());  // mj_kinematics, the load carried, mj_forward
    const double* site = w.data()->site_xpos + 3 * r.gripper_site;
    EXPECT_LT((kinematics.site_position() - Eigen::Vector3d(site[0], site[1], site[2])).norm(), 1e-9);
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> rotation(w.data()->site_xmat +
                                                                                  9 * r.gripper_site);
    EXPECT_LT((kinematics.site_rotation() - rotation).norm(), 1e-9);
    for (const std::vector<int>* geoms : {&kinematics.robot_geoms(), &kinematics.load_geoms()}) {
      for (int g : *geoms) {
        double pos[3], mat[9];
        kinematics.geom_pose(g, pos, mat);
        for (int i = 0; i < 3; ++i) EXPECT_NEAR(pos[i], w.data()->geom_xpos[3 * g + i], 1e-9) << "geom " << g;
        for (int i = 0; i < 9; ++i) EXPECT_NEAR(mat[i], w.data()->geom_xmat[9 * g + i], 1e-9) << "geom " << g;
      }
    }
  }
}

TEST(RobotKinematics, SiteJacobianMatchesMujocos) {
  Env env = make_env("store_decoration");
  env.reset(2);
  World& w = env.impl().world();
  const Robot& r = *w.robot();
  RobotKinematics kinematics(w);
  Sampler sample;
  std::vector<double> jacp(3 * w.model()->nv), jacr(3 * w.model()->nv);
  for (int t = 0; t < 10; ++t) {
    const Pose2 base = sample.base(w.base_pose(), 0.5);
    const ArmConfiguration q = sample.arm(r);
    kinematics.set(base, q);
    w.set_robot_configuration(base, q.data());
    mj_jacSite(w.model(), w.data(), jacp.data(), jacr.data(), r.gripper_site);
    const auto jac = kinematics.site_jacobian();
    const auto joints = r.torso_and_arm();
    for (size_t k = 0; k < joints.size(); ++k) {
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(jac(i, static_cast<Eigen::Index>(k)), jacp[i * w.model()->nv + joints[k]->dof], 1e-9);
        EXPECT_NEAR(jac(3 + i, static_cast<Eigen::Index>(k)), jacr[i * w.model()->nv + joints[k]->dof], 1e-9);
      }
    }
  }
}

// MuJoCo's verdict: the robot (or its load) in contact with anything else
// after mj_collision over the whole scene.
bool mujoco_says_collides(const World& w, int load_body) {
  const mjModel* m = w.model();
  const mjData* d = w.data();
  const int robot = m->body_rootid[w.robot()->gripper_body];
  for (int c = 0; c < d->ncon; ++c) {
    const int r1 = m->body_rootid[m->geom_bodyid[d->contact[c].geom[0]]];
    const int r2 = m->body_rootid[m->geom_bodyid[d->contact[c].geom[1]]];
    const bool mine1 = r1 == robot || r1 == load_body, mine2 = r2 == robot || r2 == load_body;
    if (mine1 != mine2) return true;
  }
  return false;
}

TEST(ArmCollisionChecker, AgreesWithMujocosCollisionDetection) {
  for (const std::string activity : {"store_decoration", "clean_table"}) {
    Env env = make_env(activity);
    env.reset(3);
    World& w = env.impl().world();
    const Robot& r = *w.robot();
    Sampler sample;
    int collisions = 0, trials = 0;
    const Pose2 start = w.base_pose();
    for (int t = 0; t < 150; ++t) {
      // Around the start pose, where walls and furniture are near.
      const Pose2 base = sample.base(start, 1.5);
      const ArmConfiguration q = sample.arm(r);
      const ArmConfiguration now = arm_configuration(w);
      w.set_robot_configuration(base, now.data());
      ArmCollisionChecker checker(w);
      const bool fast = checker.collides(q.data());
      w.set_robot_configuration(base, q.data());
      mj_collision(w.model(), w.data());
      EXPECT_EQ(fast, mujoco_says_collides(w, -1)) << activity << " trial " << t;
      collisions += fast;
      ++trials;
    }
    // Both verdicts occur, so the agreement means something.
    EXPECT_GT(collisions, trials / 10) << activity;
    EXPECT_LT(collisions, trials * 9 / 10) << activity;
  }
}

// A clearance counts what comes within it as touching, for what the torso and
// arm move only: the base stands on the floor whatever the clearance.
TEST(ArmCollisionChecker, AClearanceAppliesToWhatTheArmMoves) {
  Env env = make_env("store_decoration");
  env.reset(1);
  const World& w = env.world();
  const ArmConfiguration tucked = arm_configuration(w);
  ArmCollisionChecker checker(w);
  EXPECT_FALSE(checker.collides(tucked.data()));
  EXPECT_FALSE(checker.collides(tucked.data(), nullptr, 0.015));  // the base's contact with the floor does not count
  EXPECT_TRUE(checker.collides(tucked.data(), nullptr, 3.0));     // a wall or furniture within 3 m of the arm
}

}  // namespace
}  // namespace chore
