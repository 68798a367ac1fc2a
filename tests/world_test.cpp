#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstring>
#include <random>

#include "base/error.hpp"
#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "test_util.hpp"
#include "world/mujoco_errors.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

EnvConfig box_room_config() {
  EnvConfig c = test::box_room_config();
  c.observations = {"proprio", "is_grasping"};
  return c;
}

TEST(MujocoErrors, ErrorsBecomeChoreErrorsNotExit) {
  install_mujoco_handlers();
  EXPECT_THROW(mju_error("boom"), Error);
  // A real failure inside the engine: the data stack overflows.
  auto scene = Scene::load(test::box_room());
  mjData* d = mj_makeData(scene->model());
  EXPECT_THROW(mj_stackAllocNum(d, d->narena), Error);
  mj_deleteData(d);
}

TEST(World, DivergingSimulationTruncatesWithAFlag) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  const SceneObject* block = w.scene().find_object("small_block_1");
  const int dof = w.model()->jnt_dofadr[w.model()->body_jntadr[block->body]];
  w.data()->qvel[dof] = 1e30;  // beyond mjMAXVAL: MuJoCo resets and warns
  std::vector<float> zero(kLowLevelActionSize, 0.f);
  auto step = env.step(zero);
  EXPECT_TRUE(step.truncated);
  EXPECT_FALSE(step.terminated);
  EXPECT_TRUE(step.info.diverged);
  EXPECT_THROW(env.step(zero), Error);  // must reset first
  EXPECT_FALSE(env.reset(0).info.diverged);
}

// A MuJoCo error inside a step (seen in training: "xaxis of contact frame
// undefined", a degenerate contact normal) ends the episode as a divergence
// instead of the run, and leaves the model whole: no sleeper stays masked.
void fail_mid_step(const mjModel*, mjData*) {
  mju_error("injected failure");
}

TEST(World, AMuJoCoErrorMidStepTruncatesLikeADivergence) {
  Env env(box_room_config());
  env.reset(0);
  std::vector<float> zero(kLowLevelActionSize, 0.f);
  for (int i = 0; i < 10; ++i) env.step(zero);  // the blocks fall asleep
  const World& w = env.world();
  const std::vector<int> geoms(w.model()->body_geomnum, w.model()->body_geomnum + w.model()->nbody);
  const int ngeom = w.model()->ngeom;
  mjcb_control = fail_mid_step;
  const Env::StepResult step = [&] {
    struct Restore {
      ~Restore() { mjcb_control = nullptr; }
    } restore;
    return env.step(zero);
  }();
  EXPECT_TRUE(step.truncated);
  EXPECT_TRUE(step.info.diverged);
  EXPECT_EQ(std::vector<int>(w.model()->body_geomnum, w.model()->body_geomnum + w.model()->nbody), geoms);
  EXPECT_EQ(w.model()->ngeom, ngeom);
  // The next episode runs as one that never failed.
  env.reset(0);
  const auto first = env.step(zero);
  Env fresh(box_room_config());
  fresh.reset(0);
  const auto reference = fresh.step(zero);
  EXPECT_FALSE(first.info.diverged);
  const Array& a = first.obs["proprio"];
  const Array& b = reference.obs["proprio"];
  EXPECT_EQ(std::memcmp(a.item(0), b.item(0), a.item_bytes()), 0);
}

// MuJoCo resets a diverging state inside mj_step and goes on with the step:
// what the rest of that step makes of it must not reach the episode. The step
// ends in MuJoCo's reset state, every geom posed, as a fresh reset gives it.
TEST(World, ADivergedStepEndsInMuJoCosResetStatePosedOverTheWholeModel) {
  auto scene = Scene::load(test::data_path("scenes/predicate_room.json"));
  World w(scene);
  const mjModel* m = w.model();
  const SceneObject& apple = *scene->find_object("apple_1");
  w.data()->qvel[m->jnt_dofadr[m->body_jntadr[apple.body]]] = 1e30;  // beyond mjMAXVAL
  const World::StepReport report = w.step(1);
  ASSERT_TRUE(report.diverged);
  mjData* fresh = mj_makeData(m);
  mj_kinematics(m, fresh);
  const mjData* d = w.data();
  const auto same = [](const double* a, const double* b, int n) { return std::memcmp(a, b, sizeof(double) * n) == 0; };
  EXPECT_TRUE(same(d->qpos, fresh->qpos, m->nq));
  EXPECT_TRUE(same(d->qvel, fresh->qvel, m->nv));
  EXPECT_EQ(d->time, 0.0);
  for (int g = 0; g < m->ngeom; ++g) {
    EXPECT_TRUE(same(d->geom_xpos + 3 * g, fresh->geom_xpos + 3 * g, 3)) << "geom " << g;
    EXPECT_TRUE(same(d->geom_xmat + 9 * g, fresh->geom_xmat + 9 * g, 9)) << "geom " << g;
  }
  mj_deleteData(fresh);
}

