// The observation modalities of env/world/sensors.hpp, each against a
// constructed scene whose answer is known: segmentation ids of known objects,
// normals of a floor and a wall, flow of a camera turn and of a moving object,
// LiDAR ranges to walls; sensor noise models and their determinism.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <set>

#include "env/env.hpp"
#include "env/vector_env.hpp"
#include "env/world/error.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

constexpr int kSize = 128;

// (col, row) of the pixel that sees world point p in the env's camera.
std::array<int, 2> pixel_of(const Env& env, const double p[3]) {
  const int cam = env.world().scene().camera();
  const Pinhole pinhole = Pinhole::of(env.world().model(), cam, kSize, kSize);
  double local[3], u, v;
  CameraPose::of(env.world().data(), cam).to_camera(p, local);
  EXPECT_TRUE(pinhole.project(local, u, v));
  const int col = std::clamp(static_cast<int>(std::floor(u)), 0, kSize - 1);
  const int row = std::clamp(static_cast<int>(std::floor(v)), 0, kSize - 1);
  EXPECT_TRUE(col == std::floor(u) && row == std::floor(v)) << "outside the image: " << u << "," << v;
  return {col, row};
}

int instance_named(const Env& env, const std::string& name) {
  const auto& instances = env.segmentation().instances();
  for (size_t i = 0; i < instances.size(); ++i) {
    if (instances[i].name == name) return static_cast<int>(i);
  }
  ADD_FAILURE() << "no instance " << name;
  return -1;
}

TEST(Segmentation, KnownObjectsFloorWallsAndCeilingAtKnownPixels) {
  EnvConfig c = test::box_room_config();
  c.observations = {"seg_semantic", "seg_instance"};
  Env env(c);
  const auto r = env.reset(0);
  const int32_t* instance = r.obs["seg_instance"].data<int32_t>();
  const int32_t* semantic = r.obs["seg_semantic"].data<int32_t>();
  const Segmentation& seg = env.segmentation();
  // Points on each surface, clear of the others from where the robot stands
  // (the panel spans y in [-0.6, 0.6] at x = 2.45; the pillar stands at y = 0.9).
  const struct {
    double point[3];
    const char* instance;
    const char* category;
  } expected[] = {
      {{2.45, 0.0, 1.1}, "red_panel_1", "panel"},        // fixed: drawn in the merged static mesh
      {{1.9, 0.9, 1.5}, "blue_pillar_1", "pillar"},
      {{2.2, -0.8, 0.0}, "floor_living_room_0", "floors"},
      {{2.95, -1.5, 1.5}, "wall_1", "walls"},             // the wall at x = 3
      {{2.9, -1.2, 2.6}, "ceilings", "ceilings"},
  };
  for (const auto& e : expected) {
    const auto [col, row] = pixel_of(env, e.point);
    const int id = instance[row * kSize + col];
    EXPECT_EQ(id, instance_named(env, e.instance)) << e.instance << " at " << col << "," << row;
    EXPECT_EQ(seg.classes()[semantic[row * kSize + col]].category, e.category) << e.instance;
  }
  EXPECT_EQ(seg.classes()[seg.instances()[instance_named(env, "blue_pillar_1")].semantic].synset, "board.n.03");
}

TEST(Segmentation, RobotLinksAreInstancesOfTheAgentClass) {
  EnvConfig c = test::box_room_config();
  c.observations = {"seg_semantic", "seg_instance"};
  Env env(c);
  env.reset(0);
  // Head tilted fully down: the tucked arm and gripper come into view.
  const Robot* robot = env.world().robot();
  env.world().data()->qpos[robot->head_tilt.qpos] = -0.98;
  env.world().command_position(robot->head_tilt, -0.98);
  const auto r = env.step(std::vector<float>(kLowLevelActionSize, 0.f));
  const int32_t* instance = r.obs["seg_instance"].data<int32_t>();
  const int32_t* semantic = r.obs["seg_semantic"].data<int32_t>();
  const Segmentation& seg = env.segmentation();
  const mjModel* m = env.world().model();
  const mjData* d = env.world().data();
  std::set<int> links;
  for (const char* name : {"robot_palm_v", "robot_arm_6_v"}) {
    const int geom = mj_name2id(m, mjOBJ_GEOM, name);
    const auto [col, row] = pixel_of(env, d->geom_xpos + 3 * geom);
    const Instance& seen = seg.instances()[instance[row * kSize + col]];
    EXPECT_EQ(seen.kind, Instance::Kind::robot_link) << name;
    EXPECT_EQ(seen.body, m->geom_bodyid[geom]) << name << " seen as " << seen.name;
    EXPECT_EQ(semantic[row * kSize + col], Segmentation::kAgent);
    links.insert(instance[row * kSize + col]);
  }
  EXPECT_EQ(links.size(), 2u);  // two links, two ids
  EXPECT_EQ(seg.classes()[Segmentation::kAgent].synset, "agent.n.01");
}

