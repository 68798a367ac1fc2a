#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cstring>
#include <random>

#include "base/error.hpp"
#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "test_util.hpp"
#include "world/mujoco_errors.hpp"
#include "world/pair_early_outs.hpp"
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
  d->pstack = d->nstack - 4;
  EXPECT_THROW(mj_stackAlloc(d, 1000), Error);
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

// MuJoCo resets a diverging state inside mj_step, where the static geoms are
// left out of kinematics: the rest of that step collides with their zeroed
// poses (degenerate boxes at the origin). What a pair function makes of those
// must not reach the episode: the step ends in MuJoCo's reset state, every
// geom posed, as a fresh reset gives it (seen: an early-out and MuJoCo's own
// function disagreeing on such a box changed a training run).
TEST(World, ADivergedStepEndsInMuJoCosResetStatePosedOverTheWholeModel) {
  auto scene = Scene::load(test::data_path("scenes/predicate_room.json"));
  World w(scene);
  const mjModel* m = w.model();
  ASSERT_LT(scene->first_static_geom(), m->ngeom);
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

// The object's contacts in the list: those physics computed, and the resting
// contacts sleeping keeps for it (efc_address Sleeping::kKeptContact).
int contacts_of(const World& w, const char* name, bool kept) {
  const int object = object_index(w, name);
  int n = 0;
  for (int c = 0; c < w.data()->ncon; ++c) {
    const mjContact& con = w.data()->contact[c];
    const bool mine = w.scene().object_of_geom(con.geom1) == object || w.scene().object_of_geom(con.geom2) == object;
    n += mine && (con.efc_address == Sleeping::kKeptContact) == kept;
  }
  return n;
}
bool in_contact_list(const World& w, const char* name) {
  return contacts_of(w, name, false) > 0;
}

TEST(Sleeping, ObjectsAtRestAwayFromTheRobotSleepStillAndKeepTheirContacts) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  w.set_sleeping(false);
  // A block 0.45 m in front of the robot (within its reach) and one 2.8 m away.
  double* near = w.data()->qpos + (object_qpos(w, "heavy_block_1") - w.data()->qpos);
  near[0] = 0.45, near[1] = 0;
  mj_forward(w.model(), w.data());
  w.step(60);  // both come to rest on the floor
  const int resting = contacts_of(w, "small_block_1", false);
  ASSERT_GT(resting, 0);

  w.set_sleeping(true);
  w.step(60);
  ASSERT_TRUE(w.asleep(object_index(w, "small_block_1")));
  const std::vector<double> far_rest(object_qpos(w, "small_block_1"), object_qpos(w, "small_block_1") + 7);
  w.step(60);
  EXPECT_TRUE(w.asleep(object_index(w, "small_block_1")));
  EXPECT_TRUE(w.asleep(object_index(w, "red_panel_1")));     // furniture nothing moves near
  EXPECT_FALSE(w.asleep(object_index(w, "heavy_block_1")));  // within the robot's region
  EXPECT_EQ(w.sleepers(), 3);
  for (int k = 0; k < 7; ++k) EXPECT_EQ(object_qpos(w, "small_block_1")[k], far_rest[k]) << k;  // held exactly
  // Out of collision detection, its resting contacts kept: the same number,
  // with no force in the solver.
  EXPECT_EQ(contacts_of(w, "small_block_1", false), 0);
  EXPECT_EQ(contacts_of(w, "small_block_1", true), resting);
  for (int c = 0; c < w.data()->ncon; ++c) {
    if (w.data()->contact[c].efc_address != Sleeping::kKeptContact) continue;
    double force[6];
    mj_contactForce(w.model(), w.data(), c, force);
    EXPECT_EQ(force[0], 0.0);
  }
  EXPECT_TRUE(in_contact_list(w, "heavy_block_1"));
  EXPECT_TRUE(onfloor(w, object_index(w, "small_block_1"), 0));  // contact predicates read the kept ones

  w.set_sleeping(false);  // everyone awake, every contact computed again
  EXPECT_EQ(w.sleepers(), 0);
  EXPECT_EQ(contacts_of(w, "small_block_1", false), resting);
  EXPECT_EQ(contacts_of(w, "small_block_1", true), 0);
}

