// The observation modalities of world/sensors.hpp, each against a
// constructed scene whose answer is known: segmentation ids of known objects,
// normals of a floor and a wall, flow of a camera turn and of a moving object,
// LiDAR ranges to walls; sensor noise models and their determinism.
#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <cstring>
#include <set>

#include "base/error.hpp"
#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "env/vector_env.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

constexpr int kSize = 128;

// (col, row) of the pixel that sees world point p in the env's camera.
std::array<int, 2> pixel_of(const Env& env, const double p[3]) {
  const int cam = env.world().scene().camera();
  const Pinhole pinhole = Pinhole::of(env.world().model(), cam, kSize, kSize);
  double local[3], u = -1, v = -1;  // outside the image if project() fails
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
      {{2.45, 0.0, 1.1}, "red_panel_1", "panel"},  // fixed: drawn in the merged static mesh
      {{1.9, 0.9, 1.5}, "blue_pillar_1", "pillar"}, {{2.2, -0.8, 0.0}, "floor_living_room_0", "floors"},
      {{2.95, -1.5, 1.5}, "wall_1", "walls"},  // the wall at x = 3
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
  env.impl().world().command_position(robot->head_tilt, -0.98);
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
  mju_mulMatTVec3(out.data(), env.world().data()->cam_xmat + 9 * cam, v);
  return out;
}

