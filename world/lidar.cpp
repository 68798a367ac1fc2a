#include "world/lidar.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <string>

#include "base/error.hpp"
#include "world/scene.hpp"
#include "world/world.hpp"

namespace chore {

void validate(const LidarConfig& c) {
  if (c.beams < 1 || c.beams > 100000) {
    throw Error("lidar.beams = " + std::to_string(c.beams) + ": expected 1..100000");
  }
  if (!(c.fov > 0 && c.fov <= 2 * M_PI)) {
    throw Error("lidar.fov = " + std::to_string(c.fov) + ": expected radians in (0, 2 pi]");
  }
  if (!(c.range > 0 && std::isfinite(c.range))) {
    throw Error("lidar.range = " + std::to_string(c.range) + ": expected positive metres");
  }
}

void lidar_scan(const World& world, const LidarConfig& c, float* ranges) {
  const Robot* robot = world.robot();
  if (!robot) throw Error("lidar: the scene has no robot");
  const mjModel* m = world.model();
  const mjData* d = world.data();
  const mjtNum* origin = d->site_xpos + 3 * robot->lidar_site;
  const mjtNum* frame = d->site_xmat + 9 * robot->lidar_site;
  const int base = m->site_bodyid[robot->lidar_site];
  // Drawn objects and robot links (group 0), collision geometry (group 3); not
  // the merged static mesh, which duplicates the collision geometry.
  mjtByte groups[mjNGROUP] = {};
  groups[kStaticGroup] = groups[kCollisionGroup] = 1;
  for (int i = 0; i < c.beams; ++i) {
    const double a = beam_angle(c, i);
    const mjtNum local[3] = {std::cos(a), std::sin(a), 0};
    mjtNum direction[3];
    mju_mulMatVec3(direction, frame, local);
    int geom = -1;
    const mjtNum hit = mj_ray(m, d, origin, direction, groups, 1, base, &geom, nullptr);
    ranges[i] = static_cast<float>(hit < 0 ? c.range : std::min<double>(hit, c.range));
  }
}

}  // namespace chore