// Reaching pose of assets/robots/tiago.xml: the gripper 0.6 m in front at
// 0.8 m height, pointing forward, fingers opening horizontally.
void untuck(World& w) {
  const Robot& r = *w.robot();
  const double torso = 0.15;
  const double arm[Robot::kArmJoints] = {0.74, -0.61, -0.28, 2.06, -0.63, -1.29, -0.07};
  w.data()->qpos[r.torso.qpos] = torso;
  w.command_position(r.torso, torso);
  for (int i = 0; i < Robot::kArmJoints; ++i) {
    w.data()->qpos[r.arm[i].qpos] = arm[i];
    w.command_position(r.arm[i], arm[i]);
  }
  mj_forward(w.model(), w.data());
}

// Puts a free object between the open fingers of the reaching arm, with
// gravity off so that it stays there while the gripper closes.
int place_between_fingers(World& w, const char* name) {
  untuck(w);
  const SceneObject* o = w.scene().find_object(name);
  const mjModel* m = w.model();
  const int qpos = m->jnt_qposadr[m->body_jntadr[o->body]];
  const double* site = w.data()->site_xpos + 3 * w.robot()->gripper_site;
  // The model origin is the block's bottom centre: lower it by its half height.
  w.data()->qpos[qpos + 0] = site[0];
  w.data()->qpos[qpos + 1] = site[1];
  w.data()->qpos[qpos + 2] = site[2] - 0.025;
  w.model()->opt.gravity[2] = 0;
  mj_forward(w.model(), w.data());
  return o->body;
}

std::vector<float> gripper_action(float gripper, float torso = 0) {
  std::vector<float> a(kLowLevelActionSize, 0.f);
  a[11] = gripper;
  a[3] = torso;
  return a;
}

TEST(World, AssistiveGraspHoldsAnObjectBothFingersTouchUntilOpened) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  const int body = place_between_fingers(w, "small_block_1");
  for (int i = 0; i < 15 && w.grasped_object() < 0; ++i) env.step(gripper_action(-1));
  ASSERT_GE(w.grasped_object(), 0);
  EXPECT_EQ(w.scene().objects()[w.grasped_object()].name, "small_block_1");
  EXPECT_TRUE(attached(w, w.grasped_object(), -1));  // connected to the robot by the weld
  EXPECT_EQ(env.step(gripper_action(-1)).obs["is_grasping"].data<float>()[0], 1.0f);
  // With gravity back, the held block moves with the hand as the torso rises.
  w.model()->opt.gravity[2] = -9.81;
  const double* hand = w.data()->xpos + 3 * w.robot()->gripper_body;
  const double* obj = w.data()->xpos + 3 * body;
  const double offset_before = obj[2] - hand[2], z_before = obj[2];
  for (int i = 0; i < 30; ++i) env.step(gripper_action(-1, 1));
  EXPECT_GT(obj[2] - z_before, 0.05);  // lifted with the torso
  EXPECT_NEAR(obj[2] - hand[2], offset_before, 0.01);
  // Opening releases it and it falls.
  const double z_held = obj[2];
  for (int i = 0; i < 30; ++i) env.step(gripper_action(1));
  EXPECT_LT(w.grasped_object(), 0);
  EXPECT_FALSE(attached(w, static_cast<int>(w.scene().find_object("small_block_1") - w.scene().objects().data()), -1));
  EXPECT_LT(obj[2], 0.1) << "held at " << z_held;  // on the floor
}

