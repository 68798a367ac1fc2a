// pour(object): the substance the held container holds, onto the object
// (covered) and, into a container, into it (it then contains it too),
// OmniGibson's pouring and particle application. The held container is carried over the object's
// top as place carries a load; there what it holds runs out. Substances are
// states (world/object_states.hpp), not simulated particles: physically the
// motion is tracked in physics and the substance moves at the pour pose.
#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/sampling.hpp"

namespace chore {
namespace {

constexpr double kFullLevel = 0.8;  // a container poured into fills up to this (sampling's filled)
// m between the held container's bottom and the target's top as it pours: a
// pour needs no room to descend, and a mug held high over a bowl on a
// counter is beyond the arm.
constexpr double kPourClearance = 0.03;

bool applies(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  return ab && (ab->holds_liquid || ab->covered);
}

std::string unmet_precondition(const World& w, int object) {
  const int held = w.carried_object();
  if (held < 0) return "the hand holds nothing";
  if (held == object) return "cannot pour into what the hand holds";
  const ObjectAbilities* from = w.states().abilities(held);
  const std::string name = "'" + w.scene().objects()[held].name + "'";
  if (!from || !from->holds_liquid || w.states().state(held).level() <= 0) return name + " holds nothing to pour";
  const ObjectAbilities* to = w.states().abilities(object);
  const std::string target = "'" + w.scene().objects()[object].name + "'";
  if (!to || !(to->holds_liquid || to->covered)) return target + " takes no substance";
  return "";
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  const int held = w.grasped_object(), target = e.object();
  if (!e.go_to_pre_pose_with_load()) return false;
  m.wait(0.3);
  ObjectState& from = w.states().state(held);
  const std::string substance = from.main_substance();
  // Into a container it fills it, beside what is there (a recipe's
  // ingredients mix there); onto anything that keeps a covered state, a
  // container too (poured in, it wets it), it covers it.
  const ObjectAbilities& to_ab = *w.states().abilities(target);
  if (to_ab.holds_liquid) {
    ObjectState& to = w.states().state(target);
    const double room = std::max(0.0, kFullLevel - to.level()), poured = from.level();
    for (const auto& [name, level] : from.contents) to.contents[name] += level * std::min(1.0, room / poured);
  }
  if (to_ab.covered) {
    Rng rng(m.next_seed());
    for (const auto& [name, level] : from.contents) sample_covered(w, target, name, true, rng);
  }
  // A source that is on (a sprayer, a watering can) gives on: it keeps what it gives.
  const ObjectAbilities& from_ab = *w.states().abilities(held);
  if (!(from.toggled && !from_ab.source.empty())) from.contents.clear();
  m.line(kUp * kLift, false, kRetreatSpeed, 0.0);
  if (!e.tuck_where_possible()) return false;
  if (!contains(w, target, substance) && !covered(w, target, substance)) {
    return e.fail(PrimitiveStatus::place_failure, "nothing of '" + substance + "' reached '" + e.name() + "'");
  }
  return true;
}

// Symbolically: what the held container contains goes onto the object
// (covered) and, for a container, into it (contains, filled).
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  const SymbolicObject& target = objects[a.target];
  const SymbolicObject& held = a.held < 0 ? target : objects[a.held];
  // A container, or a bottle, shaker or sprayer that gives its substance
  // (particleSource, particleApplier: what it gives, it contains).
  const bool gives = held.has("fillable") || held.has("particleSource") || held.has("particleApplier");
  if (agent < 0 || a.held < 0 || a.substance < 0 || a.held == a.target || target.kind != SymbolicObject::Kind::object ||
      !gives) {
    return {};
  }
  SymbolicStep s;
  s.needs = {literal("grasped", {agent, a.held}), literal(kWithinReach, {a.target}),
             literal("contains", {a.held, a.substance})};
  s.deletes = {literal("contains", {a.held, a.substance}), literal("filled", {a.held, a.substance})};
  s.adds = {literal("covered", {a.target, a.substance})};
  if (target.has("fillable")) {
    s.adds.push_back(literal("contains", {a.target, a.substance}));
    s.adds.push_back(literal("filled", {a.target, a.substance}));
  }
  return {s};
}

}  // namespace

const PrimitiveDef& pour_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .about_substance = true,
                                .touches = false,
                                .clearance = kPourClearance};
  return def;
}

}  // namespace chore
