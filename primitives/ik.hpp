// Inverse kinematics of the arm (and torso): damped least squares on the
// gripper site's Jacobian, on the robot's own kinematics, so the world itself
// is untouched. The building block of the primitives' Cartesian motions.
#pragma once

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "primitives/kinematics.hpp"
#include "world/world.hpp"

namespace chore {

struct IkTarget {
  Eigen::Vector3d position;                 // of the gripper_center site, world frame
  std::optional<Eigen::Vector3d> approach;  // direction the gripper's x axis should point, if any
  std::optional<Eigen::Vector3d> closing;   // direction of its y axis (the fingers' line), if any
};

struct IkOptions {
  int iterations = 200;
  double damping = 0.05;              // lambda of damped least squares
  double position_tolerance = 0.005;  // m
  double angle_tolerance = 0.05;      // rad between approach and the gripper's x axis
  bool use_torso = true;
  // Solve as if the base stood here / the arm started here (default: as in the world).
  std::optional<Pose2> base;
  std::optional<ArmConfiguration> start;
};

struct IkResult {
  bool success = false;
  double position_error = 0, angle_error = 0;
  ArmConfiguration joints{};  // the solution (or the best found); torso as given without use_torso
  std::string reason;         // why it failed
};

// Solves on the robot's own kinematics (primitives/kinematics.hpp), from the
// world's base and arm at each call: the world itself is untouched.
class IkSolver {
 public:
  explicit IkSolver(const World& world);
  IkSolver(const IkSolver&) = delete;
  IkSolver& operator=(const IkSolver&) = delete;
  // Starts from the world's configuration (or options.start); joint limits are respected.
  IkResult solve(const IkTarget& target, const IkOptions& options = {});

 private:
  const World& world_;
  RobotKinematics kinematics_;
};

// One solve on a fresh scratch copy.
IkResult solve_ik(const World& world, const IkTarget& target, const IkOptions& options = {});

}  // namespace chore
