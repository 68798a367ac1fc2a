// push(object), close(object): a drawer pulled open or pushed shut, a door
// or lid swung open or shut about its hinge (OmniGibson's OPEN and CLOSE).
// push: to the handle until the fingertips touch the front, close on it,
// then pull: a drawer by backing the base away (the arm held), most of the
// way open; a door by turning the hand with it about the hinge, as far as
// the arm reaches; release, back off, tuck. close: the closed hand to the
// handle and on, pushing: a drawer along its axis as far as it is open, a
// door about its hinge until shut (physically by contact; symbolically the
// link follows the hand), back off, tuck. Both share this file: one link,
// two directions.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "primitives/primitive_def.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

constexpr double kTurnSpeed = 0.1;  // m/s of the base round a door's hinge

bool applies(const World& w, int object) {
  return articulation(w, object).has_value();
}

std::string unmet(const World& w, int object, bool open) {
  if (w.grasped_object() >= 0) return "the hand is not empty";
  const std::string name = "'" + w.scene().objects().at(object).name + "'";
  const auto a = articulation(w, object);
  if (!a) return name + " has no drawer, door or lid to " + (open ? "open" : "close");
  if (open) return open_fraction(*a) > 0.9 ? name + " is already open" : "";
  return is_open(w, object) ? "" : name + " is already closed";
}

std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  if (const auto a = articulation(w, object)) {
    // The fingers close across a drawer's front, along a door's hinge.
    const Eigen::Vector3d closing = !a->hinge ? kUp : a->axis.z() < 0 ? Eigen::Vector3d(-a->axis) : a->axis;
    return {{a->handle, -a->pull, closing}};
  }
  return {{top_centre(w, object, base), kDown, std::nullopt}};
}

// The angle (rad) the hand turned about a hinge from `from` to `to`.
double turned(const Articulation& a, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  const Eigen::Vector3d r0 = from - a.pivot, r1 = to - a.pivot;
  return std::atan2(a.axis.dot(r0.cross(r1)), r0.dot(r1) - a.axis.dot(r0) * a.axis.dot(r1));
}

// The hand turned by `angle` about a hinge, as far as it goes: round a
// door's upright hinge first the whole robot (the base, the arm held: the
// arm alone does not reach far round) as far as there is room, then the arm
// alone; round a lid's the arm.
bool turn(Motion& m, const Articulation& a, double angle) {
  const Eigen::Vector3d from = m.hand_position();
  if (std::abs(a.axis.z()) > 0.9 && !m.base_arc(a.pivot, angle * a.axis.z(), a.link, kTurnSpeed, 0.0)) return false;
  const double left = angle - turned(a, from, m.hand_position());
  // Pulling open, the hand holds the handle and turns with it; pushing shut,
  // a closed hand pushes whichever way it points (which reaches further).
  const bool turn_hand = angle > 0;
  return std::abs(left) < 1e-3 || m.arc(a.pivot, a.axis, left, false, kApproachSpeed, 0.0, turn_hand);
}

bool pull_open(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  const auto a = articulation(w, e.object());  // there is one: the precondition held
  if (!e.go_to_pre_pose()) return false;
  // To the handle until the fingertips touch the front, close on the handle, pull.
  if (!m.line(-a->pull * (kClearance + 0.06), true, kApproachSpeed)) return false;
  if (!m.touched()) return e.fail(PrimitiveStatus::motion_planning_failure, "the hand did not reach the handle");
  m.gripper(false);
  if (m.physical() && w.grasped_body() != a->link) {
    m.gripper(true);
    return e.fail(PrimitiveStatus::grasp_failure, "the hand missed the handle of '" + e.name() + "'");
  }
  const double pull = (a->high - a->low) * kPullFraction - (a->value - a->low);
  const Eigen::Vector3d before = m.hand_position();
  if (a->hinge) {
    if (!turn(m, *a, pull)) return false;
    if (!m.physical()) set_articulation(w, *a, a->value + turned(*a, before, m.hand_position()));
  } else {
    // Most of the way open by backing the base away, the arm held.
    if (!m.base_line(a->axis * pull)) return false;
    if (!m.physical()) set_articulation(w, *a, a->value + a->axis.dot(m.hand_position() - before));
  }
  m.gripper(true);
  // Back off as far as the arm goes.
  m.line(a->hinge ? Eigen::Vector3d(-m.hand_axis(0) * 0.08) : Eigen::Vector3d(a->axis * 0.08), false, kRetreatSpeed,
         0.0);
  if (!e.tuck_where_possible()) return false;
  if (!is_open(w, e.object()))
    return e.fail(PrimitiveStatus::grasp_failure, "the handle slipped: '" + e.name() + "' stays closed");
  return true;
}

// The hand's centre ends where a drawer's handle is when it is shut; at a
// door's face, from where it turns the door shut.
Eigen::Vector3d line_end(const World& w, int object, const Approach& ap, const Pose2&, double) {
  const auto a = articulation(w, object);
  const Eigen::Vector3d at_face = ap.point - ap.direction * kFingerReach;
  return a->hinge ? at_face : Eigen::Vector3d(at_face - a->axis * (a->value - a->low));
}

bool push_shut(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  const auto a = articulation(w, e.object());  // there is one: the precondition held
  m.gripper(false);                            // a closed hand pushes
  if (!e.go_to_pre_pose()) return false;
  if (a->hinge) {
    // To the door's face, then about the hinge to where it is shut (and 3
    // degrees on), as far as the arm goes: physically the hand pushes the
    // door; symbolically the door follows it.
    m.line(-a->pull * (kClearance + 0.02), true, kApproachSpeed, 0.0);
    const Eigen::Vector3d before = m.hand_position();
    turn(m, *a, -(a->value - a->low) - 0.05);
    if (!m.physical()) set_articulation(w, *a, a->value + turned(*a, before, m.hand_position()));
    m.line(-m.hand_axis(0) * 0.08, false, kRetreatSpeed, 0.0);
  } else {
    // On through where the front is to where it is when shut (and 2 cm on):
    // physically the hand meets the front and pushes it; symbolically the
    // drawer follows the hand past where it met the front.
    const Eigen::Vector3d before = m.hand_position();
    m.line(-a->axis * (kClearance + (a->value - a->low) + 0.02), false, kApproachSpeed, 0.0);  // as far as the arm goes
    if (!m.physical()) set_articulation(w, *a, a->value - (-a->axis.dot(m.hand_position() - before) - kClearance));
    m.line(a->axis * 0.08, false, kRetreatSpeed, 0.0);
  }
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
