#include "env/world/sleeping.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "env/world/object_geometry.hpp"
#include "env/world/scene.hpp"

namespace chore {
namespace {

// A geom's box from its bounding sphere: cheap enough for every geom at every step.
void add_geom(Aabb& box, const mjModel* m, const mjData* d, int g) {
  Aabb sphere;
  sphere.lo = sphere.hi = Eigen::Vector3d(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
  box.grow(sphere.grown(m->geom_rbound[g]));
}

}  // namespace

Sleeping::Sleeping(const Scene& scene, const mjModel* m, int robot_root)
    : body_geomnum_(m->body_geomnum, m->body_geomnum + m->nbody) {
  for (int g = 0; g < m->ngeom; ++g) {
    if (robot_root >= 0 && m->body_rootid[m->geom_bodyid[g]] == robot_root) robot_geoms_.push_back(g);
  }
  for (const SceneObject& so : scene.objects()) {
    Object o;
    o.free = !so.fixed;
    o.geoms = so.geoms;
    for (int g : so.geoms) o.never |= m->geom_type[g] == mjGEOM_PLANE || m->geom_type[g] == mjGEOM_HFIELD;
    for (int b = 1; b < m->nbody; ++b) {
      if (m->body_rootid[b] != so.body) continue;
      o.bodies.push_back(b);
      for (int j = m->body_jntadr[b]; j >= 0 && j < m->body_jntadr[b] + m->body_jntnum[b]; ++j) {
        const int nq = m->jnt_type[j] == mjJNT_FREE ? 7 : m->jnt_type[j] == mjJNT_BALL ? 4 : 1;
        const int nv = m->jnt_type[j] == mjJNT_FREE ? 6 : m->jnt_type[j] == mjJNT_BALL ? 3 : 1;
        for (int k = 0; k < nq; ++k) o.qpos.push_back(m->jnt_qposadr[j] + k);
        for (int k = 0; k < nv; ++k) o.dofs.push_back(m->jnt_dofadr[j] + k);
      }
    }
    objects_.push_back(std::move(o));
  }
}

void Sleeping::mask(mjModel* m, const mjData* d, int held_body) {
  const size_t n = objects_.size();
  // Scratch kept between steps: this runs before every physics step.
  boxes_.assign(n, Aabb{});
  awake_.assign(n, 0);
  regions_.clear();
  if (!robot_geoms_.empty()) {
    Aabb robot;
    for (int g : robot_geoms_) add_geom(robot, m, d, g);
    regions_.push_back(robot.grown(kRobotMargin));
  }
  for (size_t i = 0; i < n; ++i) {
    const Object& o = objects_[i];
    for (int g : o.geoms) add_geom(boxes_[i], m, d, g);
    if (o.never || o.geoms.empty()) {
      awake_[i] = 1;
      if (!o.geoms.empty()) regions_.push_back(boxes_[i].grown(kTouchMargin));
      continue;
    }
    if (std::find(o.bodies.begin(), o.bodies.end(), held_body) != o.bodies.end()) {
      awake_[i] = 1;  // moves with the robot: part of its region
      regions_.push_back(boxes_[i].grown(kRobotMargin));
      continue;
    }
    if (!o.asleep) {
      double speed = 0;
      for (size_t k = 0; k < o.dofs.size(); ++k) {
        // Free joints: 3 linear then 3 angular; hinges and slides count as linear.
        const bool angular = o.free && k % 6 >= 3;
        speed = std::max(speed, std::abs(d->qvel[o.dofs[k]]) / (angular ? 10.0 : 1.0));
      }
      if (speed > kRestSpeed) {
        awake_[i] = 1;
        regions_.push_back(boxes_[i].grown(kMovingMargin));
      }
    }
  }
  // Awake objects wake what they touch (a cup awake on a plate keeps the
  // plate, and the table, awake), until nothing changes.
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < n; ++i) {
      if (awake_[i]) continue;
      for (const Aabb& r : regions_) {
        if (!boxes_[i].overlaps(r)) continue;
        awake_[i] = 1;
        changed = true;
        // Furniture does not move: it wakes nothing more than its neighbours already did.
        if (objects_[i].free) regions_.push_back(boxes_[i].grown(kTouchMargin));
        break;
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    Object& o = objects_[i];
    const bool falls_asleep = !awake_[i] && !o.asleep;
    o.asleep = !awake_[i];
    if (!o.asleep) continue;
    if (falls_asleep) {
      o.rest_qpos.resize(o.qpos.size());
      for (size_t k = 0; k < o.qpos.size(); ++k) o.rest_qpos[k] = d->qpos[o.qpos[k]];
    }
    for (int b : o.bodies) m->body_geomnum[b] = 0;
  }
}

void Sleeping::unmask(mjModel* m, mjData* d) const {
  for (const Object& o : objects_) {
    if (!o.asleep) continue;
    for (int b : o.bodies) m->body_geomnum[b] = body_geomnum_[static_cast<size_t>(b)];
    for (size_t k = 0; k < o.qpos.size(); ++k) d->qpos[o.qpos[k]] = o.rest_qpos[k];
    for (int v : o.dofs) d->qvel[v] = 0;
  }
}

void Sleeping::wake_all() {
  for (Object& o : objects_) o.asleep = false;
}

int Sleeping::sleepers() const {
  return static_cast<int>(std::count_if(objects_.begin(), objects_.end(), [](const Object& o) { return o.asleep; }));
}

}  // namespace chore
