// Inverse kinematics of the arm (and torso): damped least squares on MuJoCo's
// site Jacobian, on a scratch copy of the world's state, so the world itself
// is untouched. The building block of the primitives' Cartesian motions.
#pragma once

#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

#include "env/world/world.hpp"

namespace chore {

struct IkTarget {
  Eigen::Vector3d position;                 // of the gripper_center site, world frame
  std::optional<Eigen::Vector3d> approach;  // direction the gripper's x axis should point, if any
};

struct IkOptions {
  int iterations = 200;
  double damping = 0.05;           // lambda of damped least squares
  double position_tolerance = 0.005;  // m
  double angle_tolerance = 0.05;      // rad between approach and the gripper's x axis
  bool use_torso = true;
};

struct IkResult {
  bool success = false;
  double position_error = 0, angle_error = 0;
  std::vector<double> joints;  // torso, then arm_1..7: the solution (or the best found)
  std::string reason;          // why it failed
};

// Starts from the world's current configuration; joint limits are respected.
IkResult solve_ik(const World& world, const IkTarget& target, const IkOptions& options = {});

}  // namespace chore