TEST(World, ObjectsOverTheMassLimitAreRefused) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  place_between_fingers(w, "heavy_block_1");
  bool refused = false;
  for (int i = 0; i < 15; ++i) refused |= env.step(gripper_action(-1)).info.grasp_refused;
  EXPECT_TRUE(refused);
  EXPECT_LT(w.grasped_object(), 0);
}

// The free joint's position of an object: x, y, z, then the quaternion.
const double* object_qpos(const World& w, const char* name) {
  const mjModel* m = w.model();
  return w.data()->qpos + m->jnt_qposadr[m->body_jntadr[w.scene().find_object(name)->body]];
}

int object_index(const World& w, const char* name) {
  return static_cast<int>(w.scene().find_object(name) - w.scene().objects().data());
}

// The object's contacts: those in MuJoCo's list (kept = false), or the
// resting contacts World keeps for it while it sleeps (kept = true).
int contacts_of(const World& w, const char* name, bool kept) {
  const int object = object_index(w, name);
  const auto mine = [&](const mjContact& con) {
    return w.scene().object_of_geom(con.geom[0]) == object || w.scene().object_of_geom(con.geom[1]) == object;
  };
  int n = 0;
  if (kept) {
    w.resting_contacts().for_each(w.model(), w.data(), [&](const mjContact& con) { n += mine(con); });
    return n;
  }
  for (int c = 0; c < w.data()->ncon; ++c) n += mine(w.data()->contact[c]);
  return n;
}

// MuJoCo's sleeping (3.4 on), as chore uses it: the scene's objects start
// asleep where they were placed and stay exactly there; MuJoCo computes none
// of their contacts, and World keeps those they rest on, which contact
// predicates read.
TEST(Sleeping, TheScenesObjectsStartAsleepAndKeepTheirRestingContacts) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  const int block = object_index(w, "small_block_1");
  ASSERT_TRUE(w.asleep(block));
  EXPECT_TRUE(w.asleep(object_index(w, "heavy_block_1")));
  EXPECT_FALSE(w.asleep(object_index(w, "red_panel_1")));  // furniture in the world body: no tree to sleep
  const std::vector<double> rest(object_qpos(w, "small_block_1"), object_qpos(w, "small_block_1") + 7);
  w.step(60);
  EXPECT_TRUE(w.asleep(block));
  for (int k = 0; k < 7; ++k) EXPECT_EQ(object_qpos(w, "small_block_1")[k], rest[k]) << k;  // held exactly
  EXPECT_EQ(contacts_of(w, "small_block_1", false), 0);
  const int resting = contacts_of(w, "small_block_1", true);
  EXPECT_GT(resting, 0);
  EXPECT_TRUE(onfloor(w, block, 0));  // contact predicates read the kept ones

  w.set_sleeping(false);  // everyone awake, every contact computed again
  EXPECT_EQ(w.sleepers(), 0);
  EXPECT_EQ(contacts_of(w, "small_block_1", true), 0);
  EXPECT_EQ(contacts_of(w, "small_block_1", false), resting);
  EXPECT_TRUE(onfloor(w, block, 0));
  w.step(30);
  EXPECT_FALSE(w.asleep(block));
  w.set_sleeping(true);  // still, it falls asleep again after mjMINAWAKE steps
  w.step(30);
  EXPECT_TRUE(w.asleep(block));
  EXPECT_EQ(contacts_of(w, "small_block_1", true), resting);
}

// The scene compiler lets the placed objects settle once (Scene): each comes
// to rest where it was put, on the furniture it was put on, and sleeps there.
TEST(Sleeping, ThePlacedObjectsRestWhereTheyWerePutAndSleep) {
  for (const char* name : {"apartment", "restaurant"}) {
    World w(Scene::load(name));
    w.reset(Pose2{});
    const mjData* d = w.data();
    int free = 0;
    for (size_t i = 0; i < w.scene().objects().size(); ++i) {
      const SceneObject& o = w.scene().objects()[i];
      if (o.fixed || !o.keypoints.empty()) continue;  // furniture, cloths
      ++free;
      EXPECT_TRUE(w.asleep(static_cast<int>(i))) << name << ": " << o.name;
      const double* x = d->xpos + 3 * o.body;
      EXPECT_LT(std::hypot(x[0] - o.pos[0], x[1] - o.pos[1], x[2] - o.pos[2]), 0.005) << name << ": " << o.name;
    }
    EXPECT_GT(free, 20) << name;
  }
}

