#include "primitives/base_planner.hpp"

#include <mujoco/mujoco.h>
#include <ompl/base/spaces/SE2StateSpace.h>
#include <ompl/geometric/SimpleSetup.h>

#include <cmath>

#include "primitives/rrt_connect.hpp"
#include "world/object_geometry.hpp"

namespace chore {
namespace {

constexpr double kRobotHeight = 1.5;  // m: what the base, torso and tucked arm sweep
constexpr double kMaxEscape = 0.4;    // m the base may move straight out of inflated space

// OMPL's SE2 takes headings in [-pi, pi): std::remainder alone can give +pi.
double wrap(double yaw) {
  const double y = std::remainder(yaw, 2 * M_PI);
  return y >= M_PI ? y - 2 * M_PI : y;
}

}  // namespace

bool driven_over(const World& world, int geom, const Aabb& box) {
  if (box.hi.z() < Robot::kDrivesOver) return true;
  if (box.hi.z() >= Robot::kDrivesOverCloth) return false;
  const int object = world.scene().object_of_geom(geom);
  return object >= 0 && !world.scene().objects()[object].keypoints.empty();
}

OccupancyMap::OccupancyMap(const World& world, double inflation, double above, int moving) {
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
  const int held = world.carried_object() >= 0 ? world.scene().objects()[world.carried_object()].body : -1;
  // The geoms' cells first, then grown by a disk of `inflation` (a robot is
  // round: a square would block diagonal approaches for no reason). Only cells
  // on an obstacle's rim need stamping.
  std::vector<unsigned char> raw(occupied_.size(), 0);
  for (int g = 0; g < m->ngeom; ++g) {
    if (!m->geom_contype[g] && !m->geom_conaffinity[g]) continue;
    const int root = m->body_rootid[m->geom_bodyid[g]];
    if (root == robot || root == held || m->geom_bodyid[g] == moving) continue;  // they move along
    const Aabb box = geom_aabb(world, g);
    if (box.hi.z() < above || driven_over(world, g, box) || box.lo.z() > kRobotHeight) continue;
    const int i0 = std::max(0, static_cast<int>(std::floor((box.lo.x() - x0_) / kResolution)));
    const int i1 = std::min(width_ - 1, static_cast<int>(std::floor((box.hi.x() - x0_) / kResolution)));
    const int j0 = std::max(0, static_cast<int>(std::floor((box.lo.y() - y0_) / kResolution)));
    const int j1 = std::min(height_ - 1, static_cast<int>(std::floor((box.hi.y() - y0_) / kResolution)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) raw[static_cast<size_t>(j) * width_ + i] = 1;
    }
  }
  const int grow = static_cast<int>(std::ceil(inflation / kResolution));
  std::vector<std::pair<int, int>> disk;
  for (int dj = -grow; dj <= grow; ++dj) {
    for (int di = -grow; di <= grow; ++di) {
      if (std::hypot(di, dj) * kResolution <= inflation + kResolution / 2) disk.push_back({di, dj});
    }
  }
  const auto at = [&](int i, int j) { return raw[static_cast<size_t>(j) * width_ + i]; };
  for (int j = 0; j < height_; ++j) {
    for (int i = 0; i < width_; ++i) {
      if (!at(i, j)) continue;
      occupied_[static_cast<size_t>(j) * width_ + i] = 1;
      const bool rim = i == 0 || j == 0 || i == width_ - 1 || j == height_ - 1 || !at(i - 1, j) || !at(i + 1, j) ||
                       !at(i, j - 1) || !at(i, j + 1);
      if (!rim) continue;
      for (const auto& [di, dj] : disk) {
        const int x = i + di, y = j + dj;
        if (x >= 0 && y >= 0 && x < width_ && y < height_) occupied_[static_cast<size_t>(y) * width_ + x] = 1;
      }
    }
  }
}

bool OccupancyMap::free(double x, double y) const {
  const int i = static_cast<int>(std::floor((x - x0_) / kResolution));
  const int j = static_cast<int>(std::floor((y - y0_) / kResolution));
  if (i < 0 || j < 0 || i >= width_ || j >= height_) return false;
  return !occupied_[static_cast<size_t>(j) * width_ + i];
}

bool OccupancyMap::connected(double x0, double y0, double x1, double y1) const {
  return free(x0, y0) && free(x1, y1) && flood(x0, y0, x1, y1).free(x1, y1);
}

OccupancyMap OccupancyMap::reachable_from(double x, double y) const {
  return flood(x, y, std::nullopt, std::nullopt);
}

OccupancyMap OccupancyMap::flood(double x, double y, std::optional<double> stop_x, std::optional<double> stop_y) const {
  const auto cell = [&](double cx, double cy) {
    return std::pair{static_cast<int>(std::floor((cx - x0_) / kResolution)),
                     static_cast<int>(std::floor((cy - y0_) / kResolution))};
  };
  OccupancyMap out = *this;
  std::fill(out.occupied_.begin(), out.occupied_.end(), 1);
  if (!free(x, y)) return out;
  const auto [gi, gj] = stop_x ? cell(*stop_x, *stop_y) : std::pair{-1, -1};
  std::vector<std::pair<int, int>> frontier = {cell(x, y)};
  out.occupied_[static_cast<size_t>(frontier[0].second) * width_ + frontier[0].first] = 0;
  while (!frontier.empty()) {
    const auto [i, j] = frontier.back();
    frontier.pop_back();
    if (i == gi && j == gj) break;
    // 8-connected: a planner's checks one cell apart may step diagonally.
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        const int ni = i + di, nj = j + dj;
        if (ni < 0 || nj < 0 || ni >= width_ || nj >= height_) continue;
        const size_t k = static_cast<size_t>(nj) * width_ + ni;
        if (!out.occupied_[k] || occupied_[k]) continue;
        out.occupied_[k] = 0;
        frontier.push_back({ni, nj});
      }
    }
  }
  return out;
}

