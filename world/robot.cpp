#include "world/robot.hpp"

#include <mujoco/mujoco.h>

#include <memory>
#include <string>

#include "base/error.hpp"
#include "world/mujoco_errors.hpp"

namespace chore {
namespace {

int require(const mjModel* m, int type, const std::string& name, const char* kind) {
  const int id = mj_name2id(m, type, name.c_str());
  if (id < 0) throw Error("robot model: missing " + std::string(kind) + " '" + name + "'");
  return id;
}

RobotJoint bind_joint(const mjModel* m, const std::string& name, bool actuated = true) {
  RobotJoint j;
  j.joint = require(m, mjOBJ_JOINT, name, "joint");
  j.qpos = m->jnt_qposadr[j.joint];
  j.dof = m->jnt_dofadr[j.joint];
  j.low = m->jnt_range[2 * j.joint];
  j.high = m->jnt_range[2 * j.joint + 1];
  if (actuated) {
    j.actuator = require(m, mjOBJ_ACTUATOR, "act_" + name, "actuator");
    if (m->actuator_trnid[2 * j.actuator] != j.joint) {
      throw Error("robot model: actuator 'act_" + name + "' does not drive joint '" + name + "'");
    }
  }
  return j;
}

}  // namespace

// The arm folded in front of the torso, within the base footprint (assets/robots/tiago.xml).
const std::array<double, Robot::kArmJoints> Robot::kTuckedArm = {0.12, -1.45, -1.06, 2.13, 1.23, -1.26, -1.00};

Robot Robot::bind(const mjModel* m) {
  Robot r;
  r.base_x = bind_joint(m, "base_x");
  r.base_y = bind_joint(m, "base_y");
  r.base_yaw = bind_joint(m, "base_yaw");
  r.torso = bind_joint(m, "torso_lift");
  for (int i = 0; i < kArmJoints; ++i) r.arm[i] = bind_joint(m, "arm_" + std::to_string(i + 1));
  r.gripper_left = bind_joint(m, "gripper_left");
  r.gripper_right = bind_joint(m, "gripper_right");
  r.head_pan = bind_joint(m, "head_pan");
  r.head_tilt = bind_joint(m, "head_tilt");
  r.gripper_body = require(m, mjOBJ_BODY, "gripper", "body");
  r.left_finger_body = require(m, mjOBJ_BODY, "gripper_left_finger", "body");
  r.right_finger_body = require(m, mjOBJ_BODY, "gripper_right_finger", "body");
  r.gripper_site = require(m, mjOBJ_SITE, "gripper_center", "site");
  r.lidar_site = require(m, mjOBJ_SITE, "base_lidar", "site");
  r.camera = require(m, mjOBJ_CAMERA, "head_camera", "camera");
  return r;
}

std::string robot_mjcf_children(const std::string& text, const std::string& path) {
  // Alone, MuJoCo's errors and the missing elements name this file's lines.
  const std::unique_ptr<mjModel, void (*)(mjModel*)> alone(load_mjcf(text, path + ": invalid robot MJCF"),
                                                           mj_deleteModel);
  try {
    Robot::bind(alone.get());
  } catch (const Error& e) {
    throw Error(path + ": " + e.what());
  }
  const auto open = text.find("<mujoco");
  const auto open_end = open == std::string::npos ? open : text.find('>', open);
  const auto close = text.rfind("</mujoco>");
  if (open_end == std::string::npos || close == std::string::npos || close < open_end) {
    throw Error(path + ": expected a <mujoco> ... </mujoco> document");
  }
  return text.substr(open_end + 1, close - open_end - 1);
}

}  // namespace chore
