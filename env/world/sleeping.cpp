#include "env/world/sleeping.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "env/world/scene.hpp"

namespace chore {
namespace {

struct Box {
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  void add_geom(const mjModel* m, const mjData* d, int g) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], d->geom_xpos[3 * g + k] - m->geom_rbound[g]);
      hi[k] = std::max(hi[k], d->geom_xpos[3 * g + k] + m->geom_rbound[g]);
    }
  }
  Box grown(double margin) const {
    Box b = *this;
    for (int k = 0; k < 3; ++k) b.lo[k] -= margin, b.hi[k] += margin;
    return b;
  }
  bool overlaps(const Box& o) const {
    for (int k = 0; k < 3; ++k) {
      if (hi[k] < o.lo[k] || o.hi[k] < lo[k]) return false;
    }
    return true;
  }
};

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
  std::vector<Box> boxes(n);
  std::vector<char> awake(n, 0);
  std::vector<Box> regions;
  if (!robot_geoms_.empty()) {
    Box robot;
    for (int g : robot_geoms_) robot.add_geom(m, d, g);
    regions.push_back(robot.grown(kRobotMargin));
  }
  for (size_t i = 0; i < n; ++i) {
    Object& o = objects_[i];
    for (int g : o.geoms) boxes[i].add_geom(m, d, g);
    if (o.never || o.geoms.empty()) {
      awake[i] = 1;
      if (!o.geoms.empty()) regions.push_back(boxes[i].grown(kTouchMargin));
      continue;
    }
    bool held = false;
    for (int b : o.bodies) held |= b == held_body;
    if (held) {
      awake[i] = 1;  // moves with the robot: part of its region
      regions.push_back(boxes[i].grown(kRobotMargin));
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
        awake[i] = 1;
        regions.push_back(boxes[i].grown(kMovingMargin));
      }
    }
  }
  // Awake objects wake what they touch (a cup awake on a plate keeps the
  // plate, and the table, awake), until nothing changes.
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < n; ++i) {
      if (awake[i]) continue;
      for (const Box& r : regions) {
        if (!boxes[i].overlaps(r)) continue;
        awake[i] = 1;
        changed = true;
        // Furniture does not move: it wakes nothing more than its neighbours already did.
        if (objects_[i].free) regions.push_back(boxes[i].grown(kTouchMargin));
        break;
      }
    }
  }
  for (size_t i = 0; i < n; ++i) {
    Object& o = objects_[i];
    if (!awake[i] && !o.asleep) {
      o.asleep = true;
      o.rest_qpos.resize(o.qpos.size());
      for (size_t k = 0; k < o.qpos.size(); ++k) o.rest_qpos[k] = d->qpos[o.qpos[k]];
    }
    o.asleep = !awake[i];
    if (o.asleep) {
      for (int b : o.bodies) m->body_geomnum[b] = 0;
    }
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