TEST(Segmentation, TablesNumberClassesAndInstances) {
  EnvConfig c = test::box_room_config();
  c.observations = {"seg_instance"};
  Env env(c);
  const Segmentation& seg = env.segmentation();
  const auto& objects = env.world().scene().objects();
  for (size_t i = 0; i < objects.size(); ++i) {
    const Instance& in = seg.instances()[seg.instance_of_object(static_cast<int>(i))];
    EXPECT_EQ(in.name, objects[i].name);
    EXPECT_EQ(in.kind, Instance::Kind::object);
    EXPECT_EQ(seg.classes()[in.semantic].category, objects[i].category);
    EXPECT_EQ(seg.classes()[in.semantic].synset, objects[i].synset);
  }
  // Two blocks share one class; every class but the background is used.
  EXPECT_EQ(seg.instances()[seg.instance_of_object(2)].semantic, seg.instances()[seg.instance_of_object(3)].semantic);
  std::set<int> used;
  for (const Instance& in : seg.instances()) used.insert(in.semantic);
  EXPECT_EQ(used.size(), seg.classes().size());
  EXPECT_EQ(env.observation_space()["seg_instance"].high, seg.instances().size() - 1.0);
}

// The camera-frame direction of world vector v.
std::array<double, 3> in_camera(const Env& env, const double v[3]) {
  const int cam = env.world().scene().camera();
  std::array<double, 3> out;
  mju_rotVecMatT(out.data(), v, env.world().data()->cam_xmat + 9 * cam);
  return out;
}

TEST(Normals, FloorAndWallInTheCameraFrameAreUnitAndExact) {
  EnvConfig c = test::box_room_config();
  c.observations = {"normal", "seg_instance"};
  Env env(c);
  const auto r = env.reset(0);
  const float* normal = r.obs["normal"].data<float>();
  const int32_t* instance = r.obs["seg_instance"].data<int32_t>();
  const double up[3] = {0, 0, 1}, into_room[3] = {-1, 0, 0};  // floor; the wall at x = 3
  const auto floor_n = in_camera(env, up), wall_n = in_camera(env, into_room);
  const int floor = instance_named(env, "floor_living_room_0"), wall = instance_named(env, "wall_1");
  double worst_floor = 0, worst_wall = 0, worst_length = 0;
  int floors = 0, walls = 0;
  for (int row = 1; row < kSize - 1; ++row) {
    for (int col = 1; col < kSize - 1; ++col) {
      const int i = row * kSize + col;
      const float* n = normal + 3 * i;
      worst_length = std::max(worst_length, std::abs(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1.0));
      // Away from other surfaces: all four neighbours see the same one.
      bool interior = true;
      for (int k : {i - 1, i + 1, i - kSize, i + kSize}) interior &= instance[k] == instance[i];
      if (!interior) continue;
      auto error = [&](const std::array<double, 3>& e) {
        return std::acos(std::min(1.0, n[0] * e[0] + n[1] * e[1] + n[2] * e[2]));
      };
      if (instance[i] == floor) worst_floor = std::max(worst_floor, error(floor_n)), ++floors;
      if (instance[i] == wall) worst_wall = std::max(worst_wall, error(wall_n)), ++walls;
    }
  }
  EXPECT_GT(floors, 500);
  EXPECT_GT(walls, 2000);
  EXPECT_LT(worst_floor, 1e-3) << "radians";
  EXPECT_LT(worst_wall, 1e-3) << "radians";
  EXPECT_LT(worst_length, 1e-5);
  // The level camera: the floor faces up the image (+y), the wall faces the camera (+z).
  EXPECT_NEAR(floor_n[1], 1.0, 1e-9);
  EXPECT_NEAR(wall_n[2], 1.0, 1e-9);
}

