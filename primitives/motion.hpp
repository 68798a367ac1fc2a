// The motions primitives are composed of, executed in one mode: planned,
// smoothed and tracked by the robot's controllers in physics, or (symbolic)
// checked and applied kinematically. Internal to primitives/.
#pragma once

#include <Eigen/Core>

#include <array>
#include <functional>
#include <random>

#include "primitives/base_planner.hpp"
#include "primitives/ik.hpp"
#include "primitives/primitive.hpp"

namespace chore {

class Motion {
 public:
  // `look_at`: the object the primitive acts on, which the head's camera follows.
  Motion(World& world, const PrimitiveOptions& options, uint64_t seed, int look_at, PrimitiveResult& result);

  World& world() { return world_; }
  bool physical() const { return options_.mode == ExecutionMode::physical; }
  // A fresh seed for a planner or sampler, from the primitive's seed.
  uint64_t next_seed() { return seeds_(); }

  // Each motion returns false after setting result's status and reason.
  bool fail(PrimitiveStatus status, const std::string& reason);

  // Collision-free arm path to `goal` (torso and arm), planned and executed.
  bool arm_to(const ArmConfiguration& goal);
  // Collision-free base path to `goal` for `footprint`, planned and executed.
  bool base_to(const Pose2& goal, const Footprint& footprint);
  // The hand's centre along a straight line by `delta` (world frame), keeping
  // its orientation, at `speed` m/s, as far as IK can follow; less than
  // `min_fraction` of it is a motion-planning failure. With `until_contact` it
  // stops at the first contact of the hand (or what it holds) with anything
  // else; touched() says whether it did; then, cut short by IK before any
  // contact, it fails below `min_fraction`. In symbolic mode the state rules (soaking, cleaning) run
  // at every waypoint for the time the motion would take.
  bool line(const Eigen::Vector3d& delta, bool until_contact, double speed = 0.2, double min_fraction = 1.0);
  bool touched() const { return touched_; }
  // The hand's pose turned by `angle` (rad, right-handed) about the line
  // through `pivot` along `axis`, as a door's handle turns with the door
  // (without `turn_hand` its position only, pointing as IK finds),
  // otherwise as line() (`speed` along the hand's path).
  bool arc(const Eigen::Vector3d& pivot, const Eigen::Vector3d& axis, double angle, bool until_contact,
           double speed = 0.2, double min_fraction = 1.0, bool turn_hand = true);
  // The base along a straight line by `delta` (world frame, heading kept), the
  // arm held: the hand, and what it holds, follow (pulling a drawer open).
  bool base_line(const Eigen::Vector3d& delta, double speed = 0.15);
  // The base turned by `angle` (rad, about +z) round the vertical line
  // through `pivot`, the arm held: the hand turns with it, and the body
  // `moving` (the door whose handle it turns about its hinge). As far as the
  // body's map is free; less than `min_fraction` of the way is a
  // motion-planning failure.
  bool base_arc(const Eigen::Vector3d& pivot, double angle, int moving, double speed = 0.15, double min_fraction = 1.0);
  // Opens or closes the gripper and waits for the fingers; the assistive
  // grasp attaches or releases as they do.
  void gripper(bool open);
  // Holds still for `seconds` (physics runs; symbolic: the state rules run once over that time).
  void wait(double seconds);
  // Tucked arm when the hand is empty; while it holds something, the first
  // carry pose (kCarryConfigurations) that touches nothing.
  bool tuck();
  // Points the head's camera at the object, as OmniGibson's Tiago primitives
  // track theirs, so that the robot sees what it acts on: physical motions
  // command the head at every control step (its servos follow); a symbolic
  // primitive calls this once at its end, and the head is set there.
  void look_at_object();

  // The hand's centre and axes now.
  Eigen::Vector3d hand_position() const;
  Eigen::Vector3d hand_axis(int column) const;  // 0: approach, 1: closing
  IkSolver& ik() { return ik_; }

 private:
  // line() and arc(): the hand through target_at(f) for f in (0, 1], `length`
  // m in all, named `what` in failures.
  bool follow(const std::function<IkTarget(double)>& target_at, double length, const char* what, bool until_contact,
              double speed, double min_fraction);
  // base_line() and base_arc(): the base through pose_at(f) for f in (0, 1],
  // `length` m in all; failing with `blocked` where the map stops it short
  // of min_fraction.
  bool base_path(const std::function<Pose2(double)>& pose_at, double length, double speed, double min_fraction,
                 const char* blocked, int moving = -1);
  void step_physics(int env_steps);  // with divergence bookkeeping
  bool hand_in_contact() const;
  // Steps until the torso and arm are within `tolerance` (rad) of `goal`, at
  // most kSettleSteps control steps; goal.size() when they are, else the
  // joint furthest from it.
  size_t settle_arm(const ArmConfiguration& goal, double tolerance);
  bool track_arm(const std::vector<ArmConfiguration>& path, double max_speed);

  World& world_;
  PrimitiveOptions options_;
  std::mt19937_64 seeds_;
  PrimitiveResult& result_;
  IkSolver ik_;
  int look_at_;
  bool touched_ = false;
};

// Arm configurations the primitives move through: tucked (home), untucked
// (hand out in front, ready to reach) and carrying (hand up and in, holding).
extern const ArmConfiguration kTuckedConfiguration;
extern const ArmConfiguration kUntuckedConfiguration;
extern const ArmConfiguration kCarryConfiguration;
// kCarryConfiguration, then the same pose turned about the shoulder (the hand
// still pointing down, 0.3-0.45 m from the base's centre): where the robot
// stopped beside furniture to pick (a fridge by the table), the elbow of the
// first meets it, and the arm left out over where it picked walled the base in.
extern const std::array<ArmConfiguration, 5> kCarryConfigurations;
// Where reach() starts the IK, in turn: damped least squares converges to a
// solution near its start, and from the untucked pose alone the hand points
// down no lower than 0.2 m and no higher than 1.0 m above the floor, where
// the arm reaches 0.1 to 1.2 m (Ik.ThreeStartsReachFromTheFloorToAboveACounter):
// untucked, then the arm reaching down in front of the base, then up over it.
extern const std::array<ArmConfiguration, 3> kReachStarts;

}  // namespace chore
