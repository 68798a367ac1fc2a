// Collision-free paths of the torso and arm in joint space: OMPL RRTConnect
// with MuJoCo's collision detection on a scratch copy of the world as the
// validity check, shortened by OMPL's simplifier. The manipulation primitives
// move between poses along these paths.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "env/world/world.hpp"
#include "primitives/ik.hpp"

namespace chore {

struct ArmPath {
  bool success = false;
  std::vector<ArmConfiguration> waypoints;  // start first, goal last
  std::string reason;
};

// Collision queries on the world's scratch data (slot 1) holding the world's
// positions at construction, so the world itself is never touched.
class ArmCollisionChecker {
 public:
  explicit ArmCollisionChecker(const World& world);
  ArmCollisionChecker(const ArmCollisionChecker&) = delete;
  ArmCollisionChecker& operator=(const ArmCollisionChecker&) = delete;
  // Whether the robot (or what it holds) with torso and arm at q touches
  // anything else, with the base where it is or at `base`.
  bool collides(const double* q, const Pose2* base = nullptr);

 private:
  const World& world_;
  const mjModel_* model_;
  mjData_* data_;
  int robot_, held_ = -1;
};

// Whether the robot (or what it holds) in configuration q touches anything else.
bool arm_in_collision(const World& world, const ArmConfiguration& q);

// A path from the world's current arm configuration to `goal`; a held object
// moves with the hand and must not collide either. The same seed gives the same path.
ArmPath plan_arm_path(const World& world, const ArmConfiguration& goal, uint64_t seed,
                      unsigned iterations = 2000);

}  // namespace chore