TEST(Sleeping, AnObjectLetGoInTheAirFallsBeforeItSleeps) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  w.step(120);
  ASSERT_TRUE(w.asleep(object_index(w, "small_block_1")));
  // A sampler's move: 30 cm up, still. The sleeper wakes, and an object
  // still in the air is not at rest: it falls to the floor, then sleeps.
  double* block = w.data()->qpos + (object_qpos(w, "small_block_1") - w.data()->qpos);
  const double floor_z = block[2];
  block[2] += 0.3;
  mj_forward(w.model(), w.data());
  w.step(1);
  EXPECT_FALSE(w.asleep(object_index(w, "small_block_1")));
  w.step(120);
  EXPECT_NEAR(object_qpos(w, "small_block_1")[2], floor_z, 0.005);
  EXPECT_TRUE(w.asleep(object_index(w, "small_block_1")));
  EXPECT_GT(contacts_of(w, "small_block_1", true), 0);
}

TEST(Sleeping, AnObjectKeptAwakeThenPutInTheAirFallsBeforeItSleeps) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  const int block_index = object_index(w, "small_block_1");
  double* block = w.data()->qpos + (object_qpos(w, "small_block_1") - w.data()->qpos);
  const double floor_z = block[2], x = block[0], y = block[1];
  // Still beside the robot: awake (its region), however long it rests.
  const Pose2 base = w.base_pose();
  block[0] = base.x + 0.45 * std::cos(base.yaw);
  block[1] = base.y + 0.45 * std::sin(base.yaw);
  mj_forward(w.model(), w.data());
  w.step(120);
  ASSERT_FALSE(w.asleep(block_index));
  // A sampler puts it back where it was, 30 cm up: away from the robot and
  // still, but not at rest. It falls, then sleeps.
  block[0] = x, block[1] = y, block[2] = floor_z + 0.3;
  mj_forward(w.model(), w.data());
  w.step(1);
  EXPECT_FALSE(w.asleep(block_index));
  w.step(120);
  EXPECT_NEAR(object_qpos(w, "small_block_1")[2], floor_z, 0.005);
  EXPECT_TRUE(w.asleep(block_index));
}

TEST(Sleeping, StaticGeomsLeftOutOfTheStepStayPutAndStillCollide) {
  auto scene = Scene::load(test::data_path("scenes/predicate_room.json"));
  World w(scene);
  const mjModel* m = w.model();
  const int ngeom = m->ngeom, first = scene->first_static_geom();
  ASSERT_LT(first, ngeom);
  for (int g = first; g < ngeom; ++g) {
    const int b = m->geom_bodyid[g];
    EXPECT_EQ(m->body_weldid[b], 0) << g;  // never moves
    EXPECT_EQ(m->body_jntnum[b], 0) << g;
  }
  const std::vector<double> before(w.data()->geom_xpos + 3 * first, w.data()->geom_xpos + 3 * ngeom);
  // An apple let go 5 cm above the table (a static body's geoms): it lands
  // on the table top, 0.75 m, and rests there.
  const SceneObject& apple = *scene->find_object("apple_1");
  double* q = w.data()->qpos + m->jnt_qposadr[m->body_jntadr[apple.body]];
  q[0] = 1.5, q[1] = 1.5, q[2] = 0.80;
  mj_forward(w.model(), w.data());
  w.step(240);
  EXPECT_EQ(m->ngeom, ngeom);  // the full count outside a step
  EXPECT_NEAR(q[2], 0.75, 0.01);
  const int table = static_cast<int>(scene->find_object("table_1") - scene->objects().data());
  EXPECT_TRUE(ontop(w, object_index(w, "apple_1"), table));
  const std::vector<double> after(w.data()->geom_xpos + 3 * first, w.data()->geom_xpos + 3 * ngeom);
  EXPECT_EQ(before, after);
}