TEST(Sleeping, AnObjectMovedIntoTheAirWakesFallsAndSleepsAgain) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  const int block = object_index(w, "small_block_1");
  ASSERT_TRUE(w.asleep(block));
  // A sampler's move: 30 cm up, still. MuJoCo wakes a sleeper whose joints
  // moved; an object in the air is not at rest: it falls to the floor, then sleeps.
  double* q = w.data()->qpos + (object_qpos(w, "small_block_1") - w.data()->qpos);
  const double floor_z = q[2];
  q[2] += 0.3;
  mj_forward(w.model(), w.data());
  EXPECT_FALSE(w.asleep(block));
  EXPECT_FALSE(onfloor(w, block, 0));  // its kept contacts no longer count
  w.step(1);
  EXPECT_FALSE(w.asleep(block));
  w.step(120);
  EXPECT_NEAR(object_qpos(w, "small_block_1")[2], floor_z, 0.005);
  EXPECT_TRUE(w.asleep(block));
  EXPECT_GT(contacts_of(w, "small_block_1", true), 0);
  EXPECT_TRUE(onfloor(w, block, 0));
}

TEST(Sleeping, AMovingObjectWakesWhatItHits) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  ASSERT_TRUE(w.asleep(object_index(w, "heavy_block_1")));  // at (-2, 2), 25 kg
  // Slide the small block along the floor at it, 15 cm between their faces.
  const mjModel* m = w.model();
  const int small = w.scene().find_object("small_block_1")->body;
  double* q = w.data()->qpos + m->jnt_qposadr[m->body_jntadr[small]];
  q[0] = -2.0, q[1] = 1.8;
  w.data()->qvel[m->jnt_dofadr[m->body_jntadr[small]] + 1] = 2.0;
  mj_forward(w.model(), w.data());
  bool woken = false;
  for (int k = 0; k < 60; ++k) {
    w.step(1);
    woken |= !w.asleep(object_index(w, "heavy_block_1"));
  }
  EXPECT_TRUE(woken);  // when the blocks met (both may sleep again since)
  // The small one stopped at the heavy one's face (5 cm cubes, centres 5 cm
  // apart) instead of passing through it.
  EXPECT_LT(object_qpos(w, "small_block_1")[1], object_qpos(w, "heavy_block_1")[1] - 0.045);
  EXPECT_GT(object_qpos(w, "small_block_1")[1], 1.85);
}

TEST(World, ZeroActionHoldsTheRobotStill) {
  Env env(box_room_config());
  auto start = env.reset(0);
  std::vector<float> before(start.obs["proprio"].data<float>(), start.obs["proprio"].data<float>() + 30);
  std::vector<float> zero(kLowLevelActionSize, 0.f);
  const float* p = nullptr;
  for (int i = 0; i < 90; ++i) p = env.step(zero).obs["proprio"].data<float>();
  for (int k : {0, 1, 2, 3}) EXPECT_NEAR(p[k], before[k], 1e-3) << "base " << k;
  for (int k = 7; k < 17; ++k) EXPECT_NEAR(p[k], before[k], 0.01) << "joint " << k;
}

TEST(World, BaseVelocityActionDrivesTheRobot) {
  Env env(box_room_config());
  env.reset(0);
  std::vector<float> forward(kLowLevelActionSize, 0.f);
  forward[0] = 1.0f;  // 0.5 m/s
  const float* p = nullptr;
  for (int i = 0; i < 30; ++i) p = env.step(forward).obs["proprio"].data<float>();
  EXPECT_NEAR(p[0], 0.5, 0.08);  // one second forward along +x
  EXPECT_NEAR(p[1], 0.0, 0.02);
  EXPECT_NEAR(p[4], 0.5, 0.05);  // forward velocity in the robot frame
}

}  // namespace
}  // namespace chore
