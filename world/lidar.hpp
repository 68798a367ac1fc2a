// A planar LiDAR on the robot's base (site base_lidar, 0.1 m above the floor,
// at the front of the base): one mj_ray per beam, in the base's horizontal plane.
#pragma once

#include <cmath>

namespace chore {

class World;

struct LidarConfig {
  int beams = 180;
  double fov = M_PI;    // radians, centred on the base's forward direction
  double range = 10.0;  // metres: nothing hit within it reads `range`
};

// Throws chore::Error naming a bad value.
void validate(const LidarConfig& c);

// Beam i points at angle -fov/2 + (i + 0.5) fov/beams from the base's forward
// direction (counter-clockwise, i.e. right to left, as ROS's LaserScan).
inline double beam_angle(const LidarConfig& c, int i) {
  return -c.fov / 2 + (i + 0.5) * c.fov / c.beams;
}

// Writes `beams` ranges (m): the distance to the first drawn object or
// collision geometry along each beam, capped at `range`. The base does not see
// itself; the arm, when it dips into the plane, is seen (as on the real robot).
void lidar_scan(const World& world, const LidarConfig& c, float* ranges);

}  // namespace chore