TEST(Sleeping, AMovingObjectWakesWhatItWouldHit) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  w.step(60);
  w.set_sleeping(true);
  w.step(4);
  ASSERT_TRUE(w.asleep(object_index(w, "heavy_block_1")));  // at (-2, 2), 25 kg
  // Slide the small block along the floor at it, 15 cm between their faces.
  w.set_sleeping(false);
  const mjModel* m = w.model();
  const int small = w.scene().find_object("small_block_1")->body;
  double* q = w.data()->qpos + m->jnt_qposadr[m->body_jntadr[small]];
  q[0] = -2.0, q[1] = 1.8;
  w.data()->qvel[m->jnt_dofadr[m->body_jntadr[small]] + 1] = 2.0;
  mj_forward(w.model(), w.data());
  w.set_sleeping(true);
  w.step(2);
  EXPECT_FALSE(w.asleep(object_index(w, "heavy_block_1")));  // woken before the blocks meet
  w.step(58);
  // The blocks met: the small one stopped at the heavy one's face (5 cm
  // cubes, centres 5 cm apart) instead of passing through it.
  EXPECT_LT(object_qpos(w, "small_block_1")[1], object_qpos(w, "heavy_block_1")[1] - 0.045);
  EXPECT_GT(object_qpos(w, "small_block_1")[1], 1.85);
}

// The degrees of freedom MuJoCo's step sees, read from inside it (mjcb_control
// runs mid-step).
int dofs_seen_in_step = 0;
void record_dofs(const mjModel* m, mjData*) {
  dofs_seen_in_step = m->nv;
}
int dofs_in_a_step(World& w) {
  mjcb_control = record_dofs;
  w.step(1);
  mjcb_control = nullptr;
  return dofs_seen_in_step;
}

TEST(Sleeping, APhysicsStepLeavesTheDofsOfTheLastSleepersOut) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  const mjModel* m = w.model();
  const int full = m->nv, nq = m->nq, njnt = m->njnt;
  const auto dof_of = [&](const char* name) {
    return m->jnt_dofadr[m->body_jntadr[w.scene().find_object(name)->body]];
  };
  const int small = dof_of("small_block_1"), heavy = dof_of("heavy_block_1");
  // The robot's dofs come first: every joint before the blocks' is the robot's.
  ASSERT_LT(small, heavy);
  for (int j = 0; j < m->njnt && m->jnt_dofadr[j] < small; ++j) {
    EXPECT_LT(w.scene().object_of_body(m->jnt_bodyid[j]), 0) << j;
  }
  w.step(120);
  ASSERT_TRUE(w.asleep(object_index(w, "small_block_1")));
  ASSERT_TRUE(w.asleep(object_index(w, "heavy_block_1")));
  EXPECT_EQ(dofs_in_a_step(w), small);  // the robot's only
  EXPECT_EQ(m->nv, full);               // the whole model outside a step
  EXPECT_EQ(m->nq, nq);
  EXPECT_EQ(m->njnt, njnt);

  // Held, the small block is kept (its grasp weld ties it to the hand); the
  // heavy one, asleep and last, is still left out.
  ASSERT_TRUE(w.hold(object_index(w, "small_block_1")));
  EXPECT_EQ(dofs_in_a_step(w), heavy);
  w.release();

  // Falling with the heavy block's dofs left out, the small block follows
  // the same steps as with everyone awake and in the step: free fall,
  // semi-implicit Euler, bit for bit.
  auto fall = [&](bool sleeping) {
    env.reset(0);
    w.step(120);
    w.set_sleeping(sleeping);
    double* q = w.data()->qpos + m->jnt_qposadr[m->body_jntadr[w.scene().find_object("small_block_1")->body]];
    q[2] += 0.3;
    mj_forward(w.model(), w.data());
    std::vector<double> z;
    for (int k = 0; k < 20; ++k) {
      if (sleeping)
        EXPECT_EQ(dofs_in_a_step(w), heavy) << k;
      else
        w.step(1);
      z.push_back(q[2]);
    }
    w.set_sleeping(true);
    return z;
  };
  const std::vector<double> cut = fall(true), whole = fall(false);
  EXPECT_EQ(cut, whole);
  const double h = m->opt.timestep, g = -m->opt.gravity[2];
  EXPECT_NEAR(whole[0] - whole[19], g * h * h * (2 + 20) * 19 / 2, 1e-9);  // sum of k g h^2, k = 2..20
}

// Each body's geoms (first, count) as MuJoCo's step sees them.
std::vector<int> geomadr_seen_in_step, geomnum_seen_in_step;
void record_geomnum(const mjModel* m, mjData*) {
  geomadr_seen_in_step.assign(m->body_geomadr, m->body_geomadr + m->nbody);
  geomnum_seen_in_step.assign(m->body_geomnum, m->body_geomnum + m->nbody);
}

