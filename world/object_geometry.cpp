#include "world/object_geometry.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

namespace chore {

Frame object_frame(const World& world, int object) {
  const SceneObject& o = world.scene().objects()[object];
  using RowMajor = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  if (o.body < 0) return {Eigen::Vector3d(o.pos.data()), Eigen::Map<const RowMajor>(o.mat.data())};
  const mjData* d = world.data();
  return {Eigen::Vector3d(d->xpos + 3 * o.body), Eigen::Map<const RowMajor>(d->xmat + 9 * o.body)};
}

Aabb geom_aabb(const World& world, int g) {
  return geom_aabb(world.model(), g, world.data()->geom_xpos + 3 * g, world.data()->geom_xmat + 9 * g);
}

Aabb geom_aabb(const mjModel* m, int g, const double* xpos, const double* r) {
  const double* s = m->geom_size + 3 * g;  // r row-major: r[3 * i + j] = R(i, j)
  Eigen::Vector3d half;
  for (int i = 0; i < 3; ++i) {
    const double zi = std::abs(r[3 * i + 2]);  // the geom's local z along world axis i
    switch (m->geom_type[g]) {
      case mjGEOM_BOX:
        half[i] = std::abs(r[3 * i]) * s[0] + std::abs(r[3 * i + 1]) * s[1] + zi * s[2];
        break;
      case mjGEOM_SPHERE:
        half[i] = s[0];
        break;
      case mjGEOM_CYLINDER:
        half[i] = zi * s[1] + s[0] * std::sqrt(std::max(0.0, 1 - zi * zi));
        break;
      case mjGEOM_CAPSULE:
        half[i] = zi * s[1] + s[0];
        break;
      default:
        half[i] = m->geom_rbound[g];
    }
  }
  const Eigen::Vector3d c(xpos[0], xpos[1], xpos[2]);
  return {c - half, c + half};
}

Aabb object_aabb(const World& world, int object) {
  Aabb box;
  for (int g : world.scene().objects()[object].geoms) box.grow(geom_aabb(world, g));
  return box;
}

double ray_to_geoms(const World& world, const std::vector<int>& geoms, const Eigen::Vector3d& p,
                    const Eigen::Vector3d& dir, double max_distance) {
  const mjModel* m = world.model();
  const mjData* d = world.data();
  double best = -1;
  for (int g : geoms) {
    const double t = mju_rayGeom(d->geom_xpos + 3 * g, d->geom_xmat + 9 * g, m->geom_size + 3 * g, p.data(), dir.data(),
                                 m->geom_type[g], nullptr);
    if (t >= 0 && t <= max_distance && (best < 0 || t < best)) best = t;
  }
  return best;
}

double ray_to_object(const World& world, int object, const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                     double max_distance) {
  return ray_to_geoms(world, world.scene().objects()[object].geoms, p, dir, max_distance);
}

namespace {

template <class OtherTest>
bool any_contact(const World& world, int a, OtherTest is_other) {
  const mjData* d = world.data();
  const Scene& scene = world.scene();
  const auto joins = [&](const mjContact& con) {
    const int o1 = scene.object_of_geom(con.geom[0]);
    const int o2 = scene.object_of_geom(con.geom[1]);
    return (o1 == a && is_other(con.geom[1])) || (o2 == a && is_other(con.geom[0]));
  };
  for (int c = 0; c < d->ncon; ++c) {
    if (joins(d->contact[c])) return true;
  }
  // Those of sleepers, which MuJoCo no longer computes.
  bool found = false;
  world.resting_contacts().for_each(world.model(), d, [&](const mjContact& con) { found = found || joins(con); });
  return found;
}

}  // namespace

bool in_contact(const World& world, int a, int b) {
  const Scene& scene = world.scene();
  return any_contact(world, a, [&](int g) { return scene.object_of_geom(g) == b; });
}

bool in_contact_with_geoms(const World& world, int a, const std::vector<int>& geoms) {
  return any_contact(world, a, [&](int g) { return std::find(geoms.begin(), geoms.end(), g) != geoms.end(); });
}

}  // namespace chore
