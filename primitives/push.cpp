// push(object): opens a drawer. To its handle until the fingertips touch the
// front, close on the handle, back the base away (the arm held) to pull it
// most of the way open, release, tuck.
#include <mujoco/mujoco.h>

#include <algorithm>

#include "primitives/primitive_def.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

bool applies(const World& w, int object) {
  return articulation(w, object).has_value();
}

std::string unmet_precondition(const World& w, int object) {
  if (w.grasped_object() >= 0) return "the hand is not empty";
  const std::string name = "'" + w.scene().objects().at(object).name + "'";
  const auto a = articulation(w, object);
  if (!a) return name + " has no drawer to open";
  return open_fraction(*a) > 0.9 ? name + " is already open" : "";
}

std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  if (const auto a = articulation(w, object)) return {{a->handle, -a->axis, kUp}};
  return {{top_centre(w, object, base), kDown, std::nullopt}};
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  const auto a = articulation(w, e.object());  // there is one: the precondition held
  if (!e.go_to_pre_pose()) return false;
  // To the handle until the fingertips touch the front, close on the handle, pull.
  if (!m.line(-a->axis * (kClearance + 0.06), true, kApproachSpeed)) return false;
  if (!m.touched()) return e.fail(PrimitiveStatus::motion_planning_failure, "the hand did not reach the handle");
  m.gripper(false);
  if (m.physical() && w.grasped_body() != a->link) {
    m.gripper(true);
    return e.fail(PrimitiveStatus::grasp_failure, "the hand missed the handle of '" + e.name() + "'");
  }
  // Pull most of the way open by backing the base away, the arm held.
  const double pull = (a->high - a->low) * kPullFraction - (a->value - a->low);
  const Eigen::Vector3d before = m.hand_position();
  if (!m.base_line(a->axis * pull)) return false;
  if (!m.physical()) {
    // The drawer follows the hand kinematically.
    const double moved = a->axis.dot(m.hand_position() - before);
    w.data()->qpos[w.model()->jnt_qposadr[a->joint]] = std::clamp(a->value + moved, a->low, a->high);
    mj_forward(w.model(), w.data());
  }
  m.gripper(true);
  m.line(a->axis * 0.08, false, kRetreatSpeed, 0.0);  // back off as far as the arm goes
  if (!e.tuck_where_possible()) return false;
  if (!is_open(w, e.object()))
    return e.fail(PrimitiveStatus::grasp_failure, "the handle slipped: '" + e.name() + "' stays closed");
  return true;
}

// Symbolically: an openable object opens.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const SymbolicObject& o = objects[a.target];
  if (o.kind != SymbolicObject::Kind::object || !o.has("openable")) return {};
  SymbolicStep s;
  s.needs = {literal(kHandEmpty, {}), literal(kWithinReach, {a.target}), literal("real", {a.target})};
  s.needs_not = {literal("open", {a.target})};
  s.adds = {literal("open", {a.target})};
  return {s};
}

}  // namespace

const PrimitiveDef& push_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .approaches = approaches,
                                .opens = true};
  return def;
}

}  // namespace chore