std::optional<Pose2> free_pose_near(const Footprint& footprint, const Pose2& at) {
  // As it stands first; then turned, the hand and its load (ahead of the
  // base's centre) swung away from what they meet (a pizza box held by the
  // fridge it came out of).
  for (const double turn : {0.0, M_PI / 4, -M_PI / 4, M_PI / 2, -M_PI / 2, 3 * M_PI / 4, -3 * M_PI / 4, M_PI}) {
    for (double r = 0; r <= kMaxEscape + 1e-9; r += OccupancyMap::kResolution) {
      for (int k = 0; k < (r == 0 ? 1 : 16); ++k) {
        const Pose2 pose{at.x + r * std::cos(k * M_PI / 8), at.y + r * std::sin(k * M_PI / 8),
                         turn == 0 ? at.yaw : wrap(at.yaw + turn)};
        if (footprint.free(pose)) return turn == 0 && r == 0 ? at : pose;
      }
    }
  }
  return std::nullopt;
}

namespace {

// Robot-frame horizontal box of a geom: its box's corners, or its axis's ends
// widened by its radius (a world-aligned box would grow as the robot turns).
void grow_robot_frame(const World& world, int g, const Pose2& base, Eigen::Vector2d& lo, Eigen::Vector2d& hi) {
  const mjModel* m = world.model();
  const mjData* d = world.data();
  const Eigen::Vector3d centre(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
  const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(d->geom_xmat + 9 * g);
  const double* size = m->geom_size + 3 * g;
  std::vector<Eigen::Vector3d> points;
  double pad = 0;
  switch (m->geom_type[g]) {
    case mjGEOM_BOX:
      for (int k = 0; k < 8; ++k) {
        points.push_back(centre + r * Eigen::Vector3d((k & 1 ? 1 : -1) * size[0], (k & 2 ? 1 : -1) * size[1],
                                                      (k & 4 ? 1 : -1) * size[2]));
      }
      break;
    case mjGEOM_CAPSULE:
    case mjGEOM_CYLINDER:
      points = {centre + r.col(2) * size[1], centre - r.col(2) * size[1]};
      pad = size[0];
      break;
    default:
      points = {centre};
      pad = m->geom_rbound[g];
  }
  const double c = std::cos(base.yaw), s = std::sin(base.yaw);
  for (const Eigen::Vector3d& w : points) {
    const Eigen::Vector2d p(c * (w.x() - base.x) + s * (w.y() - base.y), -s * (w.x() - base.x) + c * (w.y() - base.y));
    lo = lo.cwiseMin(p - Eigen::Vector2d::Constant(pad));
    hi = hi.cwiseMax(p + Eigen::Vector2d::Constant(pad));
  }
}

bool descends_from(const mjModel* m, int body, int ancestor) {
  for (; body > 0; body = m->body_parentid[body]) {
    if (body == ancestor) return true;
  }
  return false;
}

double body_radius_of(const World& world) {
  const mjModel* m = world.model();
  const mjData* d = world.data();
  const Robot& r = *world.robot();
  const Pose2 base = world.base_pose();
  const int robot = m->body_rootid[r.gripper_body], arm = m->jnt_bodyid[r.arm[0].joint];
  double radius = 0;
  for (int g = 0; g < m->ngeom; ++g) {
    const int b = m->geom_bodyid[g];
    if (m->body_rootid[b] != robot || descends_from(m, b, arm)) continue;
    if (!m->geom_contype[g] && !m->geom_conaffinity[g]) continue;
    if (m->geom_type[g] == mjGEOM_CYLINDER && std::abs(d->geom_xmat[9 * g + 8]) > 0.99) {
      // Upright cylinders (the base): exact, not their box's corners.
      radius = std::max(
          radius, std::hypot(d->geom_xpos[3 * g] - base.x, d->geom_xpos[3 * g + 1] - base.y) + m->geom_size[3 * g]);
      continue;
    }
    Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e9), hi = -lo;
    grow_robot_frame(world, g, base, lo, hi);
    for (double x : {lo.x(), hi.x()}) {
      for (double y : {lo.y(), hi.y()}) radius = std::max(radius, std::hypot(x, y));
    }
  }
  return radius;
}

}  // namespace

