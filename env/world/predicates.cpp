#include "env/world/predicates.hpp"

#include <mujoco/mujoco.h>

#include <cmath>

#include "env/world/object_geometry.hpp"

namespace chore {
namespace {

constexpr double kVerticalRange = 5.0;    // m, BEHAVIOR's vertical ray length
constexpr double kHorizontalRange = 1.0;  // m, for inside's horizontal rays
constexpr int kHorizontalAngles = 5;      // directions over [0, pi/2)
constexpr double kOpenFraction = 0.05;

const Eigen::Vector3d kUp(0, 0, 1), kDown(0, 0, -1);

bool hits(const World& w, int object, const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
          double range) {
  return ray_to_object(w, object, p, dir, range) >= 0;
}

}  // namespace

bool touching(const World& w, int a, int b) { return in_contact(w, a, b); }

bool ontop(const World& w, int a, int b) {
  const Eigen::Vector3d c = object_aabb(w, a).center();
  return touching(w, a, b) && hits(w, b, c, kDown, kVerticalRange) &&
         !hits(w, b, c, kUp, kVerticalRange);
}

bool inside(const World& w, int a, int b) {
  const Eigen::Vector3d c = object_aabb(w, a).center();
  if (!object_aabb(w, b).contains(c)) return false;
  int axes = hits(w, b, c, kUp, kVerticalRange) && hits(w, b, c, kDown, kVerticalRange);
  bool first = false, second = false;
  for (int k = 0; k < kHorizontalAngles; ++k) {
    const double t = M_PI / 2 * k / kHorizontalAngles;
    const Eigen::Vector3d d(std::cos(t), std::sin(t), 0), e(-std::sin(t), std::cos(t), 0);
    first = first || (hits(w, b, c, d, kHorizontalRange) && hits(w, b, c, -d, kHorizontalRange));
    second = second || (hits(w, b, c, e, kHorizontalRange) && hits(w, b, c, -e, kHorizontalRange));
  }
  return axes + first + second >= 2;
}

bool nextto(const World& w, int a, int b) {
  const Aabb box_a = object_aabb(w, a), box_b = object_aabb(w, b);
  const double threshold = (box_a.extent() + box_b.extent()).mean() / 6.0;
  if (Aabb::gap(box_a, box_b) > threshold) return false;
  const Eigen::Vector3d c = box_a.center();
  const double range = box_a.extent().head<2>().norm() / 2 + threshold + box_b.extent().head<2>().norm();
  for (int k = 0; k < 8; ++k) {
    const double t = M_PI / 4 * k;
    if (hits(w, b, c, Eigen::Vector3d(std::cos(t), std::sin(t), 0), range)) return true;
  }
  return false;
}

bool under(const World& w, int a, int b) {
  const Eigen::Vector3d c = object_aabb(w, a).center();
  return hits(w, b, c, kUp, kVerticalRange) && !hits(w, b, c, kDown, kVerticalRange);
}

bool onfloor(const World& w, int a, int room) {
  const std::vector<int>& floors = w.scene().floor_geoms(room);
  return in_contact_with_geoms(w, a, floors) &&
         ray_to_geoms(w, floors, object_aabb(w, a).center(), kDown, kVerticalRange) >= 0;
}

bool inroom(const World& w, int a, int room) {
  const Eigen::Vector3d c = object_aabb(w, a).center();
  const Room* r = w.scene().room_at(c.x(), c.y());
  return r == &w.scene().rooms()[room];
}

bool is_open(const World& w, int a) {
  const mjModel* m = w.model();
  for (int j : w.scene().objects()[a].joints) {
    const double lo = m->jnt_range[2 * j], hi = m->jnt_range[2 * j + 1];
    if (w.data()->qpos[m->jnt_qposadr[j]] > lo + kOpenFraction * (hi - lo)) return true;
  }
  return false;
}

bool grasped(const World& w, int a) { return w.grasped_object() == a; }

}  // namespace chore
