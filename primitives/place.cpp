// place(object): the carried object over a flat spot on (or in) the object,
// released, and the hand back: on or in it, or a place failure.
#include "primitives/primitive_def.hpp"
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

bool act(Executor& e) {
  World& w = e.world();
  const int held = w.grasped_object();
  if (!e.go_to_pre_pose_with_load() || !e.release()) return false;
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
  // On it, it touches it.
  const SymbolicStep on = setting_down(agent, a,
                                       {literal("touching", {a.held, a.target}),
                                        literal("touching", {a.target, a.held}), literal("ontop", {a.held, a.target})});
  if (!target.has("fillable")) return {on};
  SymbolicStep in = setting_down(agent, a, {literal("inside", {a.held, a.target})});
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