Footprint::Footprint(const World& world, int moving)
    : body_radius_(body_radius_of(world)), body_(world, body_radius_ + kMargin, 0.0, moving) {
  const mjModel* m = world.model();
  const Robot& r = *world.robot();
  const Pose2 base = world.base_pose();
  // The hand and its load: the rest of the arm stays over the base in the
  // tucked and carry poses (and the body disk covers it). Of a cloth only
  // the part in the hand: the rest hangs and gives way.
  const int hand = r.gripper_body;
  const int held = world.carried_object() >= 0 ? world.scene().objects()[world.carried_object()].body : -2;
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(1e9), hi = -lo;
  double bottom = 1e9;
  for (int g = 0; g < m->ngeom; ++g) {
    const int b = m->geom_bodyid[g];
    if (!descends_from(m, b, hand) && b != held) continue;
    if (!m->geom_contype[g] && !m->geom_conaffinity[g]) continue;
    grow_robot_frame(world, g, base, lo, hi);
    bottom = std::min(bottom, geom_aabb(world, g).lo.z());
  }
  arm_centre_ = (lo + hi) / 2;
  const double arm_radius = (hi - lo).norm() / 2;
  if (arm_centre_.norm() + arm_radius > body_radius_) {
    arm_.emplace(world, arm_radius + kMargin, bottom - kMargin);
  }
}

bool Footprint::free(const Pose2& p) const {
  if (!body_.free(p.x, p.y)) return false;
  if (!arm_) return true;
  const double c = std::cos(p.yaw), s = std::sin(p.yaw);
  return arm_->free(p.x + c * arm_centre_.x() - s * arm_centre_.y(), p.y + s * arm_centre_.x() + c * arm_centre_.y());
}

