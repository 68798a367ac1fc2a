#include "primitives/ik.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <memory>

#include "base/error.hpp"

namespace chore {

IkSolver::IkSolver(const World& world) : world_(world), kinematics_(world) {}

IkResult solve_ik(const World& world, const IkTarget& target, const IkOptions& options) {
  return IkSolver(world).solve(target, options);
}

IkResult IkSolver::solve(const IkTarget& target, const IkOptions& options) {
  const Robot* robot = world_.robot();
  const Pose2 base = options.base ? *options.base : world_.base_pose();
  ArmConfiguration q = options.start ? *options.start : arm_configuration(world_);
  const auto joints = robot->torso_and_arm();
  // Columns of the Jacobian that move: the torso's only with use_torso.
  const int first = options.use_torso ? 0 : 1, n = static_cast<int>(joints.size()) - first;
  const bool orient = target.approach || target.closing;
  const int rows = orient ? 6 : 3;

  IkResult result;
  for (int it = 0; it <= options.iterations; ++it) {
    kinematics_.set(base, q);
    const Eigen::Vector3d p = kinematics_.site_position();
    const Eigen::Matrix3d rotation = kinematics_.site_rotation();
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
    // The site's x axis is the gripper's approach direction, y the closing one (tiago.xml).
    if (target.approach) align(rotation.col(0), target.approach->normalized());
    if (target.closing) align(rotation.col(1), target.closing->normalized());
    if (result.position_error < options.position_tolerance && result.angle_error < options.angle_tolerance) {
      result.success = true;
      break;
    }
    if (it == options.iterations) break;
    const Eigen::MatrixXd jac = kinematics_.site_jacobian().block(0, first, rows, n);
    // dq = J^T (J J^T + lambda^2 I)^-1 e
    const Eigen::MatrixXd jjt =
        jac * jac.transpose() + options.damping * options.damping * Eigen::MatrixXd::Identity(rows, rows);
    const Eigen::VectorXd dq = jac.transpose() * jjt.ldlt().solve(error);
    for (int k = 0; k < n; ++k) {
      const RobotJoint& joint = *joints[static_cast<size_t>(first + k)];
      double& value = q[static_cast<size_t>(first + k)];
      value = std::clamp(value + dq[k], joint.low, joint.high);
    }
  }
  result.joints = q;
  if (!result.success) {
    result.reason = "no arm configuration reaches the target: " + std::to_string(result.position_error) + " m and " +
                    std::to_string(result.angle_error) + " rad off after " + std::to_string(options.iterations) +
                    " iterations";
  }
  return result;
}

}  // namespace chore
