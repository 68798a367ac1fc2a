#include "primitives/ik.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>

#include "env/world/error.hpp"

namespace chore {

ArmConfiguration arm_configuration(const World& world) {
  ArmConfiguration q;
  const auto joints = world.robot()->torso_and_arm();
  for (size_t k = 0; k < joints.size(); ++k) q[k] = world.data()->qpos[joints[k]->qpos];
  return q;
}

IkSolver::IkSolver(const World& world) : world_(world), data_(nullptr) {
  if (!world.robot()) throw Error("ik: the scene has no robot");
  data_ = world.scratch(0);
}

IkResult solve_ik(const World& world, const IkTarget& target, const IkOptions& options) {
  return IkSolver(world).solve(target, options);
}

IkResult IkSolver::solve(const IkTarget& target, const IkOptions& options) {
  const Robot* robot = world_.robot();
  const mjModel* m = world_.model();
  mjData* d = data_;
  // Only the robot's joints change here: copy just positions back from the world.
  mju_copy(d->qpos, world_.data()->qpos, m->nq);
  if (options.base) {
    d->qpos[robot->base_x.qpos] = options.base->x;
    d->qpos[robot->base_y.qpos] = options.base->y;
    d->qpos[robot->base_yaw.qpos] = options.base->yaw;
  }
  if (options.start) {
    const auto all = robot->torso_and_arm();
    for (size_t k = 0; k < all.size(); ++k) d->qpos[all[k]->qpos] = (*options.start)[k];
  }

  std::vector<const RobotJoint*> joints;
  if (options.use_torso) joints.push_back(&robot->torso);
  for (const RobotJoint& j : robot->arm) joints.push_back(&j);
  const int n = static_cast<int>(joints.size());
  const int site = robot->gripper_site;
  const bool orient = target.approach || target.closing;
  const int rows = orient ? 6 : 3;

  Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor> jacp(3, m->nv), jacr(3, m->nv);
  IkResult result;
  for (int it = 0; it <= options.iterations; ++it) {
    mj_kinematics(m, d);
    mj_comPos(m, d);
    const Eigen::Vector3d p(d->site_xpos[3 * site], d->site_xpos[3 * site + 1], d->site_xpos[3 * site + 2]);
    // The site's x axis is the gripper's approach direction (tiago.xml).
    const Eigen::Vector3d x(d->site_xmat[9 * site], d->site_xmat[9 * site + 3], d->site_xmat[9 * site + 6]);
    Eigen::VectorXd error(rows);
    error.head<3>() = target.position - p;
    result.position_error = error.head<3>().norm();
    result.angle_error = 0;
    // Rotations taking each constrained axis towards its target, summed.
    if (orient) error.tail<3>().setZero();
    const auto align = [&](const Eigen::Vector3d& axis, const Eigen::Vector3d& want) {
      error.tail<3>() += axis.cross(want);
      result.angle_error = std::max(result.angle_error, std::acos(std::clamp(axis.dot(want), -1.0, 1.0)));
    };
    if (target.approach) align(x, target.approach->normalized());
    if (target.closing) {
      const Eigen::Vector3d y(d->site_xmat[9 * site + 1], d->site_xmat[9 * site + 4], d->site_xmat[9 * site + 7]);
      align(y, target.closing->normalized());
    }
    if (result.position_error < options.position_tolerance && result.angle_error < options.angle_tolerance) {
      result.success = true;
      break;
    }
    if (it == options.iterations) break;
    mj_jacSite(m, d, jacp.data(), jacr.data(), site);
    Eigen::MatrixXd jac(rows, n);
    for (int k = 0; k < n; ++k) {
      jac.block(0, k, 3, 1) = jacp.col(joints[k]->dof);
      if (orient) jac.block(3, k, 3, 1) = jacr.col(joints[k]->dof);
    }
    // dq = J^T (J J^T + lambda^2 I)^-1 e
    const Eigen::MatrixXd jjt = jac * jac.transpose() +
                                options.damping * options.damping * Eigen::MatrixXd::Identity(rows, rows);
    const Eigen::VectorXd dq = jac.transpose() * jjt.ldlt().solve(error);
    for (int k = 0; k < n; ++k) {
      double& q = d->qpos[joints[k]->qpos];
      q = std::clamp(q + dq[k], joints[k]->low, joints[k]->high);
    }
  }
  const auto all = robot->torso_and_arm();
  for (size_t k = 0; k < all.size(); ++k) result.joints[k] = d->qpos[all[k]->qpos];
  if (!result.success) {
    result.reason = "no arm configuration reaches the target: " +
                    std::to_string(result.position_error) + " m and " +
                    std::to_string(result.angle_error) + " rad off after " +
                    std::to_string(options.iterations) + " iterations";
  }
  return result;
}

}  // namespace chore
