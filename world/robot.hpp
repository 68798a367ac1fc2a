// The robot's joints, actuators and frames in a compiled scene, found by the
// names of assets/robots/tiago.xml (docs/assets.md lists them).
#pragma once

#include <array>
#include <string>

struct mjModel_;

namespace chore {

struct RobotJoint {
  int joint = -1;            // joint id
  int qpos = -1;             // address in qpos
  int dof = -1;              // address in qvel
  int actuator = -1;         // actuator driving it
  double low = 0, high = 0;  // joint range
};

struct Robot {
  static constexpr int kArmJoints = 7;
  // Throws chore::Error naming the first missing element.
  static Robot bind(const mjModel_* model);

  RobotJoint base_x, base_y, base_yaw;
  RobotJoint torso;
  std::array<RobotJoint, kArmJoints> arm;
  RobotJoint gripper_left, gripper_right;
  RobotJoint head_pan, head_tilt;
  // The joints an arm configuration lists: torso, arm_1 .. arm_7.
  std::array<const RobotJoint*, 1 + kArmJoints> torso_and_arm() const {
    std::array<const RobotJoint*, 1 + kArmJoints> joints;
    joints[0] = &torso;
    for (int i = 0; i < kArmJoints; ++i) joints[1 + i] = &arm[i];
    return joints;
  }

  int gripper_body = -1, left_finger_body = -1, right_finger_body = -1;
  int gripper_site = -1, lidar_site = -1, camera = -1;

  // Home configuration at reset: torso down, arm tucked, head level, gripper open.
  static constexpr double kHomeTorso = 0.0;
  static const std::array<double, kArmJoints> kTuckedArm;
  static constexpr double kGripperOpen = 0.045;  // per finger (m)
  // m from gripper_center to the fingertips along the hand's approach axis
  // (the site's x; the finger pads end at x 0.21 in tiago.xml, the site is at 0.17).
  static constexpr double kFingertips = 0.04;
  // The base drives over what lies lower than this (m): floors, a rug, a rag;
  // and over a cloth on the floor lower than kDrivesOverCloth (a towel folded
  // in half, its hem and seams: soft, it gives way): base_planner.hpp's driven_over().
  static constexpr double kDrivesOver = 0.02;
  static constexpr double kDrivesOverCloth = 0.05;
};

// Robot MJCF files are read up to this size.
constexpr size_t kMaxMjcfBytes = 16u << 20;

// The robot's MJCF document (assets/robots/tiago.xml), checked alone (MuJoCo's
// syntax and schema, then every element Robot::bind needs, errors naming
// `path`), as the children of its <mujoco> element: what Scene::build splices
// into the scene document.
std::string robot_mjcf_children(const std::string& text, const std::string& path);

}  // namespace chore
