// Collision-free paths of the torso and arm in joint space: OMPL RRTConnect
// with MuJoCo's collision detection on a scratch copy of the world as the
// validity check, shortened by OMPL's simplifier. The manipulation primitives
// move between poses along these paths.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "env/world/world.hpp"

namespace chore {

// torso, arm_1 .. arm_7
using ArmConfiguration = std::array<double, 1 + Robot::kArmJoints>;

struct ArmPath {
  bool success = false;
  std::vector<ArmConfiguration> waypoints;  // start first, goal last
  std::string reason;
};

// Whether the robot in configuration q touches anything (the scene, objects).
bool arm_in_collision(const World& world, const ArmConfiguration& q);

// A path from the world's current arm configuration to `goal`.
ArmPath plan_arm_path(const World& world, const ArmConfiguration& goal, double time_limit = 1.0);

}  // namespace chore
