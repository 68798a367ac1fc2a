// close(object): OmniGibson's CLOSE for a drawer. The closed hand to the
// drawer's front at its handle, then on along the drawer's axis as far as it
// is open, pushing it shut (physically by contact; symbolically the drawer
// follows the hand), back off, tuck.
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
  if (!a) return name + " has no drawer to close";
  return is_open(w, object) ? "" : name + " is already closed";
}

std::vector<Approach> approaches(const World& w, int object, const Pose2&) {
  const auto a = articulation(w, object);
  if (!a) return {};
  return {{a->handle, -a->axis, kUp}};
}

// The hand's centre ends where the handle is when the drawer is shut.
Eigen::Vector3d line_end(const World& w, int object, const Approach& ap, const Pose2&, double) {
  const auto a = articulation(w, object);
  return ap.point - ap.direction * kFingerReach - a->axis * (a->value - a->low);
}

bool act(Executor& e) {
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

// Symbolically: an open openable object closes.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const SymbolicObject& o = objects[a.target];
  if (o.kind != SymbolicObject::Kind::object || !o.has("openable")) return {};
  SymbolicStep s;
  s.needs = {literal(kHandEmpty, {}), literal(kWithinReach, {a.target}), literal("open", {a.target}),
             literal("real", {a.target})};
  s.deletes = {literal("open", {a.target})};
  return {s};
}

}  // namespace

const PrimitiveDef& close_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .approaches = approaches,
                                .line_end = line_end,
                                .opens = true};
  return def;
}

}  // namespace chore
