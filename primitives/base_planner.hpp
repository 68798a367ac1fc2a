// Collision-free paths of the robot's base in SE2: an occupancy grid of the
// scene at the robot's height, inflated by the base radius, searched by OMPL's
// RRTConnect and shortened by its simplifier. The navigate primitive drives
// along these paths.
#pragma once

#include <string>
#include <vector>

#include "env/world/world.hpp"

namespace chore {

class OccupancyMap {
 public:
  static constexpr double kResolution = 0.05;  // m per cell
  // Cells covered by a collision geom of the scene between the floor and the
  // robot's height, grown by `inflation` (the base radius plus a margin).
  // Free objects count as obstacles where they are now; the robot does not.
  OccupancyMap(const World& world, double inflation);

  bool free(double x, double y) const;
  double min_x() const { return x0_; }
  double min_y() const { return y0_; }
  double max_x() const { return x0_ + width_ * kResolution; }
  double max_y() const { return y0_ + height_ * kResolution; }

 private:
  double x0_ = 0, y0_ = 0;
  int width_ = 0, height_ = 0;
  std::vector<unsigned char> occupied_;
};

struct BasePath {
  bool success = false;
  std::vector<Pose2> waypoints;  // start first, goal last
  std::string reason;
};

// A path from the world's current base pose to `goal`. OMPL seeds its random
// numbers once per process: paths repeat across runs of one program, not per
// call (bit-exact primitive episodes will need a sampler of their own).
BasePath plan_base_path(const World& world, const OccupancyMap& map, const Pose2& goal,
                        unsigned seed, double time_limit = 1.0);

}  // namespace chore
