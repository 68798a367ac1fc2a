#include "world/world.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <vector>

#include "base/error.hpp"
#include "world/mujoco_errors.hpp"
#include "world/state_rules.hpp"

namespace chore {

World::World(std::shared_ptr<const Scene> scene) : scene_(std::move(scene)) {
  install_mujoco_handlers();
  model_ = mj_copyModel(nullptr, scene_->model());
  data_ = mj_makeData(model_);
  if (!model_ || !data_) throw Error("world: out of memory copying scene '" + scene_->name() + "'");
  if (scene_->has_robot()) robot_ = Robot::bind(model_);
  object_trees_.resize(scene_->objects().size());
  hidden_.assign(scene_->objects().size(), 0);
  for (int b = 1; b < model_->nbody; ++b) {
    const int object = scene_->object_of_body(b), tree = model_->body_treeid[b];
    if (object < 0 || tree < 0) continue;
    std::vector<int>& trees = object_trees_[object];
    if (std::find(trees.begin(), trees.end(), tree) == trees.end()) trees.push_back(tree);
  }
  reset(scene_->robot_start());
}

World::~World() {
  if (scratch_) mj_deleteData(scratch_);
  if (data_) mj_deleteData(data_);
  if (model_) mj_deleteModel(model_);
}

mjData* World::scratch() const {
  if (!scratch_) scratch_ = mj_makeData(model_);
  if (!scratch_) throw Error("world: out of memory for scratch data");
  return scratch_;
}

void World::reset(const Pose2& base) {
  release();
  states_.reset();
  // Every object real (mj_resetData puts it back where it was).
  for (size_t object = 0; object < hidden_.size(); ++object) {
    if (hidden_[object]) make_real(static_cast<int>(object));
  }
  // Grasps and attachments off (eq_active0); the scene's objects asleep where
  // they were placed, with their resting contacts kept.
  reset_data();
  base_command_[0] = base_command_[1] = base_command_[2] = 0;
  velocity_command_.assign(model_->nu, 0.0);
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
    for (const RobotJoint* j : {&r.torso, &r.gripper_left, &r.gripper_right, &r.head_pan, &r.head_tilt}) {
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

void World::randomize_appearance(const AppearanceRandomization& r, Rng& rng) {
  // Process-wide, so that two worlds' randomised textures never share a version.
  static std::atomic<int> versions{0};
  texture_version_ = chore::randomize_appearance(*scene_, model_, r, rng) ? ++versions : 0;
}

void World::command_base_velocity(double forward, double left, double turn) {
  base_command_[0] = forward;
  base_command_[1] = left;
  base_command_[2] = turn;
}

void World::command_position(const RobotJoint& joint, double target, double velocity) {
  data_->ctrl[joint.actuator] = std::clamp(target, joint.low, joint.high);
  velocity_command_[joint.actuator] = velocity;
}

double World::commanded_position(const RobotJoint& joint) const {
  return data_->ctrl[joint.actuator];
}

Pose2 World::base_pose() const {
  if (!robot_) return scene_->robot_start();
  return {data_->qpos[robot_->base_x.qpos], data_->qpos[robot_->base_y.qpos], data_->qpos[robot_->base_yaw.qpos]};
}

double World::time() const {
  return data_->time;
}

void World::reset_data() {
  mj_resetData(model_, data_);
  resting_.before_reset(model_);
  if (!sleeping()) return;
  // MuJoCo computed the contacts of the objects it put to sleep, then left
  // them out of the list: computed again with sleeping off (a collision pass,
  // which wakes no one), those are the resting contacts to keep.
  model_->opt.enableflags &= ~mjENBL_SLEEP;
  mj_collision(model_, data_);
  model_->opt.enableflags |= mjENBL_SLEEP;
  resting_.after_step(model_, data_);
}

World::StepReport World::step(int substeps) {
  StepReport report;
  for (int s = 0; s < substeps; ++s) {
    if (robot_) {
      const double yaw = data_->qpos[robot_->base_yaw.qpos];
      const double c = std::cos(yaw), sn = std::sin(yaw);
      data_->ctrl[robot_->base_x.actuator] = c * base_command_[0] - sn * base_command_[1];
      data_->ctrl[robot_->base_y.actuator] = sn * base_command_[0] + c * base_command_[1];
      data_->ctrl[robot_->base_yaw.actuator] = base_command_[2];
      // Gravity compensation, as the robot's own controllers do: the position
      // servos only correct tracking errors instead of also carrying the arm,
      // so trajectories are followed closely rather than lagging (and arrive
      // within the primitives' settling time). qfrc_bias is from the last step.
      for (const RobotJoint* j : robot_->torso_and_arm()) {
        data_->qfrc_applied[j->dof] =
            data_->qfrc_bias[j->dof] + model_->dof_damping[j->dof] * velocity_command_[j->actuator];
      }
      // And the carried load's weight, a known payload, at its centre of mass.
      if (const int load = carried_object(); load >= 0) {
        const int body = scene_->objects()[load].body;
        payload_jacobian_.resize(3 * model_->nv);
        mj_jac(model_, data_, payload_jacobian_.data(), nullptr, data_->xipos + 3 * body, robot_->gripper_body);
        const double weight = -model_->opt.gravity[2] * model_->body_subtreemass[body];
        for (const RobotJoint* j : robot_->torso_and_arm()) {
          data_->qfrc_applied[j->dof] += payload_jacobian_[2 * model_->nv + j->dof] * weight;
        }
      }
    }
    auto bad_state_count = [&] {
      return data_->warning[mjWARN_BADQPOS].number + data_->warning[mjWARN_BADQVEL].number +
             data_->warning[mjWARN_BADQACC].number;
    };
    const int bad_before = bad_state_count();
    bool failed = false;
    resting_.before_step(model_, data_);
    try {
      mj_step(model_, data_);
    } catch (const Error&) {
      failed = true;
    }
    if (failed || bad_state_count() != bad_before) {
      // The state is lost: MuJoCo reset it inside the step (a bad position,
      // velocity or acceleration), or failed mid-step. The step ends in
      // MuJoCo's reset state, the same whatever happened inside it; the reset
      // also restores MuJoCo's arena, left mid-step by an error. The episode
      // cannot go on. Sleeping off for the reset and the posing: its
      // sleep="init" would run a whole forward pass, and with it whatever
      // failed; and with sleeping on, mj_kinematics poses only what is awake.
      release();
      resting_.clear();
      const int flags = model_->opt.enableflags;
      model_->opt.enableflags &= ~mjENBL_SLEEP;
      mj_resetData(model_, data_);
      mj_kinematics(model_, data_);  // poses to draw the last frame from; nothing that could fail again
      mj_camlight(model_, data_);
      model_->opt.enableflags = flags;
      report.diverged = true;
      return report;
    }
    resting_.after_step(model_, data_);
    if (robot_) update_grasp(report);
    if (state_updates_) update_states_after_physics_step(*this, model_->opt.timestep);
  }
  if (state_updates_) update_states_after_env_step(*this, substeps * model_->opt.timestep);
  // Hidden objects fell freely (they collide with nothing): back, at rest.
  for (size_t object = 0; object < hidden_.size(); ++object) {
    if (hidden_[object]) keep_out(static_cast<int>(object));
  }
  return report;
}

void World::hide(int object) {
  const SceneObject& o = scene_->objects().at(object);
  if (o.fixed || o.grasp_weld < 0) throw Error("world: '" + o.name + "' is not a free object and cannot be hidden");
  if (hidden_[object]) return;
  if (grasped_ == object) release();
  for (const Scene::Attachment& a : scene_->attachments()) {
    if ((a.object == object || a.to == object) && a.weld >= 0) data_->eq_active[a.weld] = 0;
  }
  for (const int g : o.geoms) model_->geom_contype[g] = model_->geom_conaffinity[g] = 0;
  hidden_[object] = 1;
  keep_out(object);
  mj_forward(model_, data_);
}

void World::keep_out(int object) {
  // Under the floor and outside every room, each object at its own place.
  constexpr double kOut = -1000, kSpacing = 3, kDepth = -10;
  const int joint = model_->body_jntadr[scene_->objects()[object].body];
  mjtNum* qpos = data_->qpos + model_->jnt_qposadr[joint];
  qpos[0] = kOut - kSpacing * object;
  qpos[1] = kOut;
  qpos[2] = kDepth;
  mju_zero(data_->qvel + model_->jnt_dofadr[joint], 6);
}

void World::make_real(int object) {
  for (const int g : scene_->objects()[object].geoms) {
    model_->geom_contype[g] = scene_->model()->geom_contype[g];
    model_->geom_conaffinity[g] = scene_->model()->geom_conaffinity[g];
  }
  hidden_[object] = 0;
}

void World::reveal(int object, const Eigen::Vector3d& pos) {
  const SceneObject& o = scene_->objects().at(object);
  if (!hidden_.at(object)) return;
  make_real(object);
  const int joint = model_->body_jntadr[o.body];
  mjtNum* qpos = data_->qpos + model_->jnt_qposadr[joint];
  for (int k = 0; k < 3; ++k) qpos[k] = pos[k];
  mju_mat2Quat(qpos + 3, o.mat.data());
  mju_zero(data_->qvel + model_->jnt_dofadr[joint], 6);
  mj_forward(model_, data_);
}

void World::set_sleeping(bool enabled) {
  if (enabled == sleeping()) return;
  if (enabled) {
    model_->opt.enableflags |= mjENBL_SLEEP;
    return;
  }
  model_->opt.enableflags &= ~mjENBL_SLEEP;
  resting_.clear();
  mj_forward(model_, data_);  // MuJoCo wakes every tree when sleeping is off
}

bool World::sleeping() const {
  return model_->opt.enableflags & mjENBL_SLEEP;
}

bool World::asleep(int object) const {
  const std::vector<int>& trees = object_trees_.at(object);
  return !trees.empty() &&
         std::all_of(trees.begin(), trees.end(), [&](int t) { return data_->tree_asleep[t] >= 0; });
}

int World::sleepers() const {
  int n = 0;
  for (size_t o = 0; o < object_trees_.size(); ++o) n += asleep(static_cast<int>(o));
  return n;
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
  std::vector<int> left, right;  // bodies each finger touches
  for (int c = 0; c < data_->ncon; ++c) {
    const mjContact& con = data_->contact[c];
    const int b1 = model_->geom_bodyid[con.geom[0]], b2 = model_->geom_bodyid[con.geom[1]];
    for (const auto& [finger, other] : {std::pair{b1, b2}, std::pair{b2, b1}}) {
      if (finger == r.left_finger_body) left.push_back(other);
      if (finger == r.right_finger_body) right.push_back(other);
    }
  }
  // Both fingers on `body` itself (a link), or anywhere on the tree rooted there (an object).
  const auto touched = [&](int body, bool tree) {
    const auto on = [&](int b) { return b == body || (tree && model_->body_rootid[b] == body); };
    return std::any_of(left.begin(), left.end(), on) && std::any_of(right.begin(), right.end(), on);
  };
  const auto& objects = scene_->objects();
  for (size_t i = 0; i < objects.size(); ++i) {
    const SceneObject& o = objects[i];
    // Links of articulated objects (drawers, doors) are held where they are,
    // whatever the object weighs: the joint carries the load.
    for (size_t k = 0; k < o.joints.size(); ++k) {
      const int link = model_->jnt_bodyid[o.joints[k]];
      if (o.link_welds[k] >= 0 && touched(link, false)) {
        attach(static_cast<int>(i), o.link_welds[k]);
        return;
      }
    }
    if (o.fixed || !touched(o.body, true)) continue;
    if (model_->body_subtreemass[o.body] > kGraspMassLimit) {
      report.grasp_refused = true;
      return;
    }
    attach(static_cast<int>(i), o.grasp_weld);
    return;
  }
}

int World::carried_object() const {
  return grasped_ >= 0 && grasped_body() == scene_->objects()[grasped_].body ? grasped_ : -1;
}

int World::grasped_body() const {
  return grasped_weld_ < 0 ? -1 : model_->eq_obj2id[grasped_weld_];
}

void World::hold_in_place(int weld) {
  const int holder = model_->eq_obj1id[weld], body = model_->eq_obj2id[weld];
  // Weld error in MuJoCo (2.2.2 to 4.0.1): (x_holder + R_holder * relpos) - (x_body + R_body * anchor),
  // orientation q_holder * relquat vs q_body. Zero error in the current pose:
  mjtNum* eq = model_->eq_data + mjNEQDATA * weld;
  mjtNum delta[3], relpos[3], holder_inverse[4];
  mju_zero3(eq);  // anchor at the body's origin
  mju_sub3(delta, data_->xpos + 3 * body, data_->xpos + 3 * holder);
  mju_mulMatTVec3(relpos, data_->xmat + 9 * holder, delta);
  mju_copy3(eq + 3, relpos);
  mju_negQuat(holder_inverse, data_->xquat + 4 * holder);
  mju_mulQuat(eq + 6, holder_inverse, data_->xquat + 4 * body);
  eq[10] = 1.0;  // torquescale
  data_->eq_active[weld] = 1;
}

void World::attach(int object, int weld) {
  // Taken hold of, an attached object comes off what it was attached to (as
  // OmniGibson's AttachedTo gives way to a pull).
  for (const Scene::Attachment& a : scene_->attachments()) {
    if (a.weld >= 0 && (a.object == object || a.to == object)) data_->eq_active[a.weld] = 0;
  }
  hold_in_place(weld);  // the grasp welds go from the gripper to the object
  grasped_ = object;
  grasped_weld_ = weld;
}

bool World::attach_objects(int object, int to) {
  for (const Scene::Attachment& a : scene_->attachments()) {
    if (a.object != object || a.to != to || a.weld < 0) continue;
    mj_kinematics(model_, data_);
    hold_in_place(a.weld);
    return true;
  }
  return false;
}

bool World::hold(int object) {
  const SceneObject& o = scene_->objects().at(object);
  if (o.fixed || o.grasp_weld < 0) throw Error("world: '" + o.name + "' is not a free object");
  if (model_->body_subtreemass[o.body] > kGraspMassLimit) return false;
  release();
  attach(object, o.grasp_weld);
  return true;
}

void World::release() {
  if (grasped_ < 0) return;
  data_->eq_active[grasped_weld_] = 0;
  grasped_ = grasped_weld_ = -1;
}

bool World::carry_grasped(mjData* d) const {
  const int body = grasped_body();
  if (body < 0 || model_->body_jntnum[body] != 1 || model_->jnt_type[model_->body_jntadr[body]] != mjJNT_FREE) {
    return false;  // nothing held, or a link: it stays on its joint
  }
  // The weld's relative pose, applied: x_body = x_hand + R_hand relpos, q_body = q_hand relquat.
  const mjtNum* eq = model_->eq_data + mjNEQDATA * grasped_weld_;
  const int hand = robot_->gripper_body, joint = model_->body_jntadr[body];
  mjtNum* qpos = d->qpos + model_->jnt_qposadr[joint];
  mjtNum offset[3];
  mju_mulMatVec3(offset, d->xmat + 9 * hand, eq + 3);
  mju_add3(qpos, d->xpos + 3 * hand, offset);
  mju_mulQuat(qpos + 3, d->xquat + 4 * hand, eq + 6);
  mju_zero(d->qvel + model_->jnt_dofadr[joint], 6);
  return true;
}

void World::command_gripper(bool open) {
  const double finger = open ? Robot::kGripperOpen : 0.0;
  command_position(robot_->gripper_left, finger);
  command_position(robot_->gripper_right, finger);
}

void World::set_robot_configuration(const Pose2& base, const double* torso_and_arm) {
  pose_robot(base, torso_and_arm);
  mj_forward(model_, data_);
}

void World::pose_robot(const Pose2& base, const double* torso_and_arm) {
  const Robot& r = *robot_;
  data_->qpos[r.base_x.qpos] = base.x;
  data_->qpos[r.base_y.qpos] = base.y;
  data_->qpos[r.base_yaw.qpos] = base.yaw;
  const auto joints = r.torso_and_arm();
  for (size_t k = 0; k < joints.size(); ++k) {
    data_->qpos[joints[k]->qpos] = torso_and_arm[k];
    data_->ctrl[joints[k]->actuator] = torso_and_arm[k];
    velocity_command_[joints[k]->actuator] = 0;
  }
  for (const RobotJoint* j : {&r.base_x, &r.base_y, &r.base_yaw}) data_->qvel[j->dof] = 0;
  for (const RobotJoint* j : joints) data_->qvel[j->dof] = 0;
  base_command_[0] = base_command_[1] = base_command_[2] = 0;
  mj_kinematics(model_, data_);
  if (carry_grasped(data_)) mj_kinematics(model_, data_);
}

void World::set_head(double pan, double tilt) {
  const Robot& r = *robot_;
  for (auto [joint, angle] : {std::pair{&r.head_pan, pan}, {&r.head_tilt, tilt}}) {
    const double q = std::clamp(angle, joint->low, joint->high);
    data_->qpos[joint->qpos] = q;
    data_->ctrl[joint->actuator] = q;
    data_->qvel[joint->dof] = 0;
    velocity_command_[joint->actuator] = 0;
  }
  mj_kinematics(model_, data_);
  mj_camlight(model_, data_);
}

}  // namespace chore
