// Collision-free paths of the torso and arm in joint space: OMPL RRTConnect
// with MuJoCo's narrow-phase collision functions as the validity check,
// shortened by OMPL's simplifier. The manipulation primitives move between
// poses along these paths.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "primitives/kinematics.hpp"
#include "world/aabb.hpp"
#include "world/world.hpp"

namespace chore {

struct ArmPath {
  bool success = false;
  std::vector<ArmConfiguration> waypoints;  // start first, goal last
  std::string reason;
};

// Collision queries of the robot and its load against the rest of the world,
// as the world stands at construction: the robot's own kinematics place its
// geoms (primitives/kinematics.hpp), MuJoCo's narrow-phase functions test them
// against the geoms whose boxes they reach. The world's scratch data holds the
// geom poses; the world itself is never touched. Contacts within the
// robot (and with its load) do not count; of a cloth load only the part in
// the hand counts (the rest drapes and gives way).
class ArmCollisionChecker {
 public:
  explicit ArmCollisionChecker(const World& world);
  ArmCollisionChecker(const ArmCollisionChecker&) = delete;
  ArmCollisionChecker& operator=(const ArmCollisionChecker&) = delete;
  // Whether the robot (or what it holds) with torso and arm at q touches
  // anything else, with the base where it is or at `base`. With a clearance,
  // what the torso and arm move (and the load) touches what comes that close
  // (the base stands on the floor whatever the clearance).
  bool collides(const double* q, const Pose2* base = nullptr, double clearance = 0.0);
  // Whether the hand (gripper and fingers) or what it holds touches anything
  // else (but `ignored_object`), with the base where it is or at `base`.
  bool hand_touches(const ArmConfiguration& q, const Pose2* base = nullptr, int ignored_object = -1);
  // Where the whole load (a cloth's whole sheet) meets anything but the robot
  // at q, the base where it is: MuJoCo's contacts as its collision pass would
  // write them (no forces), and the load's box. What a symbolic motion's state
  // rules need at each waypoint, without posing the world.
  Aabb load_contacts(const ArmConfiguration& q, std::vector<mjContact_>& contacts);

 private:
  struct Box {
    int geom;
    Eigen::Vector3d lo, hi;
    bool driven_over;  // by the base (base_planner.hpp), as its map takes it
  };
  bool touches(const std::vector<int>& mine, int ignored_object, double clearance);
  // Each contact of `mine` (posed in data_) with the others, until `visit` returns true.
  template <typename Visit>
  bool for_each_contact(const std::vector<int>& mine, int ignored_object, double clearance, Visit visit);

  const World& world_;
  RobotKinematics kinematics_;
  mjData_* data_;
  std::vector<Box> others_;          // what the robot can touch, with world boxes
  std::vector<int> robot_and_load_;  // colliding geoms moving with the robot
  std::vector<int> hand_and_load_;
  std::vector<int> whole_load_;              // every geom of the load, a cloth's draped part too
  std::vector<unsigned char> moved_by_arm_;  // by geom id: a clearance applies to it
};

// Whether the robot (or what it holds) in configuration q touches anything else.
bool arm_in_collision(const World& world, const ArmConfiguration& q);

// A path from the world's current arm configuration to `goal`; a held object
// moves with the hand and must not collide either. The same seed gives the same path.
ArmPath plan_arm_path(const World& world, const ArmConfiguration& goal, uint64_t seed, unsigned iterations = 2000);

}  // namespace chore