// The box room without the robot: a fixed camera at (0, 0, 1.1) looking along +x.
EnvConfig fixed_camera_config(std::vector<std::string> observations) {
  EnvConfig c = test::box_room_config();
  c.robot = false;
  c.observations = std::move(observations);
  return c;
}

TEST(Flow, APureCameraYawMatchesTheAnalyticFlow) {
  Env env(fixed_camera_config({"flow"}));
  const auto first = env.reset(0);
  const float* flow = first.obs["flow"].data<float>();
  EXPECT_TRUE(std::all_of(flow, flow + 2 * kSize * kSize, [](float f) { return f == 0; }))
      << "the first frame of an episode has no flow";
  // Turn the camera left by delta about its own vertical axis.
  const double delta = 0.05;
  mjModel* m = env.world().model();
  const int cam = env.world().scene().camera();
  const double turn[4] = {std::cos(delta / 2), 0, std::sin(delta / 2), 0};  // about camera +y
  double q[4];
  mju_mulQuat(q, m->cam_quat + 4 * cam, turn);
  mju_copy4(m->cam_quat + 4 * cam, q);
  const auto r = env.step({});
  flow = r.obs["flow"].data<float>();
  // A pixel's ray (x, y, -1) was, before the turn, R_y(delta) (x, y, -1).
  const double f = 0.5 * kSize / std::tan(m->cam_fovy[cam] * M_PI / 360.0);
  const double c = std::cos(delta), s = std::sin(delta);
  double worst = 0;
  for (int row = 0; row < kSize; ++row) {
    for (int col = 0; col < kSize; ++col) {
      const double x = (col + 0.5 - kSize / 2.0) / f, y = -(row + 0.5 - kSize / 2.0) / f;
      const double w = x * s + c;
      const double u_before = kSize / 2.0 + f * (x * c - s) / w, v_before = kSize / 2.0 - f * y / w;
      const float* fl = flow + 2 * (row * kSize + col);
      worst = std::max({worst, std::abs(fl[0] - (col + 0.5 - u_before)), std::abs(fl[1] - (row + 0.5 - v_before))});
    }
  }
  EXPECT_LT(worst, 1e-3) << "pixels";
  // At the centre the scene moved right by f tan(delta).
  EXPECT_NEAR(flow[2 * (64 * kSize + 64)], f * std::tan(delta), 0.01);
}

TEST(Flow, AMovingObjectMatchesTheAnalyticFlowAndTheRestIsStill) {
  Env env(fixed_camera_config({"depth", "seg_instance", "flow"}));
  env.reset(0);
  // The small block, set on the floor in front of the panel, then slid 0.2 m left (+y).
  const SceneObject& block = *env.world().scene().find_object("small_block_1");
  mjModel* m = env.world().model();
  mjData* d = env.world().data();
  double* qpos = d->qpos + m->jnt_qposadr[m->body_jntadr[block.body]];
  const double unit_quat[4] = {1, 0, 0, 0};
  auto place = [&](double x, double y) {
    qpos[0] = x, qpos[1] = y, qpos[2] = 0;
    mju_copy4(qpos + 3, unit_quat);
    mju_zero(d->qvel, m->nv);
    mj_forward(m, d);
  };
  place(2.3, 0.0);
  env.step({});
  double before[3];
  mju_copy3(before, d->xpos + 3 * block.body);
  place(2.3, 0.2);
  const auto r = env.step({});
  const double* now = d->xpos + 3 * block.body;
  // A translation at constant depth moves every point of the front face alike:
  // by f dy / depth pixels, leftwards (image right is -y).
  const int cam = env.world().scene().camera();
  const double f = 0.5 * kSize / std::tan(m->cam_fovy[cam] * M_PI / 360.0);
  const double face = now[0] - 0.025, depth = face - d->cam_xpos[3 * cam];
  const double expected_u = -f * (now[1] - before[1]) / depth;
  EXPECT_NEAR(expected_u, -f * 0.2 / 2.275, 0.05);  // the block barely settles
  const double face_centre[3] = {face, now[1], now[2]};
  const auto [col, row] = pixel_of(env, face_centre);
  const int id = env.segmentation().instance_of_object(static_cast<int>(&block - &env.world().scene().objects()[0]));
  const int32_t* instance = r.obs["seg_instance"].data<int32_t>();
  ASSERT_EQ(instance[row * kSize + col], id);
  const float* flow = r.obs["flow"].data<float>();
  EXPECT_NEAR(flow[2 * (row * kSize + col)], expected_u, 0.05);
  EXPECT_NEAR(flow[2 * (row * kSize + col) + 1], 0.0, 0.05);
  // Everything else (the panel, floor, walls; where the block was) stood still.
  int moving = 0;
  float still = 0;
  for (int i = 0; i < kSize * kSize; ++i) {
    if (instance[i] == id) {
      ++moving;
    } else {
      still = std::max({still, std::abs(flow[2 * i]), std::abs(flow[2 * i + 1])});
    }
  }
  EXPECT_GT(moving, 4);
  EXPECT_LT(still, 1e-3);
}

