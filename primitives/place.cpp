// place(object): the carried object over a flat spot on (or in) the object,
// released, and the hand back: on or in it, or a place failure.
#include <mujoco/mujoco.h>

#include <algorithm>

#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

bool applies(const World&, int) {
  return true;  // which objects are placement targets is the activity's to say
}

std::string unmet_precondition(const World& w, int object) {
  if (w.carried_object() < 0) return "the hand holds nothing";
  return w.grasped_object() == object ? "cannot place an object on itself" : "";
}

constexpr double kRestingDepth = 0.0005;  // m

// Symbolic release: the object drops straight down onto what is below it.
void settle_kinematically(Executor& e, int held) {
  const Clock::time_point t = Clock::now();
  World& w = e.world();
  const SceneObject& o = w.scene().objects()[held];
  const Aabb box = object_aabb(w, held);
  std::vector<int> others;
  const mjModel* m = w.model();
  for (int g = 0; g < m->ngeom; ++g) {
    const int root = m->body_rootid[m->geom_bodyid[g]];
    if ((m->geom_contype[g] || m->geom_conaffinity[g]) && root != o.body &&
        root != m->body_rootid[w.robot()->gripper_body]) {
      others.push_back(g);
    }
  }
  double drop = 1e9;
  const Eigen::Vector3d c = box.center();
  const double hx = (box.hi.x() - box.lo.x()) / 2 * 0.8, hy = (box.hi.y() - box.lo.y()) / 2 * 0.8;
  for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, {hx, hy}, {-hx, hy}, {hx, -hy}, {-hx, -hy}}) {
    const double hit = ray_to_geoms(w, others, Eigen::Vector3d(c.x() + dx, c.y() + dy, box.lo.z()), kDown, 5.0);
    if (hit >= 0) drop = std::min(drop, hit);
  }
  if (drop < 1e9) {
    const int adr = m->jnt_qposadr[m->body_jntadr[o.body]];
    // Half a millimetre into the support, as MuJoCo's soft contacts rest:
    // a gap, however small, is no contact, and ontop needs one.
    w.data()->qpos[adr + 2] -= std::max(0.0, drop + kRestingDepth);
    mj_forward(m, w.data());
  }
  e.result().execution_seconds += since(t);
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  const int held = w.grasped_object();
  if (!e.go_to_pre_pose_with_load()) return false;
  m.gripper(true);
  if (!m.physical()) settle_kinematically(e, held);
  m.wait(0.3);
  m.line(kUp * kLift, false, kRetreatSpeed, 0.0);
  if (!e.tuck_where_possible()) return false;
  if (!inside(w, held, e.object()) && !ontop(w, held, e.object())) {
    return e.fail(PrimitiveStatus::place_failure,
                  "'" + w.scene().objects()[held].name + "' is neither on nor in '" + e.name() + "'");
  }
  return true;
}

// Symbolically: what the hand holds ends on the object (or the floor), or,
// for a container, in it: the paper's place (appendix F.4 c) is OmniGibson's
// PLACE_ON_TOP and PLACE_INSIDE at once, releasing over the top or over an
// open drawer's exposed part (top_centre). An openable container must be open.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  const SymbolicObject& target = objects[a.target];
  if (agent < 0 || a.held < 0 || a.held == a.target ||
      (target.kind != SymbolicObject::Kind::object && target.kind != SymbolicObject::Kind::floor)) {
    return {};
  }
  SymbolicStep on;
  on.needs = {literal("grasped", {agent, a.held}), literal(kWithinReach, {a.target}), literal("real", {a.target})};
  on.deletes = {literal("grasped", {agent, a.held})};
  on.adds = {literal(kHandEmpty, {}), literal("ontop", {a.held, a.target})};
  if (!target.has("fillable")) return {on};
  SymbolicStep in = on;
  in.adds.back() = literal("inside", {a.held, a.target});
  if (target.has("openable")) in.needs.push_back(literal("open", {a.target}));
  return {on, in};
}

}  // namespace

const PrimitiveDef& place_primitive() {
  static const PrimitiveDef def{
      .applies = applies, .unmet_precondition = unmet_precondition, .act = act, .model = model, .touches = false};
  return def;
}

}  // namespace chore
