// push(object), close(object): a drawer pulled open or pushed shut
// (OmniGibson's OPEN and CLOSE). push: to its handle until the fingertips
// touch the front, close on the handle, back the base away (the arm held) to
// pull it most of the way open, release, tuck. close: the closed hand to the
// handle and on along the drawer's axis as far as it is open, pushing it shut
// (physically by contact; symbolically the drawer follows the hand), back
// off, tuck. Both share this file: one drawer, two directions.
#include <mujoco/mujoco.h>

#include <algorithm>

#include "primitives/primitive_def.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

bool applies(const World& w, int object) {
  return articulation(w, object).has_value();
}

std::string unmet(const World& w, int object, bool open) {
  if (w.grasped_object() >= 0) return "the hand is not empty";
  const std::string name = "'" + w.scene().objects().at(object).name + "'";
  const auto a = articulation(w, object);
  if (!a) return name + " has no drawer to " + (open ? "open" : "close");
  if (open) return open_fraction(*a) > 0.9 ? name + " is already open" : "";
  return is_open(w, object) ? "" : name + " is already closed";
}

std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  if (const auto a = articulation(w, object)) return {{a->handle, -a->axis, kUp}};
  return {{top_centre(w, object, base), kDown, std::nullopt}};
}

bool pull_open(Executor& e) {
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

// The hand's centre ends where the handle is when the drawer is shut.
Eigen::Vector3d line_end(const World& w, int object, const Approach& ap, const Pose2&, double) {
  const auto a = articulation(w, object);
  return ap.point - ap.direction * kFingerReach - a->axis * (a->value - a->low);
}

bool push_shut(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  const auto a = articulation(w, e.object());  // there is one: the precondition held
  m.gripper(false);                            // a closed hand pushes
  if (!e.go_to_pre_pose()) return false;
  // On through where the front is to where it is when shut (and 2 cm on):
  // physically the hand meets the front and pushes it; symbolically the
  // drawer follows the hand past where it met the front.
  const Eigen::Vector3d before = m.hand_position();
  m.line(-a->axis * (kClearance + (a->value - a->low) + 0.02), false, kApproachSpeed, 0.0);  // as far as the arm goes
  if (!m.physical()) {
    const double moved = -a->axis.dot(m.hand_position() - before) - kClearance;
    w.data()->qpos[w.model()->jnt_qposadr[a->joint]] = std::clamp(a->value - moved, a->low, a->high);
    mj_forward(w.model(), w.data());
  }
  m.line(a->axis * 0.08, false, kRetreatSpeed, 0.0);
  m.gripper(true);
  if (!e.tuck_where_possible()) return false;
  if (is_open(w, e.object())) {
    return e.fail(PrimitiveStatus::motion_planning_failure, "'" + e.name() + "' is still open");
  }
  return true;
}

// Symbolically: an openable object opens (closes), with an empty hand.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a, bool open) {
  const SymbolicObject& o = objects[a.target];
  if (o.kind != SymbolicObject::Kind::object || !o.has("openable")) return {};
  SymbolicStep s;
  s.needs = {literal(kHandEmpty, {}), literal(kWithinReach, {a.target}), literal("real", {a.target})};
  (open ? s.needs_not : s.needs).push_back(literal("open", {a.target}));
  (open ? s.adds : s.deletes).push_back(literal("open", {a.target}));
  return {s};
}

}  // namespace

const PrimitiveDef& push_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = [](const World& w, int object) { return unmet(w, object, true); },
                                .act = pull_open,
                                .model = [](const std::vector<SymbolicObject>& objects,
                                            const SymbolicArgs& a) { return model(objects, a, true); },
                                .approaches = approaches,
                                .opens = true};
  return def;
}

const PrimitiveDef& close_primitive() {
  static const PrimitiveDef def{
      .applies = applies,
      .unmet_precondition = [](const World& w, int object) { return unmet(w, object, false); },
      .act = push_shut,
      .model = [](const std::vector<SymbolicObject>& objects,
                  const SymbolicArgs& a) { return model(objects, a, false); },
      .approaches = approaches,
      .line_end = line_end,
      .opens = true};
  return def;
}

}  // namespace chore