TEST(World, AStepLeavesOutOnlyGeomsThatCannotCollide) {
  Env env(box_room_config());
  env.reset(0);
  World& w = env.impl().world();
  const mjModel* m = w.model();
  const std::vector<int> geomnum(m->body_geomnum, m->body_geomnum + m->nbody);
  const auto& cut = w.scene().colliding_geoms();
  ASSERT_FALSE(cut.empty());  // the robot's drawn geoms
  for (const Scene::CollidingGeoms& c : cut) {
    EXPECT_LT(w.scene().object_of_body(c.body), 0);  // the robot's
    for (int g = m->body_geomadr[c.body] + c.count; g < m->body_geomadr[c.body] + m->body_geomnum[c.body]; ++g) {
      EXPECT_EQ(m->geom_contype[g], 0) << g;
      EXPECT_EQ(m->geom_conaffinity[g], 0) << g;
    }
  }
  mjcb_control = record_geomnum;
  w.step(1);
  mjcb_control = nullptr;
  for (const Scene::CollidingGeoms& c : cut) EXPECT_EQ(geomnum_seen_in_step[c.body], c.count) << c.body;
  EXPECT_EQ(std::vector<int>(m->body_geomnum, m->body_geomnum + m->nbody), geomnum);  // all back after it
}

// A static body (2 m of furniture) near anything awake keeps in a step only
// the run of its geoms from the first to the last that an awake region meets;
// none of those left out is within 5 cm of an awake geom by MuJoCo's own pair
// functions. The restaurant with every object just woken: the robot, and the
// plates, cups and rag resting on its tables.
TEST(Sleeping, AStaticBodyKeepsOnlyTheGeomsAnAwakeRegionMeets) {
  Env env(test::primitives_config("clean_table"));
  env.reset(0);
  World& w = env.impl().world();
  const mjModel* m = w.model();
  w.set_sleeping(false);
  w.set_sleeping(true);  // all awake until they have been still for a while
  const std::vector<int> geomadr(m->body_geomadr, m->body_geomadr + m->nbody);
  const std::vector<int> geomnum(m->body_geomnum, m->body_geomnum + m->nbody);
  mjcb_control = record_geomnum;
  w.step(1);
  mjcb_control = nullptr;
  std::vector<int> awake;  // colliding geoms of the robot and of awake objects with bodies of their own
  const int robot_root = m->body_rootid[w.robot()->gripper_body];
  for (int g = 0; g < m->ngeom; ++g) {
    if (!m->geom_contype[g] && !m->geom_conaffinity[g]) continue;
    const int object = w.scene().object_of_geom(g);
    const bool moving = object >= 0 && w.scene().objects()[object].static_body < 0 && !w.asleep(object);
    if (moving || m->body_rootid[m->geom_bodyid[g]] == robot_root) awake.push_back(g);
  }
  int kept = 0, shortened = 0, left_out = 0, left_out_near = 0;
  for (int b : w.scene().static_bodies()) {
    const int first = geomadr_seen_in_step[b], count = geomnum_seen_in_step[b];
    if (count == 0) continue;  // away from every awake region: masked whole
    ++kept;
    EXPECT_GE(first, geomadr[b]);
    EXPECT_LE(first + count, geomadr[b] + geomnum[b]);
    shortened += count < geomnum[b];
    for (int g = geomadr[b]; g < geomadr[b] + geomnum[b]; ++g) {
      if (g >= first && g < first + count) continue;
      ++left_out;
      for (int a : awake) {
        const int g1 = m->geom_type[a] <= m->geom_type[g] ? a : g, g2 = g1 == a ? g : a;
        mjContact con[mjMAXCONPAIR];
        const mjfCollision collide = mjCOLLISIONFUNC[m->geom_type[g1]][m->geom_type[g2]];
        left_out_near += collide && collide(m, w.data(), con, g1, g2, 0.05) > 0;
      }
    }
  }
  EXPECT_GT(awake.size(), 100u);
  EXPECT_GT(kept, 5);
  EXPECT_GT(shortened, 0);
  EXPECT_GT(left_out, 0);
  EXPECT_EQ(left_out_near, 0);
  EXPECT_EQ(std::vector<int>(m->body_geomadr, m->body_geomadr + m->nbody), geomadr);  // all back after it
  EXPECT_EQ(std::vector<int>(m->body_geomnum, m->body_geomnum + m->nbody), geomnum);
}

