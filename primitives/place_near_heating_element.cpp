// place_near_heating_element(object): OmniGibson's PLACE_NEAR_HEATING_ELEMENT,
// the carried object set on a heat (or cold) source where the source acts on
// it (a pan on a stove, a kettle on a campfire's grate), as place sets it
// down. A source that acts only on what is inside it (an oven, a fridge) has
// no element to place near: OmniGibson refuses it, as this does (place it
// inside instead).
#include "primitives/primitive_def.hpp"
#include "world/state_rules.hpp"

namespace chore {
namespace {

// The source's heat or cold, where it has an element to place near.
const ThermalSource* element(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  if (!ab) return nullptr;
  const std::optional<ThermalSource>& t = ab->heat_source ? ab->heat_source : ab->cold_source;
  return t && !t->requires_inside ? &*t : nullptr;
}

bool applies(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  return ab && (ab->heat_source || ab->cold_source);
}

std::string unmet_precondition(const World& w, int object) {
  if (w.carried_object() < 0) return "the hand holds nothing";
  const std::string name = "'" + w.scene().objects()[object].name + "'";
  if (!applies(w, object)) return name + " is not a heat or cold source";
  if (!element(w, object)) return name + " acts only on what is inside it: place it inside";
  return "";
}

bool act(Executor& e) {
  World& w = e.world();
  const int held = w.grasped_object();
  if (!e.go_to_pre_pose_with_load() || !e.release()) return false;
  if (!within_thermal_reach(w, e.object(), *element(w, e.object()), held)) {
    return e.fail(PrimitiveStatus::place_failure,
                  "'" + w.scene().objects()[held].name + "' is not where '" + e.name() + "' would heat it");
  }
  return true;
}

// Symbolically: place's step onto the source (the planner's heated follows
// from it lying on a source that works).
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const SymbolicObject& source = objects[a.target];
  const char* property = source.has("heatSource") ? "heatSource" : source.has("coldSource") ? "coldSource" : nullptr;
  if (!property || source.parameter(property, "requires_inside", 0) > 0) return {};
  std::vector<SymbolicStep> onto = primitive_def(PrimitiveType::place).model(objects, a);
  onto.resize(std::min<size_t>(onto.size(), 1));  // on it, not in it
  return onto;
}

}  // namespace

const PrimitiveDef& place_near_heating_element_primitive() {
  static const PrimitiveDef def{
      .applies = applies, .unmet_precondition = unmet_precondition, .act = act, .model = model, .touches = false};
  return def;
}

}  // namespace chore
