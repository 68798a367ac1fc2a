// drape(object): the carried cloth laid over the object (BDDL's draped and
// overlaid: a tablecloth on a table, a sheet on a bed, a quilt over a rack).
// Symbolic only: carried over the object's top centre, the cloth is laid
// flat on the top, centred, and where it reaches past the top's edges it
// hangs down them (the hinge one tile past an edge turned down). Which of
// draped and overlaid then holds is the predicates' to say, from the cloth's
// size against the object's; one of them must. Not physical yet: a carried
// cloth hangs from the hand, and the reach checks and pre-poses plan for
// the whole of it as a rigid load below the hand (a towel hanging 40 cm puts
// a table's pre-pose beyond the arm); physically it fails its precondition
// saying so, and physical action spaces do not offer it.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

constexpr double kRestingDepth = 0.0005;  // m the tiles rest into the top (contacts: touching)

bool applies(const World&, int) {
  return true;  // what cloths are laid over is the activity's to say
}

std::string unmet_precondition(const World& w, int object) {
  const int held = w.carried_object();
  if (held < 0) return "the hand holds nothing";
  if (w.scene().objects()[held].keypoints.empty()) return "'" + w.scene().objects()[held].name + "' is not a cloth";
  return held == object ? "cannot drape a cloth over itself" : "";
}

// Symbolically: flat on the top, centred, upright at the yaw it was carried
// at, then hanging down past the edges as far as what the object stands on
// lets it (a tile that reaches it turns flat again, onto it).
void lay_over(World& w, int cloth, int object) {
  const mjModel* m = w.model();
  mjData* d = w.data();
  const SceneObject& o = w.scene().objects()[cloth];
  const int root = m->body_rootid[o.body];
  const Aabb top = object_aabb(w, object);
  const double radius = m->geom_size[3 * o.geoms.front()];
  for (int j = 0; j < m->njnt; ++j) {
    if (m->body_rootid[m->jnt_bodyid[j]] != root) continue;
    if (m->jnt_type[j] == mjJNT_FREE) {
      mjtNum* q = d->qpos + m->jnt_qposadr[j];
      const double yaw = std::atan2(2 * (q[3] * q[6] + q[4] * q[5]), 1 - 2 * (q[5] * q[5] + q[6] * q[6]));
      const mjtNum upright[7] = {
          top.center().x(), top.center().y(), top.hi.z() + radius - kRestingDepth, std::cos(yaw / 2), 0, 0,
          std::sin(yaw / 2)};
      mju_copy(q, upright, 7);
      mju_zero(d->qvel + m->jnt_dofadr[j], 6);
    } else {
      d->qpos[m->jnt_qposadr[j]] = 0;
      d->qvel[m->jnt_dofadr[j]] = 0;
    }
  }
  mj_kinematics(m, d);
  const auto over = [&](int body) {
    const double* p = d->xpos + 3 * body;
    return p[0] >= top.lo.x() && p[0] <= top.hi.x() && p[1] >= top.lo.y() && p[1] <= top.hi.y();
  };
  const auto offset = [&](int from, int to) {
    return Eigen::Vector3d(d->xpos[3 * to] - d->xpos[3 * from], d->xpos[3 * to + 1] - d->xpos[3 * from + 1],
                           d->xpos[3 * to + 2] - d->xpos[3 * from + 2]);
  };
  // The bending hinge of `body` (the one whose axis turns it out of the
  // cloth's plane) and the angle that turns it down by `drop`; -1 for none.
  const auto bend = [&](int body, int parent, double drop, double& angle) {
    const Eigen::Vector3d out = offset(parent, body);
    for (int j = m->body_jntadr[body]; j < m->body_jntadr[body] + m->body_jntnum[body]; ++j) {
      const Eigen::Vector3d axis(d->xaxis[3 * j], d->xaxis[3 * j + 1], d->xaxis[3 * j + 2]);
      const double down = axis.cross(out).z();
      if (std::abs(down) < 1e-9) continue;
      angle = (down > 0 ? -1 : 1) * drop;
      return j;
    }
    return -1;
  };
  // The first body past an edge (its parent over the top: a body's line
  // runs from its parent) hangs from its parent (its hinge is there): straight
  // down, or, where what the object stands on is nearer, down onto it and
  // the next one on along it flat.
  const double floor = top.lo.z();
  std::vector<std::pair<int, double>> bends;
  for (int body = 0; body < m->nbody; ++body) {
    if (m->body_rootid[body] != root || body == root) continue;
    const int parent = m->body_parentid[body];
    if (!over(parent) || over(body)) continue;
    const double spacing = offset(parent, body).norm();
    const double room = d->xpos[3 * body + 2] - radius - floor;
    const double drop = std::asin(std::clamp(room / spacing, 0.0, 1.0));
    double angle = 0;
    const int j = bend(body, parent, drop, angle);
    if (j < 0) continue;
    bends.push_back({m->jnt_qposadr[j], angle});
    if (drop >= M_PI / 2 - 1e-6) continue;
    for (int next = 0; next < m->nbody; ++next) {
      if (m->body_parentid[next] != body ||
          offset(body, next).normalized().dot(offset(parent, body).normalized()) < 0.9)
        continue;
      double back = 0;
      if (const int k = bend(next, body, drop, back); k >= 0) bends.push_back({m->jnt_qposadr[k], -back});
    }
  }
  for (const auto& [adr, angle] : bends) d->qpos[adr] = angle;
  mj_forward(m, d);
}

bool act(Executor& e) {
  World& w = e.world();
  const int cloth = w.grasped_object(), object = e.object();
  if (e.motion().physical()) {
    return e.fail(PrimitiveStatus::precondition_failure,
                  "draping is symbolic only: a hanging cloth is planned for as a rigid load below the hand");
  }
  if (!e.go_to_pre_pose_with_load()) return false;
  w.release();
  lay_over(w, cloth, object);
  e.motion().gripper(true);
  if (!e.tuck_where_possible()) return false;
  if (!draped(w, cloth, object) && !overlaid(w, cloth, object)) {
    return e.fail(PrimitiveStatus::place_failure, "'" + w.scene().objects()[cloth].name +
                                                      "' is neither draped over nor overlaid on '" + e.name() + "'");
  }
  return true;
}

// Symbolically: the held cloth ends over the object, draped and overlaid (the
// relaxed model's both; which holds is the cloth's size against the object's).
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  if (agent < 0 || a.held < 0 || a.held == a.target || objects[a.target].kind != SymbolicObject::Kind::object ||
      !objects[a.held].has("cloth")) {
    return {};
  }
  return {setting_down(agent, a,
                       {literal("draped", {a.held, a.target}), literal("overlaid", {a.held, a.target}),
                        literal("touching", {a.held, a.target})})};
}

}  // namespace

const PrimitiveDef& drape_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .touches = false,
                                .symbolic_only = true};
  return def;
}

}  // namespace chore