TEST(SurfaceNormals, FloorAndWallInTheCameraFrameAreUnitAndExact) {
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
  mjModel* m = env.impl().world().model();
  const int cam = env.world().scene().camera();
  const double turn[4] = {std::cos(delta / 2), 0, std::sin(delta / 2), 0};  // about camera +y
  double q[4];
  mju_mulQuat(q, m->cam_quat + 4 * cam, turn);
  mju_copy4(m->cam_quat + 4 * cam, q);
  // With sleeping on, MuJoCo poses what hangs on the world body (this camera)
  // only at a reset: an edit of the model is seen with sleeping off.
  env.impl().world().set_sleeping(false);
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
  mjModel* m = env.impl().world().model();
  mjData* d = env.impl().world().data();
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

// One env without noise and one with, reset with the same seed: the same
// scene, so the difference is the noise.
struct CleanAndNoisy {
  Env clean, noisy;
  CleanAndNoisy(EnvConfig c, const SensorNoise& noise) : clean(c), noisy((c.noise = noise, c)) {
    clean.reset(3);
    noisy.reset(3);
  }
  const Array& clean_obs(const char* name) { return clean.reset(3).obs[name]; }
  const Array& noisy_obs(const char* name) { return noisy.reset(3).obs[name]; }
};

EnvConfig observing(std::vector<std::string> observations) {
  EnvConfig c = test::box_room_config();
  c.observations = std::move(observations);
  return c;
}

TEST(SensorNoise, RgbExposureAndBlackLevelFollowTheirFormula) {
  SensorNoise n;
  n.rgb_exposure = 2.5;
  n.rgb_black_level = 0.2;
  CleanAndNoisy envs(observing({"rgb"}), n);
  const auto clean = envs.clean_obs("rgb").bytes, noisy = envs.noisy_obs("rgb").bytes;
  int burnt = 0, crushed = 0;
  for (size_t i = 0; i < clean.size(); ++i) {
    const double expected = std::round(std::max(0.0, std::min(255.0, 2.5 * clean[i]) - 51) / 0.8);
    ASSERT_EQ(noisy[i], std::min(255.0, expected)) << "value " << i << " was " << int(clean[i]);
    burnt += noisy[i] == 255;
    crushed += noisy[i] == 0;
  }
  EXPECT_GT(burnt, 100);    // highlights clip
  EXPECT_GT(crushed, 100);  // shadows crush: a narrower dynamic range
}

TEST(SensorNoise, RgbShotNoiseGrowsWithTheSquareRootOfIntensity) {
  SensorNoise n;
  n.rgb_shot_noise = 0.8;
  CleanAndNoisy envs(observing({"rgb"}), n);
  const auto clean = envs.clean_obs("rgb").bytes, noisy = envs.noisy_obs("rgb").bytes;
  // Away from the clipping ends, E[(noisy - clean)^2] = 0.64 I + 1/12 (rounding).
  double squares = 0, expected = 0;
  for (size_t i = 0; i < clean.size(); ++i) {
    if (clean[i] < 30 || clean[i] > 220) continue;
    const double r = double(noisy[i]) - clean[i];
    squares += r * r;
    expected += 0.64 * clean[i] + 1.0 / 12;
  }
  EXPECT_GT(expected, 1e5);
  EXPECT_NEAR(squares / expected, 1.0, 0.03);
}

TEST(SensorNoise, DepthNoiseGrowsWithTheSquareOfDistance) {
  SensorNoise n;
  n.depth_noise_quadratic = 0.01;
  CleanAndNoisy envs(observing({"depth"}), n);
  const Array clean = envs.clean_obs("depth");
  const Array noisy = envs.noisy_obs("depth");
  double normalised = 0;
  int count = 0;
  for (int i = 0; i < kSize * kSize; ++i) {
    const double z = clean.data<float>()[i], r = noisy.data<float>()[i] - z;
    normalised += (r / (0.01 * z * z)) * (r / (0.01 * z * z));
    ++count;
  }
  EXPECT_NEAR(normalised / count, 1.0, 0.03);  // unit variance once scaled by sigma(z)
}

TEST(SensorNoise, DepthLosesTheFarSideOfOccludingEdgesAndWhatIsOutOfRange) {
  SensorNoise n;
  n.depth_edge = 0.2;
  n.depth_max = 2.8;
  CleanAndNoisy envs(observing({"depth"}), n);
  const Array clean_array = envs.clean_obs("depth");
  const float* clean = clean_array.data<float>();
  const float* noisy = envs.noisy_obs("depth").data<float>();
  int shadows = 0, far = 0;
  for (int row = 0; row < kSize; ++row) {
    for (int col = 0; col < kSize; ++col) {
      const int i = row * kSize + col;
      bool behind_edge = false;  // a 4-neighbour is nearer by more than 0.2 m
      for (auto [c, r] : {std::pair{col - 1, row}, {col + 1, row}, {col, row - 1}, {col, row + 1}}) {
        if (c >= 0 && c < kSize && r >= 0 && r < kSize) behind_edge |= clean[i] - clean[r * kSize + c] > 0.2f;
      }
      const bool lost = behind_edge || clean[i] > 2.8f;
      ASSERT_EQ(noisy[i], lost ? 0.f : clean[i]) << col << "," << row;
      shadows += behind_edge;
      far += clean[i] > 2.8f;
    }
  }
  EXPECT_GT(shadows, 50);  // around the pillar and the panel
  EXPECT_GT(far, 1000);    // the walls beside the panel
}

TEST(SensorNoise, LidarDropsBeamsAndJittersRanges) {
  EnvConfig c = observing({"lidar"});
  c.lidar.beams = 4000;
  c.lidar.fov = 2 * M_PI;
  SensorNoise n;
  n.lidar_dropout = 0.25;
  n.lidar_noise = 0.02;
  CleanAndNoisy envs(c, n);
  const Array clean_array = envs.clean_obs("lidar");
  const float* clean = clean_array.data<float>();
  const float* noisy = envs.noisy_obs("lidar").data<float>();
  int dropped = 0, kept = 0;
  double squares = 0;
  for (int i = 0; i < c.lidar.beams; ++i) {
    ASSERT_LT(clean[i], c.lidar.range);  // the room is smaller than the range
    if (noisy[i] == c.lidar.range) {
      ++dropped;
    } else {
      squares += (noisy[i] - clean[i]) * (noisy[i] - clean[i]);
      ++kept;
    }
  }
  EXPECT_NEAR(dropped / 4000.0, 0.25, 0.025);
  EXPECT_NEAR(std::sqrt(squares / kept), 0.02, 0.001);
}

TEST(SensorNoise, BadSettingsAreErrorsNamingThem) {
  auto error = [](auto change) {
    EnvConfig c = observing({"lidar"});
    change(c);
    return test::error_of([&] { Env env(c); });
  };
  EXPECT_NE(error([](EnvConfig& c) { c.noise.depth_noise = -0.1; }).find("env config: noise.depth_noise = -0.1"),
            std::string::npos);
  EXPECT_NE(error([](EnvConfig& c) { c.noise.lidar_dropout = 1; }).find("noise.lidar_dropout"), std::string::npos);
  EXPECT_NE(error([](EnvConfig& c) { c.noise.rgb_exposure = 0; }).find("noise.rgb_exposure"), std::string::npos);
  EXPECT_NE(error([](EnvConfig& c) { c.lidar.beams = 0; }).find("env config: lidar.beams = 0"), std::string::npos);
  EXPECT_NE(error([](EnvConfig& c) { c.lidar.fov = 7; }).find("lidar.fov"), std::string::npos);
  EXPECT_NE(error([](EnvConfig& c) { c.randomization.surface_color = 1.5; }).find("randomization.surface_color"),
            std::string::npos);
  EXPECT_NE(error([](EnvConfig& c) { c.robot = false; }).find("observation 'lidar' needs the robot"),
            std::string::npos);
  EXPECT_NE(
      error([](EnvConfig& c) {
        c.observations = {"normals"};
      }).find("unknown observation 'normals' (known: rgb, depth, seg_semantic, seg_instance, normal, flow, lidar,"),
      std::string::npos);
}

const std::vector<std::string> kAllModalities = {"rgb",    "depth", "seg_semantic", "seg_instance",
                                                 "normal", "flow",  "lidar",        "proprio"};

EnvConfig everything_on() {
  EnvConfig c = observing(kAllModalities);
  c.start_jitter = 0.1;
  c.noise.rgb_shot_noise = 0.5;
  c.noise.rgb_read_noise = 2;
  c.noise.depth_noise = 0.002;
  c.noise.depth_noise_quadratic = 0.002;
  c.noise.depth_edge = 0.1;
  c.noise.lidar_noise = 0.01;
  c.noise.lidar_dropout = 0.05;
  c.randomization = {0.4, 0.2, 0.3};
  return c;
}

std::vector<unsigned char> bytes_of(const ArrayDict& obs) {
  std::vector<unsigned char> out;
  for (const Array& a : obs.arrays()) out.insert(out.end(), a.bytes.begin(), a.bytes.end());
  return out;
}

TEST(Sensors, EveryModalityWithNoiseIsFixedBitForBitByTheSeed) {
  Env a(everything_on()), b(everything_on());
  const std::vector<float> turn = {0.3f, 0, 0.5f, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0.2f, 0};
  auto episode = [&](Env& env, uint64_t seed) {
    std::vector<unsigned char> out = bytes_of(env.reset(seed).obs);
    for (int i = 0; i < 3; ++i) {
      const auto more = bytes_of(env.step(turn).obs);
      out.insert(out.end(), more.begin(), more.end());
    }
    return out;
  };
  const auto first = episode(a, 11);
  episode(b, 12);  // b has run another episode before
  EXPECT_EQ(first, episode(b, 11));
  EXPECT_NE(first, episode(b, 12));
}

TEST(Sensors, VectorEnvBatchesEveryModalityWhateverTheThreadCount) {
  VectorEnvConfig c;
  c.env = everything_on();
  c.env.max_episode_steps = 3;  // autoresets inside the comparison
  c.num_envs = 3;
  VectorEnvConfig c2 = c;
  c2.num_threads = 2;
  VectorEnv one(c), two(c2);
  Env single(c.env);
  EXPECT_EQ(bytes_of(*one.reset(7).obs), bytes_of(*two.reset(7).obs));
  single.reset(7);
  // Env 0 of the batch is the single env seeded 7 (it draws in tile 0 as the single env does).
  const std::vector<float> zero(3 * kLowLevelActionSize, 0.f);
  const Batch batch = one.step(zero);
  two.step(zero);
  const auto alone = single.step(std::span<const float>(zero).first(kLowLevelActionSize));
  for (const Array& a : alone.obs.arrays()) {
    EXPECT_EQ(std::memcmp((*batch.obs)[a.name].item(0), a.item(0), a.item_bytes()), 0) << a.name;
  }
  const std::vector<float> turn(3 * kLowLevelActionSize, 0.4f);
  for (int i = 0; i < 5; ++i) {
    const Batch b1 = one.step(turn);
    EXPECT_EQ((*b1.obs)["flow"].shape, (std::vector<int>{3, kSize, kSize, 2}));
    EXPECT_EQ(bytes_of(*b1.obs), bytes_of(*two.step(turn).obs)) << "step " << i;
  }
}

TEST(Appearance, RandomisationIsSeededAndLeavesSegmentationAlone) {
  EnvConfig plain = observing({"rgb", "seg_instance"});
  EnvConfig randomised = plain;
  randomised.randomization = {0.5, 0.3, 0.3};
  Env a(plain), b(randomised);
  const auto base_rgb = a.reset(1).obs["rgb"].bytes;
  const auto base_ids = a.reset(1).obs["seg_instance"].bytes;
  const auto rgb1 = b.reset(1).obs["rgb"].bytes;
  EXPECT_EQ(b.reset(1).obs["seg_instance"].bytes, base_ids);  // ids ignore light and colour
  const auto rgb2 = b.reset(2).obs["rgb"].bytes;
  EXPECT_NE(rgb1, base_rgb);
  EXPECT_NE(rgb1, rgb2);
  EXPECT_EQ(b.reset(1).obs["rgb"].bytes, rgb1);  // after another episode's draws
  // Zero spreads put the scene's own lights, colours and textures back.
  World& w = b.impl().world();
  Rng rng(0);
  w.randomize_appearance({}, rng);
  const mjModel* scene = w.scene().model();
  const mjModel* m = w.model();
  EXPECT_EQ(std::memcmp(m->light_diffuse, scene->light_diffuse, sizeof(float) * 3 * m->nlight), 0);
  EXPECT_EQ(std::memcmp(m->geom_rgba, scene->geom_rgba, sizeof(float) * 4 * m->ngeom), 0);
  EXPECT_EQ(std::memcmp(m->tex_data, scene->tex_data, m->ntexdata), 0);
  EXPECT_EQ(w.texture_version(), 0);
}

}  // namespace
}  // namespace chore
