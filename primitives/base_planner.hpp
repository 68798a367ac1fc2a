// Collision-free paths of the robot's base in SE2: an occupancy grid of the
// scene at the robot's height, inflated by the base radius, searched by OMPL's
// RRTConnect and shortened by its simplifier. The navigate primitive drives
// along these paths.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "world/aabb.hpp"
#include "world/world.hpp"

namespace chore {

// Whether the base drives over `geom`, its world box `box`: lower than
// Robot::kDrivesOver, or a cloth's lower than Robot::kDrivesOverCloth (a
// dress folded where it lay, a tile of it under the base).
bool driven_over(const World& world, int geom, const Aabb& box);

class OccupancyMap {
 public:
  static constexpr double kResolution = 0.05;  // m per cell
  // Cells covered by a collision geom of the scene reaching above `above`
  // (the floor by default) and below the robot's height, grown by `inflation`
  // (a radius plus a margin). Free objects count as obstacles where they are
  // now; the robot, what it carries and the body `moving` (a door the robot
  // turns with it) do not.
  OccupancyMap(const World& world, double inflation, double above = 0.0, int moving = -1);

  bool free(double x, double y) const;
  // Whether free cells join (x0, y0) to (x1, y1), 8-connected: a base path's
  // necessary condition, decided by a flood fill.
  bool connected(double x0, double y0, double x1, double y1) const;
  // The free cells 8-connected to (x, y), as a map of its own (all occupied
  // when (x, y) is not free): where the base could go from there.
  OccupancyMap reachable_from(double x, double y) const;
  double min_x() const { return x0_; }
  double min_y() const { return y0_; }
  double max_x() const { return x0_ + width_ * kResolution; }
  double max_y() const { return y0_ + height_ * kResolution; }

 private:
  // Flood fill from (x, y), stopping early once it reaches the stop cell.
  OccupancyMap flood(double x, double y, std::optional<double> stop_x, std::optional<double> stop_y) const;
  double x0_ = 0, y0_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<unsigned char> occupied_;
};

// The robot as the base planner sees it, measured in its current
// configuration: a disk around the base centre (base, torso, head) and, when
// the hand or what it carries reaches beyond that disk, a second disk around
// them. Each is checked on the occupancy grid inflated by its radius, the
// hand's only against obstacles that reach up to its height: the hand may
// pass over a pumpkin on the floor, or beside furniture the base could not.
class Footprint {
 public:
  static constexpr double kMargin = 0.03;  // m added to both radii
  // `moving`: a body that moves with the robot (OccupancyMap).
  explicit Footprint(const World& world, int moving = -1);
  bool free(const Pose2& pose) const;
  double body_radius() const { return body_radius_; }
  const OccupancyMap& body_map() const { return body_; }

 private:
  double body_radius_ = 0;
  OccupancyMap body_;
  Eigen::Vector2d arm_centre_ = Eigen::Vector2d::Zero();  // robot frame
  std::optional<OccupancyMap> arm_;
};

// The base's pose, or where it is moved straight out (up to 0.4 m) when it
// stands inside inflated obstacles (an opened drawer over it), or else turned
// (by 45 degrees at a time) and moved so; none when it is boxed in.
std::optional<Pose2> free_pose_near(const Footprint& footprint, const Pose2& at);

struct BasePath {
  bool success = false;
  std::vector<Pose2> waypoints;  // start first, goal last
  std::string reason;
};

// A path from the world's current base pose to `goal`; the same seed gives the
// same path. A start inside inflated obstacles (an opened drawer over the
// base) is first left by the shortest straight move out.
BasePath plan_base_path(const World& world, const Footprint& footprint, const Pose2& goal, uint64_t seed,
                        unsigned iterations = 50000);

}  // namespace chore
