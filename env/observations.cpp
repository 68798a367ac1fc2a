#include "env/observations.hpp"

#include <mujoco/mujoco.h>

#include <cmath>
#include <limits>

#include "base/error.hpp"
#include "base/registry.hpp"

namespace chore {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kProprioSize = 30;

Space image(const ObservationSource& s, int channels, DType type, double lo, double hi) {
  const EnvConfig& c = s.config;
  return channels == 1 ? Space::box({c.height, c.width}, type, lo, hi)
                       : Space::box({c.height, c.width, channels}, type, lo, hi);
}

// Base pose (x, y, sin, cos of heading) and velocity in its own frame, torso,
// arm and head positions and velocities, fingers, is-grasping.
void write_proprio(const ObservationSource& s, void* buffer) {
  float* p = static_cast<float*>(buffer);
  const World& w = s.world;
  const Robot& r = *w.robot();
  const mjData* d = w.data();
  const Pose2 base = w.base_pose();
  const double c = std::cos(base.yaw), sn = std::sin(base.yaw);
  const double vx = d->qvel[r.base_x.dof], vy = d->qvel[r.base_y.dof];
  int k = 0;
  for (double v : {base.x, base.y, sn, c, c * vx + sn * vy, -sn * vx + c * vy, d->qvel[r.base_yaw.dof]}) {
    p[k++] = static_cast<float>(v);
  }
  const auto arm = r.torso_and_arm();
  const std::array<const RobotJoint*, 2> head = {&r.head_pan, &r.head_tilt};
  for (const RobotJoint* j : arm) p[k++] = static_cast<float>(d->qpos[j->qpos]);
  for (const RobotJoint* j : head) p[k++] = static_cast<float>(d->qpos[j->qpos]);
  for (const RobotJoint* j : arm) p[k++] = static_cast<float>(d->qvel[j->dof]);
  for (const RobotJoint* j : head) p[k++] = static_cast<float>(d->qvel[j->dof]);
  p[k++] = static_cast<float>(d->qpos[r.gripper_left.qpos]);
  p[k++] = static_cast<float>(d->qpos[r.gripper_right.qpos]);
  p[k++] = w.grasped_object() >= 0 ? 1.0f : 0.0f;
}

// 1 where action i's precondition holds now.
void write_action_mask(const ObservationSource& s, void* buffer) {
  auto* mask = static_cast<std::uint8_t*>(buffer);
  for (size_t i = 0; i < s.primitive_actions.size(); ++i) {
    const PrimitiveAction& a = s.primitive_actions[i];
    mask[i] = unmet_precondition(s.world, a.type, a.object).empty() ? 1 : 0;
  }
}

}  // namespace

const std::vector<Modality>& modalities() {
  static const std::vector<Modality> list = {
      {"rgb", false, false, [](const ObservationSource& s) { return image(s, 3, DType::uint8, 0, 255); },
       [](SensorFrame& f, void* b) { f.rgb = static_cast<std::uint8_t*>(b); }},
      {"depth", false, false, [](const ObservationSource& s) { return image(s, 1, DType::float32, 0, kInf); },
       [](SensorFrame& f, void* b) { f.depth = static_cast<float*>(b); }},
      {"seg_semantic", false, false,
       [](const ObservationSource& s) {
         const int classes = static_cast<int>(s.sensors.segmentation(s.world).classes().size());
         return image(s, 1, DType::int32, 0, classes - 1);
       },
       [](SensorFrame& f, void* b) { f.semantic = static_cast<std::int32_t*>(b); }},
      {"seg_instance", false, false,
       [](const ObservationSource& s) {
         const int instances = static_cast<int>(s.sensors.segmentation(s.world).instances().size());
         return image(s, 1, DType::int32, 0, instances - 1);
       },
       [](SensorFrame& f, void* b) { f.instance = static_cast<std::int32_t*>(b); }},
      {"normal", false, false, [](const ObservationSource& s) { return image(s, 3, DType::float32, -1, 1); },
       [](SensorFrame& f, void* b) { f.normal = static_cast<float*>(b); }},
      {"flow", false, false, [](const ObservationSource& s) { return image(s, 2, DType::float32, -kInf, kInf); },
       [](SensorFrame& f, void* b) { f.flow = static_cast<float*>(b); }},
      {"lidar", true, false,
       [](const ObservationSource& s) {
         return Space::box({s.config.lidar.beams}, DType::float32, 0, s.config.lidar.range);
       },
       [](SensorFrame& f, void* b) { f.lidar = static_cast<float*>(b); }},
      {"proprio", true, false,
       [](const ObservationSource&) { return Space::box({kProprioSize}, DType::float32, -kInf, kInf); }, nullptr,
       write_proprio},
      {"is_grasping", true, false, [](const ObservationSource&) { return Space::box({1}, DType::float32, 0, 1); },
       nullptr,
       [](const ObservationSource& s, void* b) {
         *static_cast<float*>(b) = s.world.grasped_object() >= 0 ? 1.0f : 0.0f;
       }},
      {"action_mask", false, true,
       [](const ObservationSource& s) {
         return Space::box({static_cast<int>(s.primitive_actions.size())}, DType::uint8, 0, 1);
       },
       nullptr, write_action_mask},
  };
  return list;
}

const Modality& find_modality(const std::string& name) {
  return find_by_name(modalities(), name, "observation");
}

}  // namespace chore