// Distance from (x, y) along (dx, dy) to an axis-aligned rectangle, or infinity.
double ray_to_box(double x, double y, double dx, double dy, double x0, double y0, double x1, double y1) {
  double t0 = 0, t1 = 1e9;
  for (auto [p, d, lo, hi] : {std::array<double, 4>{x, dx, x0, x1}, std::array<double, 4>{y, dy, y0, y1}}) {
    if (std::abs(d) < 1e-12) {
      if (p < lo || p > hi) return INFINITY;
      continue;
    }
    const double a = (lo - p) / d, b = (hi - p) / d;
    t0 = std::max(t0, std::min(a, b));
    t1 = std::min(t1, std::max(a, b));
  }
  return t0 <= t1 ? t0 : INFINITY;
}

TEST(Lidar, RangesMatchTheRoomsGeometry) {
  EnvConfig c = test::box_room_config();
  c.observations = {"lidar"};
  c.lidar.beams = 360;
  c.lidar.fov = 2 * M_PI;  // all round: the base does not see itself
  c.lidar.range = 3.5;
  Env env(c);
  const auto r = env.reset(0);
  const float* ranges = r.obs["lidar"].data<float>();
  EXPECT_EQ(env.observation_space()["lidar"].to_string(), "Box(0, 3.5, (360,), float32)");
  // The scan plane (0.1 m up) meets the walls (inner faces at +-2.95), the
  // panel (x 2.45..2.55, y -0.6..0.6) and the pillar (x 1.9..2.1, y 0.8..1.0);
  // the blocks are 5 cm tall, under it. The robot stands at the origin facing +x.
  const double* origin = env.world().data()->site_xpos + 3 * env.world().robot()->lidar_site;
  EXPECT_NEAR(origin[0], 0.275, 1e-9);
  EXPECT_NEAR(origin[2], 0.1, 1e-9);
  double worst = 0;
  int capped = 0;
  for (int i = 0; i < c.lidar.beams; ++i) {
    const double a = beam_angle(c.lidar, i), dx = std::cos(a), dy = std::sin(a);
    double expected = INFINITY;
    for (double wall : {2.95, -2.95}) {
      if (std::abs(dx) > 1e-12 && (wall - origin[0]) / dx > 0) expected = std::min(expected, (wall - origin[0]) / dx);
      if (std::abs(dy) > 1e-12 && (wall - origin[1]) / dy > 0) expected = std::min(expected, (wall - origin[1]) / dy);
    }
    expected = std::min({expected, ray_to_box(origin[0], origin[1], dx, dy, 2.45, -0.6, 2.55, 0.6),
                         ray_to_box(origin[0], origin[1], dx, dy, 1.9, 0.8, 2.1, 1.0)});
    capped += expected >= c.lidar.range;
    worst = std::max(worst, std::abs(ranges[i] - std::min(expected, c.lidar.range)));
  }
  EXPECT_LT(worst, 1e-4) << "metres";
  EXPECT_GT(capped, 20);  // the corners are out of range
}

}  // namespace
}  // namespace chore
