// fold(object), unfold(object): a cloth folded in half where it lies, or
// spread flat (BDDL's folded and unfolded, read from its corner keypoints).
// Symbolic only: the hand reaches above the cloth as it would to take an
// edge, then the cloth's hinges are set (folded: each tile row of one half
// turned over the other; unfolded: every hinge straight). Physically a fold
// needs a grasp on an edge tile, and the assistive grasp holds a cloth by its
// centre body only: physically both fail their precondition, and the action
// space offers them in symbolic mode only (env/primitive_actions.cpp).
#include <mujoco/mujoco.h>

#include <cmath>

#include "primitives/primitive_def.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

// Turned just short of flat, so that the folded half lies on the other
// (tiles do not collide with each other) instead of in it.
constexpr double kFoldAngle = M_PI - 0.1;

bool applies(const World& w, int object) {
  return !w.scene().objects()[object].keypoints.empty();
}

std::string unmet(const World& w, int object, bool fold) {
  const std::string name = "'" + w.scene().objects()[object].name + "'";
  if (!applies(w, object)) return name + " is not a cloth";
  if (w.grasped_object() >= 0) return "the hand is not empty";
  if ((fold ? folded(w, object) : unfolded(w, object))) return name + " is already " + (fold ? "folded" : "unfolded");
  return "";
}

// Sets the cloth's hinges: all straight, then, to fold, the first body of
// each branch along +y turned over its spine body.
void shape(World& w, int object, bool fold) {
  const mjModel* m = w.model();
  mjData* d = w.data();
  const SceneObject& o = w.scene().objects()[object];
  const int root = m->body_rootid[o.body];
  for (int j = 0; j < m->njnt; ++j) {
    if (m->jnt_type[j] != mjJNT_HINGE || m->body_rootid[m->jnt_bodyid[j]] != root) continue;
    d->qpos[m->jnt_qposadr[j]] = 0;
    d->qvel[m->jnt_dofadr[j]] = 0;
  }
  if (fold) {
    int count = 0;  // tiles along a side: bodies <name>B<i>_0
    while (mj_name2id(m, mjOBJ_BODY, (o.name + "B" + std::to_string(count) + "_0").c_str()) >= 0) ++count;
    const std::string above = std::to_string(count / 2 + 1);
    for (int i = 0; i < count; ++i) {
      const int j = mj_name2id(m, mjOBJ_JOINT, (o.name + "J0_" + std::to_string(i) + "_" + above).c_str());
      if (j >= 0) d->qpos[m->jnt_qposadr[j]] = kFoldAngle;
    }
  }
  mj_forward(m, d);
}

bool act(Executor& e, bool fold) {
  World& w = e.world();
  if (e.motion().physical()) {
    return e.fail(PrimitiveStatus::precondition_failure,
                  "folding is symbolic only: the assistive grasp holds a cloth by its centre, not an edge");
  }
  if (!e.go_to_pre_pose()) return false;
  shape(w, e.object(), fold);
  if (!e.tuck_where_possible()) return false;
  if (fold ? !folded(w, e.object()) : !unfolded(w, e.object())) {
    return e.fail(PrimitiveStatus::place_failure,
                  "'" + e.name() + "' is not " + (fold ? "folded" : "unfolded") + " (too few tiles to fold)");
  }
  return true;
}

// Where pick takes the cloth (its top centre): within reach for one, within
// reach for the other, as navigate (which aims for a pick) and the planner's
// model have it.
std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  return pick_primitive().approaches(w, object, base);
}

// Symbolically: the cloth is folded (unfolded) by an empty hand within reach.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a, bool fold) {
  const SymbolicObject& o = objects[a.target];
  if (o.kind != SymbolicObject::Kind::object || !o.has("cloth")) return {};
  SymbolicStep s;
  s.needs = {literal(kHandEmpty, {}), literal(kWithinReach, {a.target}), literal("real", {a.target})};
  s.adds = {literal(fold ? "folded" : "unfolded", {a.target})};
  s.deletes = {literal(fold ? "unfolded" : "folded", {a.target})};
  return {s};
}

}  // namespace

const PrimitiveDef& fold_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = [](const World& w, int object) { return unmet(w, object, true); },
                                .act = [](Executor& e) { return act(e, true); },
                                .model = [](const std::vector<SymbolicObject>& objects,
                                            const SymbolicArgs& a) { return model(objects, a, true); },
                                .approaches = approaches,
                                .touches = false,
                                .symbolic_only = true};
  return def;
}

const PrimitiveDef& unfold_primitive() {
  static const PrimitiveDef def{
      .applies = applies,
      .unmet_precondition = [](const World& w, int object) { return unmet(w, object, false); },
      .act = [](Executor& e) { return act(e, false); },
      .model = [](const std::vector<SymbolicObject>& objects,
                  const SymbolicArgs& a) { return model(objects, a, false); },
      .approaches = approaches,
      .touches = false,
      .symbolic_only = true};
  return def;
}

}  // namespace chore
