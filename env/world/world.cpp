#include "env/world/world.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "env/world/error.hpp"
#include "env/world/mujoco_errors.hpp"

namespace chore {

World::World(std::shared_ptr<const Scene> scene) : scene_(std::move(scene)) {
  install_mujoco_handlers();
  model_ = mj_copyModel(nullptr, scene_->model());
  data_ = mj_makeData(model_);
  if (!model_ || !data_) throw Error("world: out of memory copying scene '" + scene_->name() + "'");
  if (scene_->has_robot()) robot_ = Robot::bind(model_);
  reset(scene_->robot_start());
}

World::~World() {
  if (data_) mj_deleteData(data_);
  if (model_) mj_deleteModel(model_);
}

void World::reset(const Pose2& base) {
  release();
  states_.reset();
  mj_resetData(model_, data_);
  base_command_[0] = base_command_[1] = base_command_[2] = 0;
  if (robot_) {
    const Robot& r = *robot_;
    data_->qpos[r.base_x.qpos] = base.x;
    data_->qpos[r.base_y.qpos] = base.y;
    data_->qpos[r.base_yaw.qpos] = base.yaw;
    data_->qpos[r.torso.qpos] = Robot::kHomeTorso;
    for (int i = 0; i < Robot::kArmJoints; ++i) data_->qpos[r.arm[i].qpos] = Robot::kTuckedArm[i];
    data_->qpos[r.gripper_left.qpos] = Robot::kGripperOpen;
    data_->qpos[r.gripper_right.qpos] = Robot::kGripperOpen;
    // Position actuators hold the configuration they start in.
    for (const RobotJoint* j : {&r.torso, &r.gripper_left, &r.gripper_right, &r.head_pan,
                                &r.head_tilt}) {
      data_->ctrl[j->actuator] = data_->qpos[j->qpos];
    }
    for (const RobotJoint& j : r.arm) data_->ctrl[j.actuator] = data_->qpos[j.qpos];
  }
  mj_forward(model_, data_);
}

void World::set_lighting(Lighting lighting) {
  for (int light : scene_->ceiling_lights()) {
    model_->light_active[light] = lighting == Lighting::full ? 1 : 0;
  }
}

void World::command_base_velocity(double forward, double left, double turn) {
  base_command_[0] = forward;
  base_command_[1] = left;
  base_command_[2] = turn;
}

void World::command_position(const RobotJoint& joint, double target) {
  data_->ctrl[joint.actuator] = std::clamp(target, joint.low, joint.high);
}

double World::commanded_position(const RobotJoint& joint) const {
  return data_->ctrl[joint.actuator];
}

Pose2 World::base_pose() const {
  if (!robot_) return scene_->robot_start();
  return {data_->qpos[robot_->base_x.qpos], data_->qpos[robot_->base_y.qpos],
          data_->qpos[robot_->base_yaw.qpos]};
}

double World::time() const { return data_->time; }

World::StepReport World::step(int substeps) {
  StepReport report;
  for (int s = 0; s < substeps; ++s) {
    if (robot_) {
      const double yaw = data_->qpos[robot_->base_yaw.qpos];
      const double c = std::cos(yaw), sn = std::sin(yaw);
      data_->ctrl[robot_->base_x.actuator] = c * base_command_[0] - sn * base_command_[1];
      data_->ctrl[robot_->base_y.actuator] = sn * base_command_[0] + c * base_command_[1];
      data_->ctrl[robot_->base_yaw.actuator] = base_command_[2];
    }
    auto bad_state_count = [&] {
      return data_->warning[mjWARN_BADQPOS].number + data_->warning[mjWARN_BADQVEL].number +
             data_->warning[mjWARN_BADQACC].number;
    };
    const int bad_before = bad_state_count();
    mj_step(model_, data_);
    if (bad_state_count() != bad_before) {
      // MuJoCo has already reset the state; the episode cannot go on.
      report.diverged = true;
      release();
      return report;
    }
    if (robot_) update_grasp(report);
    if (state_updates_) states_.after_physics_step(*this, model_->opt.timestep);
  }
  if (state_updates_) states_.after_env_step(*this, substeps * model_->opt.timestep);
  return report;
}

void World::update_grasp(StepReport& report) {
  const Robot& r = *robot_;
  const double target = data_->ctrl[r.gripper_left.actuator] + data_->ctrl[r.gripper_right.actuator];
  const bool closing = target < Robot::kGripperOpen;  // fingers commanded past half open
  if (grasped_ >= 0) {
    if (!closing) release();
    return;
  }
  if (!closing) return;
  // An object touched by both fingers is attached (OmniGibson's assisted grasp).
  std::vector<int> left, right;  // root bodies each finger touches
  for (int c = 0; c < data_->ncon; ++c) {
    const mjContact& con = data_->contact[c];
    const int b1 = model_->geom_bodyid[con.geom1], b2 = model_->geom_bodyid[con.geom2];
    for (const auto& [finger, other] : {std::pair{b1, b2}, std::pair{b2, b1}}) {
      if (finger == r.left_finger_body) left.push_back(model_->body_rootid[other]);
      if (finger == r.right_finger_body) right.push_back(model_->body_rootid[other]);
    }
  }
  const auto& objects = scene_->objects();
  for (size_t i = 0; i < objects.size(); ++i) {
    const int body = objects[i].body;
    if (objects[i].fixed || std::find(left.begin(), left.end(), body) == left.end() ||
        std::find(right.begin(), right.end(), body) == right.end()) {
      continue;
    }
    if (model_->body_subtreemass[body] > kGraspMassLimit) {
      report.grasp_refused = true;
      return;
    }
    attach(static_cast<int>(i));
    return;
  }
}

void World::attach(int object) {
  const SceneObject& o = scene_->objects()[object];
  const int hand = robot_->gripper_body, body = o.body;
  // Weld error in MuJoCo 2.2.2: (x_hand + R_hand * relpos) - (x_body + R_body * anchor),
  // orientation q_hand * relquat vs q_body. Zero error in the current pose:
  mjtNum* eq = model_->eq_data + mjNEQDATA * o.grasp_weld;
  mjtNum delta[3], relpos[3], hand_inverse[4];
  mju_zero3(eq);  // anchor at the object's origin
  mju_sub3(delta, data_->xpos + 3 * body, data_->xpos + 3 * hand);
  mju_rotVecMatT(relpos, delta, data_->xmat + 9 * hand);
  mju_copy3(eq + 3, relpos);
  mju_negQuat(hand_inverse, data_->xquat + 4 * hand);
  mju_mulQuat(eq + 6, hand_inverse, data_->xquat + 4 * body);
  eq[10] = 1.0;  // torquescale
  model_->eq_active[o.grasp_weld] = 1;
  grasped_ = object;
}

void World::release() {
  if (grasped_ < 0) return;
  model_->eq_active[scene_->objects()[grasped_].grasp_weld] = 0;
  grasped_ = -1;
}

}  // namespace chore
