#include "primitives/base_planner.hpp"

#include <mujoco/mujoco.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/util/RandomNumbers.h>

#include <cmath>

#include "env/world/object_geometry.hpp"
#include "primitives/rrt_connect.hpp"

namespace chore {
namespace {

constexpr double kFloorClearance = 0.02;  // geoms below this are floors
constexpr double kRobotHeight = 1.5;      // m: what the base, torso and tucked arm sweep

// OMPL's SE2 takes headings in [-pi, pi): std::remainder alone can give +pi.
double wrap(double yaw) {
  const double y = std::remainder(yaw, 2 * M_PI);
  return y >= M_PI ? y - 2 * M_PI : y;
}

}  // namespace

OccupancyMap::OccupancyMap(const World& world, double inflation) {
  const mjModel* m = world.model();
  const Scene& scene = world.scene();
  Aabb bounds;
  for (const Room& room : scene.rooms()) {
    for (const auto& r : room.rects) {
      Aabb box;
      box.lo = Eigen::Vector3d(r[0], r[1], 0);
      box.hi = Eigen::Vector3d(r[2], r[3], 0);
      bounds.grow(box);
    }
  }
  x0_ = bounds.lo.x();
  y0_ = bounds.lo.y();
  width_ = static_cast<int>(std::ceil((bounds.hi.x() - x0_) / kResolution));
  height_ = static_cast<int>(std::ceil((bounds.hi.y() - y0_) / kResolution));
  occupied_.assign(static_cast<size_t>(width_) * height_, 0);
  const int robot = world.robot() ? m->body_rootid[world.robot()->gripper_body] : -1;
  const int grow = static_cast<int>(std::ceil(inflation / kResolution));
  for (int g = 0; g < m->ngeom; ++g) {
    if (!m->geom_contype[g] && !m->geom_conaffinity[g]) continue;
    if (m->body_rootid[m->geom_bodyid[g]] == robot) continue;
    const Aabb box = geom_aabb(world, g);
    if (box.hi.z() < kFloorClearance || box.lo.z() > kRobotHeight) continue;
    const int i0 = std::max(0, static_cast<int>(std::floor((box.lo.x() - x0_) / kResolution)) - grow);
    const int i1 = std::min(width_ - 1, static_cast<int>(std::floor((box.hi.x() - x0_) / kResolution)) + grow);
    const int j0 = std::max(0, static_cast<int>(std::floor((box.lo.y() - y0_) / kResolution)) - grow);
    const int j1 = std::min(height_ - 1, static_cast<int>(std::floor((box.hi.y() - y0_) / kResolution)) + grow);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) occupied_[static_cast<size_t>(j) * width_ + i] = 1;
    }
  }
}

bool OccupancyMap::free(double x, double y) const {
  const int i = static_cast<int>(std::floor((x - x0_) / kResolution));
  const int j = static_cast<int>(std::floor((y - y0_) / kResolution));
  if (i < 0 || j < 0 || i >= width_ || j >= height_) return false;
  return !occupied_[static_cast<size_t>(j) * width_ + i];
}

BasePath plan_base_path(const World& world, const OccupancyMap& map, const Pose2& goal,
                        unsigned seed, double time_limit) {
  namespace ob = ompl::base;
  namespace og = ompl::geometric;
  ompl::RNG::setSeed(seed);
  BasePath out;
  const Pose2 start = world.base_pose();
  if (!map.free(start.x, start.y)) {
    out.reason = "the robot's start pose is not in free space";
    return out;
  }
  if (!map.free(goal.x, goal.y)) {
    out.reason = "the goal pose is not in free space";
    return out;
  }
  auto space = std::make_shared<ob::SE2StateSpace>();
  ob::RealVectorBounds bounds(2);
  bounds.setLow(0, map.min_x());
  bounds.setHigh(0, map.max_x());
  bounds.setLow(1, map.min_y());
  bounds.setHigh(1, map.max_y());
  space->setBounds(bounds);
  og::SimpleSetup setup(space);
  setup.setStateValidityChecker([&map](const ob::State* s) {
    const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
    return map.free(se2->getX(), se2->getY());  // a round base: heading does not matter
  });
  setup.getSpaceInformation()->setStateValidityCheckingResolution(
      OccupancyMap::kResolution / std::max(map.max_x() - map.min_x(), map.max_y() - map.min_y()));
  ob::ScopedState<ob::SE2StateSpace> from(space), to(space);
  from->setXY(start.x, start.y);
  from->setYaw(wrap(start.yaw));
  to->setXY(goal.x, goal.y);
  to->setYaw(wrap(goal.yaw));
  setup.setStartAndGoalStates(from, to);
  if (!solve_and_simplify(setup, time_limit)) {
    out.reason = "no collision-free base path found in " + std::to_string(time_limit) + " s";
    return out;
  }
  for (const ob::State* s : setup.getSolutionPath().getStates()) {
    const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
    out.waypoints.push_back({se2->getX(), se2->getY(), se2->getYaw()});
  }
  out.success = true;
  return out;
}

}  // namespace chore
