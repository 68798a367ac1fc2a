// toggle_on(object), toggle_off(object): OmniGibson's TOGGLE_ON and
// TOGGLE_OFF, one press each. The hand comes down onto the object's toggle
// point (world/state_rules.hpp) and holds there for the env steps the world's
// toggling rule counts, then lifts: physically the rule toggles it; in
// symbolic mode the motion is planned and checked the same way and the state
// set at the press. Both share this file: one press, two target states.
#include "primitives/primitive_def.hpp"
#include "world/predicates.hpp"
#include "world/state_rules.hpp"

namespace chore {
namespace {

// The env steps (1/30 s) the rule counts the hand held at the toggle point,
// and three more: the hand settles after its approach (physically 2-3 steps
// above ObjectStates::kToggleSpeed).
constexpr double kPressSeconds = (ObjectStates::kToggleSteps + 3) / 30.0;
// m from the toggle point towards the base a press may aim: the fingers
// within ObjectStates::kToggleDistance of it. Pointing down, the fingertips
// stop on the top 7 cm short. Tilted, the hand stops with its centre 5.6 cm
// back and 5.6 cm up from the point it aimed at, where a finger meets the
// top, the fingertips 2.8 cm back and up: aimed 4 cm short, they stay within
// 7.3 cm (aimed 7 cm short, 10.2 cm, and nothing turned on).
constexpr double kNearer = 0.07;
constexpr double kTiltedNearer = 0.04;

bool applies(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  return ab && ab->toggleable;
}

std::string unmet(const World& w, int object, bool on) {
  if (w.grasped_object() >= 0) return "the hand is not empty";
  const std::string name = "'" + w.scene().objects().at(object).name + "'";
  if (!applies(w, object)) return name + " cannot be toggled";
  if (toggled_on(w, object) == on) return name + " is already " + (on ? "on" : "off");
  return "";
}

// On the toggle point; else as far towards the base as the rule still
// counts the fingers there once they press down (a stove's centre on a deep
// counter lies beyond the arm's reach from above). Where no pose reaches
// down onto them, the same tilted 45 degrees towards the object: a coffee
// maker or a mixer on a counter has its top at 1.2-1.5 m, and the hand
// points down no higher than 1.2 m (tilted, Ik: 1.3-1.4 m).
std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  const Eigen::Vector3d point = toggle_point(w, object);
  const Eigen::Vector3d towards(base.x - point.x(), base.y - point.y(), 0);
  if (towards.norm() < kNearer) return {{point, kDown, std::nullopt}};
  const Eigen::Vector3d tilted = tilted_towards(-towards);
  return {{point, kDown, std::nullopt},
          {point + towards.normalized() * kNearer, kDown, std::nullopt},
          {point, tilted, std::nullopt, true},
          {point + towards.normalized() * kTiltedNearer, tilted, std::nullopt, true}};
}

bool press(Executor& e, bool on) {
  World& w = e.world();
  Motion& m = e.motion();
  const int object = e.object();
  if (!e.go_to_pre_pose()) return false;
  // Onto the toggle point until the fingers touch, no deeper than the
  // rule's reach beyond it (a sink's basin lies lower).
  const Eigen::Vector3d along = e.approach().direction * (kClearance + ObjectStates::kToggleDistance / 2);
  if (!m.line(along, true, kApproachSpeed)) return false;
  if (!m.physical()) w.states().state(object).toggled = on;
  m.wait(kPressSeconds);
  m.line(kUp * kLift, false, kRetreatSpeed, 0.0);
  if (!e.tuck_where_possible()) return false;
  if (toggled_on(w, object) != on) {
    return e.fail(PrimitiveStatus::motion_planning_failure,
                  "the hand did not stay at the toggle point of '" + e.name() + "'");
  }
  return true;
}

// Symbolically: the object is on (off), pressed with an empty hand.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a, bool on) {
  const SymbolicObject& o = objects[a.target];
  if (o.kind != SymbolicObject::Kind::object || !o.has("toggleable")) return {};
  SymbolicStep s;
  s.needs = {literal(kHandEmpty, {}), literal(kWithinReach, {a.target}), literal("real", {a.target})};
  (on ? s.needs_not : s.needs).push_back(literal("toggled_on", {a.target}));
  (on ? s.adds : s.deletes).push_back(literal("toggled_on", {a.target}));
  return {s};
}

}  // namespace

const PrimitiveDef& toggle_on_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = [](const World& w, int object) { return unmet(w, object, true); },
                                .act = [](Executor& e) { return press(e, true); },
                                .model = [](const std::vector<SymbolicObject>& objects,
                                            const SymbolicArgs& a) { return model(objects, a, true); },
                                .approaches = approaches,
                                .own_doors_as_they_are = true};
  return def;
}

const PrimitiveDef& toggle_off_primitive() {
  static const PrimitiveDef def{
      .applies = applies,
      .unmet_precondition = [](const World& w, int object) { return unmet(w, object, false); },
      .act = [](Executor& e) { return press(e, false); },
      .model = [](const std::vector<SymbolicObject>& objects,
                  const SymbolicArgs& a) { return model(objects, a, false); },
      .approaches = approaches,
      .own_doors_as_they_are = true};
  return def;
}

}  // namespace chore
