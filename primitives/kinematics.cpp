#include "primitives/kinematics.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>

#include "base/error.hpp"

namespace chore {

ArmConfiguration arm_configuration(const World& world) {
  ArmConfiguration q;
  const auto joints = world.robot()->torso_and_arm();
  for (size_t k = 0; k < joints.size(); ++k) q[k] = world.data()->qpos[joints[k]->qpos];
  return q;
}

RobotKinematics::RobotKinematics(const World& world)
    : world_(world), qpos_(world.data()->qpos, world.data()->qpos + world.model()->nq) {
  if (!world.robot()) throw Error("kinematics: the scene has no robot");
  const mjModel* m = world.model();
  pose_.resize(m->nbody);
  pose_[0] = {{0, 0, 0}, {1, 0, 0, 0}};
  axis_.resize(m->njnt);
  anchor_.resize(m->njnt);
  const int robot = m->body_rootid[world.robot()->gripper_body];
  const int carried = world.carried_object();
  if (carried >= 0) {
    load_root_ = world.scene().objects()[carried].body;
    weld_ = world.grasp_weld();
  }
  // Body ids list parents before children.
  for (int b = 1; b < m->nbody; ++b) {
    if (m->body_rootid[b] == robot) bodies_.push_back(b);
    if (load_root_ >= 0 && m->body_rootid[b] == load_root_) load_bodies_.push_back(b);
  }
  for (int g = 0; g < m->ngeom; ++g) {
    if (!m->geom_contype[g] && !m->geom_conaffinity[g]) continue;
    const int root = m->body_rootid[m->geom_bodyid[g]];
    if (root == robot) robot_geoms_.push_back(g);
    if (load_root_ >= 0 && root == load_root_) load_geoms_.push_back(g);
  }
  ArmConfiguration q;
  const auto joints = world.robot()->torso_and_arm();
  for (size_t k = 0; k < joints.size(); ++k) q[k] = qpos_[joints[k]->qpos];
  set(world.base_pose(), q);
}

// One body from its parent's pose and its joints, as mj_kinematics does it.
void RobotKinematics::forward(int b, const double* qpos) {
  const mjModel* m = world_.model();
  const BodyPose& parent = pose_[m->body_parentid[b]];
  BodyPose& x = pose_[b];
  double v[3];
  mju_rotVecQuat(v, m->body_pos + 3 * b, parent.quat);
  mju_add3(x.pos, parent.pos, v);
  mju_mulQuat(x.quat, parent.quat, m->body_quat + 4 * b);
  for (int j = m->body_jntadr[b]; j < m->body_jntadr[b] + m->body_jntnum[b]; ++j) {
    const int a = m->jnt_qposadr[j];
    if (m->jnt_type[j] == mjJNT_FREE) {
      mju_copy3(x.pos, qpos + a);
      mju_copy4(x.quat, qpos + a + 3);
      mju_normalize4(x.quat);
      continue;
    }
    double axis[3], anchor[3];
    mju_rotVecQuat(axis, m->jnt_axis + 3 * j, x.quat);
    mju_rotVecQuat(anchor, m->jnt_pos + 3 * j, x.quat);
    mju_addTo3(anchor, x.pos);
    axis_[j] = Eigen::Vector3d(axis[0], axis[1], axis[2]);
    anchor_[j] = Eigen::Vector3d(anchor[0], anchor[1], anchor[2]);
    if (m->jnt_type[j] == mjJNT_SLIDE) {
      mju_addToScl3(x.pos, axis, qpos[a] - m->qpos0[a]);
      continue;
    }
    double local[4];
    if (m->jnt_type[j] == mjJNT_BALL) {
      mju_copy4(local, qpos + a);
      mju_normalize4(local);
    } else {
      mju_axisAngle2Quat(local, m->jnt_axis + 3 * j, qpos[a] - m->qpos0[a]);
    }
    mju_mulQuat(x.quat, x.quat, local);
    // Rotation about the anchor, not the body's origin.
    mju_rotVecQuat(v, m->jnt_pos + 3 * j, x.quat);
    mju_sub3(x.pos, anchor, v);
  }
  mju_normalize4(x.quat);
}

void RobotKinematics::set(const Pose2& base, const ArmConfiguration& q) {
  const Robot& r = *world_.robot();
  qpos_[r.base_x.qpos] = base.x;
  qpos_[r.base_y.qpos] = base.y;
  qpos_[r.base_yaw.qpos] = base.yaw;
  const auto joints = r.torso_and_arm();
  for (size_t k = 0; k < joints.size(); ++k) qpos_[joints[k]->qpos] = q[k];
  for (int b : bodies_) forward(b, qpos_.data());
  if (load_root_ < 0) return;
  // The grip's relative pose (World::carry_grasped): x = x_hand + R_hand relpos, q = q_hand relquat.
  const mjtNum* eq = world_.model()->eq_data + mjNEQDATA * weld_;
  const BodyPose& hand = pose_[r.gripper_body];
  const int free_joint = world_.model()->body_jntadr[load_root_];
  double* root = qpos_.data() + world_.model()->jnt_qposadr[free_joint];
  double offset[3];
  mju_rotVecQuat(offset, eq + 3, hand.quat);
  mju_add3(root, hand.pos, offset);
  mju_mulQuat(root + 3, hand.quat, eq + 6);
  for (int b : load_bodies_) forward(b, qpos_.data());
}

Eigen::Vector3d RobotKinematics::site_position() const {
  const mjModel* m = world_.model();
  const int site = world_.robot()->gripper_site;
  const BodyPose& x = pose_[m->site_bodyid[site]];
  double v[3];
  mju_rotVecQuat(v, m->site_pos + 3 * site, x.quat);
  return {x.pos[0] + v[0], x.pos[1] + v[1], x.pos[2] + v[2]};
}

Eigen::Matrix3d RobotKinematics::site_rotation() const {
  const mjModel* m = world_.model();
  const int site = world_.robot()->gripper_site;
  double quat[4], mat[9];
  mju_mulQuat(quat, pose_[m->site_bodyid[site]].quat, m->site_quat + 4 * site);
  mju_quat2Mat(mat, quat);
  return Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(mat);
}

Eigen::Matrix<double, 6, 1 + Robot::kArmJoints> RobotKinematics::site_jacobian() const {
  const Eigen::Vector3d p = site_position();
  const auto joints = world_.robot()->torso_and_arm();
  Eigen::Matrix<double, 6, 1 + Robot::kArmJoints> jac;
  for (size_t k = 0; k < joints.size(); ++k) {
    const int j = joints[k]->joint;
    const Eigen::Vector3d& a = axis_[j];
    if (world_.model()->jnt_type[j] == mjJNT_SLIDE) {
      jac.col(static_cast<Eigen::Index>(k)) << a, Eigen::Vector3d::Zero();
    } else {
      jac.col(static_cast<Eigen::Index>(k)) << a.cross(p - anchor_[j]), a;
    }
  }
  return jac;
}

void RobotKinematics::geom_pose(int geom, double* xpos, double* xmat) const {
  const mjModel* m = world_.model();
  const BodyPose& x = pose_[m->geom_bodyid[geom]];
  double v[3], quat[4];
  mju_rotVecQuat(v, m->geom_pos + 3 * geom, x.quat);
  mju_add3(xpos, x.pos, v);
  mju_mulQuat(quat, x.quat, m->geom_quat + 4 * geom);
  mju_quat2Mat(xmat, quat);
}

}  // namespace chore
