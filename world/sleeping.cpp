#include "world/sleeping.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "world/object_geometry.hpp"
#include "world/scene.hpp"

namespace chore {
namespace {

// A geom's box from its bounding sphere: cheap enough for every geom at every step.
void add_geom(Aabb& box, const mjModel* m, const mjData* d, int g) {
  Aabb sphere;
  sphere.lo = sphere.hi = Eigen::Vector3d(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
  box.grow(sphere.grown(m->geom_rbound[g]));
}

int dof_count(int joint_type) {
  return joint_type == mjJNT_FREE ? 6 : joint_type == mjJNT_BALL ? 3 : 1;
}

}  // namespace

Sleeping::Sleeping(const Scene& scene, const mjModel* m, int robot_root)
    : geom_object_(m->ngeom),
      robot_geom_(m->ngeom, 0),
      body_geomadr_(m->body_geomadr, m->body_geomadr + m->nbody),
      body_geomnum_(m->body_geomnum, m->body_geomnum + m->nbody),
      static_bodies_(scene.static_bodies()),
      static_asleep_(static_bodies_.size(), 0) {
  for (int g = 0; g < m->ngeom; ++g) {
    geom_object_[g] = scene.object_of_geom(g);
    if (robot_root >= 0 && m->body_rootid[m->geom_bodyid[g]] == robot_root) {
      robot_geoms_.push_back(g);
      robot_geom_[g] = 1;
    }
  }
  for (const SceneObject& so : scene.objects()) {
    Object o;
    o.free = !so.fixed;
    o.geoms = so.geoms;
    if (so.static_body >= 0) {
      o.static_body = static_cast<int>(std::find(static_bodies_.begin(), static_bodies_.end(), so.static_body) -
                                       static_bodies_.begin());
    }
    for (int g : so.geoms) o.never |= m->geom_type[g] == mjGEOM_PLANE || m->geom_type[g] == mjGEOM_HFIELD;
    for (int b = 1; so.body >= 0 && b < m->nbody; ++b) {
      if (m->body_rootid[b] != so.body) continue;
      o.bodies.push_back(b);
      for (int j = m->body_jntadr[b]; j >= 0 && j < m->body_jntadr[b] + m->body_jntnum[b]; ++j) {
        const int nq = m->jnt_type[j] == mjJNT_FREE ? 7 : m->jnt_type[j] == mjJNT_BALL ? 4 : 1;
        for (int k = 0; k < nq; ++k) o.qpos.push_back(m->jnt_qposadr[j] + k);
        for (int k = 0; k < dof_count(m->jnt_type[j]); ++k) o.dofs.push_back(m->jnt_dofadr[j] + k);
      }
    }
    if (o.static_body < 0) moving_.push_back(static_cast<int>(objects_.size()));
    objects_.push_back(std::move(o));
  }
  // Per body, one past the last dof of its tree (each object is a tree of its own).
  body_dof_end_.assign(m->nbody, 0);
  for (int j = 0; j < m->njnt; ++j) {
    const int body = m->jnt_bodyid[j], end = m->jnt_dofadr[j] + dof_count(m->jnt_type[j]);
    int& tree_end = body_dof_end_[m->body_rootid[body]];
    tree_end = std::max(tree_end, end);
    if (scene.object_of_body(body) < 0) always_dofs_ = std::max(always_dofs_, end);  // the robot's
  }
  for (int b = 0; b < m->nbody; ++b) body_dof_end_[b] = body_dof_end_[m->body_rootid[b]];
  for (int w = 0; w < m->nwrap; ++w) {
    if (m->wrap_type[w] != mjWRAP_JOINT) continue;
    always_dofs_ = std::max(always_dofs_, body_dof_end_[m->jnt_bodyid[m->wrap_objid[w]]]);
  }
}

bool Sleeping::moved_while_asleep(const Object& o, const mjData* d) const {
  for (size_t k = 0; k < o.qpos.size(); ++k) {
    if (d->qpos[o.qpos[k]] != o.rest_qpos[k]) return true;
  }
  return std::any_of(o.dofs.begin(), o.dofs.end(), [&](int v) { return d->qvel[v] != 0; });
}

// An awake object put somewhere by a sampler or a kinematic move since the
// last physics step: still, but not at rest (it may hang in the air).
bool Sleeping::moved_since_step(const Object& o, const mjData* d) const {
  for (size_t k = 0; k < o.step_qpos.size(); ++k) {
    if (d->qpos[o.qpos[k]] != o.step_qpos[k]) return true;
  }
  return false;
}

void Sleeping::mask(mjModel* m, const mjData* d, int held_body) {
  const size_t n = objects_.size();
  // Scratch kept between steps: this runs before every physics step. Only
  // the moving objects' entries are written and read (furniture in static
  // bodies keeps 0s).
  boxes_.resize(n);
  awake_.resize(n);
  fell_asleep_.resize(n);
  regions_.clear();
  if (!robot_geoms_.empty()) {
    Aabb robot;
    for (int g : robot_geoms_) add_geom(robot, m, d, g);
    regions_.push_back(robot.grown(kRobotMargin));
  }
  for (const int i : moving_) {  // furniture in a static body: its static body's region decides
    const Object& o = objects_[i];
    int& still = objects_[i].still_steps;
    boxes_[i] = Aabb{};
    awake_[i] = 0;
    for (int g : o.geoms) add_geom(boxes_[i], m, d, g);
    if (o.never || o.geoms.empty()) {
      awake_[i] = 1;
      if (!o.geoms.empty()) regions_.push_back(boxes_[i].grown(kTouchMargin));
      continue;
    }
    if (std::find(o.bodies.begin(), o.bodies.end(), held_body) != o.bodies.end()) {
      awake_[i] = 1;  // moves with the robot: part of its region
      still = 0;
      regions_.push_back(boxes_[i].grown(kRobotMargin));
      continue;
    }
    double speed = 0;
    for (size_t k = 0; k < o.dofs.size(); ++k) {
      // Free joints: 3 linear then 3 angular; hinges and slides count as linear.
      const bool angular = o.free && k % 6 >= 3;
      speed = std::max(speed, std::abs(d->qvel[o.dofs[k]]) / (angular ? 10.0 : 1.0));
    }
    // A sleeper moved by anyone but physics (a sampler, a kinematic primitive) wakes.
    if (speed > kRestSpeed || (o.asleep ? moved_while_asleep(o, d) : moved_since_step(o, d))) {
      still = 0;
      awake_[i] = 1;
      regions_.push_back(boxes_[i].grown(kMovingMargin));
    } else if (++still < kStillSteps) {
      awake_[i] = 1;
      regions_.push_back(boxes_[i].grown(kTouchMargin));
    }
  }
  // Awake objects wake what they touch (a cup awake on a plate keeps the
  // plate, and the table, awake), until nothing changes.
  for (bool changed = true; changed;) {
    changed = false;
    for (const int i : moving_) {
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
  if (static_boxes_.size() != static_bodies_.size()) {
    for (int b : static_bodies_) {
      Aabb& box = static_boxes_.emplace_back();
      std::vector<Aabb>& geom_boxes = static_geom_boxes_.emplace_back();
      for (int g = m->body_geomadr[b]; g < m->body_geomadr[b] + m->body_geomnum[b]; ++g) {
        add_geom(geom_boxes.emplace_back(), m, d, g);
        box.grow(geom_boxes.back());
      }
    }
  }
  for (size_t k = 0; k < static_bodies_.size(); ++k) {
    near_regions_.clear();
    for (const Aabb& r : regions_) {
      if (static_boxes_[k].overlaps(r)) near_regions_.push_back(r);
    }
    const int b = static_bodies_[k];
    static_asleep_[k] = near_regions_.empty();
    if (static_asleep_[k]) {
      m->body_geomnum[b] = 0;
      continue;
    }
    // Of its geoms, only the run from the first to the last that an awake
    // region meets: a 2 m cell's dozens of boxes would otherwise each be
    // paired with every geom of the robot or cloth near any one of them.
    const std::vector<Aabb>& boxes = static_geom_boxes_[k];
    const auto met = [&](const Aabb& box) {
      return std::any_of(near_regions_.begin(), near_regions_.end(), [&](const Aabb& r) { return box.overlaps(r); });
    };
    int first = 0, last = static_cast<int>(boxes.size()) - 1;
    while (first <= last && !met(boxes[first])) ++first;
    while (last > first && !met(boxes[last])) --last;
    m->body_geomadr[b] = body_geomadr_[b] + first;
    m->body_geomnum[b] = last - first + 1;
  }
  bool changed = false;  // anyone fell asleep or woke
  for (const int i : moving_) {
    Object& o = objects_[i];
    fell_asleep_[i] = !awake_[i] && !o.asleep;
    changed |= o.asleep == static_cast<bool>(awake_[i]);
    o.asleep = !awake_[i];
    if (!o.asleep) continue;
    if (fell_asleep_[i]) {
      o.rest_qpos.resize(o.qpos.size());
      for (size_t k = 0; k < o.qpos.size(); ++k) o.rest_qpos[k] = d->qpos[o.qpos[k]];
    }
    for (int b : o.bodies) m->body_geomnum[b] = 0;
  }
  // The kept contacts depend on who sleeps, and only change when that does.
  if (changed) keep_resting_contacts(d);
  // The dofs physics must keep: the robot's, tendons', awake objects', and
  // those of bodies an active equality ties (a grasp, an attachment).
  awake_dofs_ = always_dofs_;
  for (const int i : moving_) {
    const Object& o = objects_[i];
    if (!o.asleep && !o.dofs.empty()) awake_dofs_ = std::max(awake_dofs_, o.dofs.back() + 1);
  }
  for (int e = 0; e < m->neq; ++e) {
    if (!m->eq_active[e]) continue;
    for (int id : {m->eq_obj1id[e], m->eq_obj2id[e]}) {
      if (id < 0) continue;
      const mjtEq type = static_cast<mjtEq>(m->eq_type[e]);
      const int body = type == mjEQ_JOINT      ? m->jnt_bodyid[id]
                       : type == mjEQ_DISTANCE ? m->geom_bodyid[id]
                       : type == mjEQ_TENDON   ? 0  // tendons' joints are always kept
                                               : id;
      awake_dofs_ = std::max(awake_dofs_, body_dof_end_[body]);
    }
  }
}

void Sleeping::keep_resting_contacts(const mjData* d) {
  auto object = [&](int g) { return geom_object_[static_cast<size_t>(g)]; };
  // Sides that physics computes contacts for: the robot and awake free objects.
  auto computed = [&](int g) {
    const int o = object(g);
    if (o < 0) return robot_geom_[static_cast<size_t>(g)] != 0;
    return objects_[o].free && objects_[o].static_body < 0 && !objects_[o].asleep;
  };
  auto sleeper = [&](int g) {
    const int o = object(g);
    return o >= 0 && objects_[o].static_body < 0 && objects_[o].asleep;
  };
  std::erase_if(resting_, [&](const mjContact& c) {
    return computed(c.geom1) || computed(c.geom2) || !(sleeper(c.geom1) || sleeper(c.geom2));
  });
  // The last step computed the contacts of those that fall asleep now.
  auto fell = [&](int g) { return object(g) >= 0 && fell_asleep_[object(g)]; };
  auto old_sleeper = [&](int g) { return sleeper(g) && !fell(g); };
  for (int c = 0; c < d->ncon; ++c) {
    const mjContact& con = d->contact[c];
    if (con.efc_address == kKeptContact || !(fell(con.geom1) || fell(con.geom2))) continue;
    if (computed(con.geom1) || computed(con.geom2) || old_sleeper(con.geom1) || old_sleeper(con.geom2)) continue;
    resting_.push_back(con);
    resting_.back().efc_address = kKeptContact;
  }
}

void Sleeping::unmask(mjModel* m, mjData* d, bool physics) {
  for (int b : static_bodies_) {
    m->body_geomadr[b] = body_geomadr_[static_cast<size_t>(b)];
    m->body_geomnum[b] = body_geomnum_[static_cast<size_t>(b)];
  }
  for (const int i : moving_) {
    Object& o = objects_[i];
    if (o.asleep) {
      for (int b : o.bodies) m->body_geomnum[b] = body_geomnum_[static_cast<size_t>(b)];
      for (size_t k = 0; k < o.qpos.size(); ++k) d->qpos[o.qpos[k]] = o.rest_qpos[k];
      for (int v : o.dofs) d->qvel[v] = 0;
    } else if (physics) {
      o.step_qpos.resize(o.qpos.size());
      for (size_t k = 0; k < o.qpos.size(); ++k) o.step_qpos[k] = d->qpos[o.qpos[k]];
    }
  }
}

void Sleeping::append_resting_contacts(const mjModel* m, mjData* d) const {
  if (d->ncon > 0 && d->contact[d->ncon - 1].efc_address == kKeptContact) return;  // appended already
  for (const mjContact& c : resting_) {
    if (d->ncon >= m->nconmax) break;
    d->contact[d->ncon++] = c;
  }
}

void Sleeping::wake_all() {
  for (Object& o : objects_) {
    o.asleep = false;
    o.still_steps = 0;
    o.step_qpos.clear();
  }
  std::fill(static_asleep_.begin(), static_asleep_.end(), 0);
  resting_.clear();
}

void Sleeping::all_at_rest() {
  for (Object& o : objects_) o.still_steps = kStillSteps;
}

bool Sleeping::asleep(int object) const {
  const Object& o = objects_[static_cast<size_t>(object)];
  return o.static_body >= 0 ? static_asleep_[static_cast<size_t>(o.static_body)] : o.asleep;
}

int Sleeping::sleepers() const {
  int count = 0;
  for (size_t i = 0; i < objects_.size(); ++i) count += asleep(static_cast<int>(i));
  return count;
}

}  // namespace chore