// The early-outs before MuJoCo's capsule-, cylinder- and box-box functions
// change no contact: over random poses of each shape around a box, and poses
// within a hair of first touch on either side (found by bisection), with and
// without a margin, the table's function gives MuJoCo's own contacts bit for
// bit, and every pair the early-out rejects is one MuJoCo finds nothing for.
TEST(World, PairEarlyOutsGiveMuJoCosOwnContactsBitForBit) {
  install_pair_early_outs();
  const std::string xml = R"(<mujoco><worldbody>
    <geom name="table" type="box" size="0.4 0.3 0.02"/>
    <body><freejoint/><geom type="capsule" size="0.02 0.05"/></body>
    <body><freejoint/><geom type="cylinder" size="0.27 0.14"/></body>
    <body><freejoint/><geom type="box" size="0.05 0.1 0.2"/></body>
  </worldbody></mujoco>)";
  mjModel* m = load_mjcf(xml, "early-out test");
  mjData* d = mj_makeData(m);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  int contacts = 0, rejected = 0, none = 0;
  // Geom g (body g - 1) against the table: MuJoCo's contact count.
  const auto check = [&](int g, double margin) {
    mjContact ours[mjMAXCONPAIR], theirs[mjMAXCONPAIR];
    std::memset(ours, 0, sizeof(ours));
    std::memset(theirs, 0, sizeof(theirs));
    const int type = m->geom_type[g];
    const int n = mjCOLLISIONFUNC[type][mjGEOM_BOX](m, d, ours, g, 0, margin);
    const int expected = mujoco_pair_function(type, mjGEOM_BOX)(m, d, theirs, g, 0, margin);
    EXPECT_EQ(n, expected) << "type " << type;
    EXPECT_EQ(std::memcmp(ours, theirs, sizeof(mjContact) * std::max(std::min(n, expected), 0)), 0);
    contacts += expected > 0;
    none += expected == 0;
    if (geoms_apart(m, d, g, 0, margin)) {
      ++rejected;
      EXPECT_EQ(expected, 0) << "type " << type << " rejected with a contact";
    }
    return expected;
  };
  const auto random_pose = [&](int body) {
    double* q = d->qpos + 7 * body;
    for (int k = 0; k < 3; ++k) q[k] = unit(rng) * (k == 2 ? 0.45 : 0.75);
    for (int k = 3; k < 7; ++k) q[k] = unit(rng);
    mju_normalize4(q + 3);
  };
  for (int trial = 0; trial < 20000; ++trial) {
    for (int b = 0; b < 3; ++b) random_pose(b);
    mj_kinematics(m, d);
    for (int g = 1; g < 4; ++g) {
      for (const double margin : {0.0, 0.02}) check(g, margin);
    }
  }
  // First touch along a ray out of the table's centre: touching at scale 0,
  // apart at 2 (convex shapes: one crossing), bisected to 1e-12.
  for (int trial = 0; trial < 300; ++trial) {
    const int g = 1 + trial % 3;
    const double margin = trial % 2 ? 0.0 : 0.02;
    random_pose(g - 1);
    double* q = d->qpos + 7 * (g - 1);
    const Eigen::Vector3d ray(q[0], q[1], q[2]);
    const auto place = [&](double scale) {
      for (int k = 0; k < 3; ++k) q[k] = ray[k] * scale;
      mj_kinematics(m, d);
    };
    double touching = 0, apart = 2;
    while (apart - touching > 1e-12) {
      const double mid = (touching + apart) / 2;
      place(mid);
      (check(g, margin) > 0 ? touching : apart) = mid;
    }
    for (const double step : {1e-9, 1e-7, 1e-5, 1e-3}) {
      for (const double scale : {touching - step, apart + step}) {
        place(scale);
        check(g, margin);
      }
    }
  }
  // Both sides were exercised, and the early-out does the work.
  EXPECT_GT(contacts, 5000);
  EXPECT_GT(rejected, none / 2);
  EXPECT_NE(mjCOLLISIONFUNC[mjGEOM_CAPSULE][mjGEOM_BOX], mujoco_pair_function(mjGEOM_CAPSULE, mjGEOM_BOX));
  mj_deleteData(d);
  mj_deleteModel(m);
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