namespace {

// The base is holonomic: its heading need not follow the planner's random
// samples (a 5 m path turned up to 5 rad). Where the footprint allows, the
// heading turns the short way from start to goal in proportion to the
// distance driven.
void straighten_headings(const Footprint& footprint, std::vector<Pose2>& path) {
  if (path.size() < 2) return;
  std::vector<double> along(path.size(), 0.0);
  for (size_t k = 1; k < path.size(); ++k) {
    along[k] = along[k - 1] + std::hypot(path[k].x - path[k - 1].x, path[k].y - path[k - 1].y);
  }
  const double turn = std::remainder(path.back().yaw - path.front().yaw, 2 * M_PI);
  std::vector<Pose2> straight = path;
  for (size_t k = 0; k < path.size(); ++k) {
    const double f = along.back() > 0 ? along[k] / along.back() : static_cast<double>(k) / (path.size() - 1);
    straight[k].yaw = wrap(path.front().yaw + f * turn);
  }
  straight.back().yaw = path.back().yaw;
  constexpr double kYawStep = 0.05;  // rad: the hand, ~0.7 m out, moves a cell
  for (size_t k = 1; k < straight.size(); ++k) {
    const Pose2& a = straight[k - 1];
    const double dyaw = std::remainder(straight[k].yaw - a.yaw, 2 * M_PI);
    const int n = 1 + static_cast<int>(std::max(along[k] - along[k - 1], 0.0) / OccupancyMap::kResolution +
                                       std::abs(dyaw) / kYawStep);
    for (int i = 1; i <= n; ++i) {
      const double f = static_cast<double>(i) / n;
      if (!footprint.free({a.x + f * (straight[k].x - a.x), a.y + f * (straight[k].y - a.y), a.yaw + f * dyaw})) return;
    }
  }
  path = std::move(straight);
}

}  // namespace

BasePath plan_base_path(const World& world, const Footprint& footprint, const Pose2& goal, uint64_t seed,
                        unsigned iterations) {
  namespace ob = ompl::base;
  namespace og = ompl::geometric;
  BasePath out;
  const OccupancyMap& map = footprint.body_map();
  const Pose2 at = world.base_pose();
  const std::optional<Pose2> escape = free_pose_near(footprint, at);
  if (!escape) {
    out.reason = "the robot is boxed in: no free space within " + std::to_string(std::lround(kMaxEscape * 100)) + " cm";
    return out;
  }
  const Pose2 start = *escape;
  if (!footprint.free(goal)) {
    out.reason = "the goal pose is not in free space";
    return out;
  }
  // The body's disk alone needs a way through: a flood fill of its map settles
  // a goal in an enclosed pocket at once, where the planner would use up its iterations.
  if (!map.connected(start.x, start.y, goal.x, goal.y)) {
    out.reason = "no collision-free base path: the goal is enclosed (no free way on the occupancy map)";
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
  setup.setStateValidityChecker([&footprint](const ob::State* s) {
    const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
    return footprint.free({se2->getX(), se2->getY(), se2->getYaw()});
  });
  setup.getSpaceInformation()->setStateValidityCheckingResolution(
      OccupancyMap::kResolution / std::max(map.max_x() - map.min_x(), map.max_y() - map.min_y()));
  ob::ScopedState<ob::SE2StateSpace> from(space), to(space);
  from->setXY(start.x, start.y);
  from->setYaw(wrap(start.yaw));
  to->setXY(goal.x, goal.y);
  to->setYaw(wrap(goal.yaw));
  setup.setStartAndGoalStates(from, to);
  if (!solve_and_simplify(setup, seed, iterations)) {
    out.reason = "no collision-free base path found in " + std::to_string(iterations) + " iterations";
    return out;
  }
  if (start.x != at.x || start.y != at.y || start.yaw != at.yaw) out.waypoints.push_back(at);
  for (const ob::State* s : setup.getSolutionPath().getStates()) {
    const auto* se2 = s->as<ob::SE2StateSpace::StateType>();
    out.waypoints.push_back({se2->getX(), se2->getY(), se2->getYaw()});
  }
  straighten_headings(footprint, out.waypoints);
  out.success = true;
  return out;
}

}  // namespace chore
