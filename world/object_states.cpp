#include "world/object_states.hpp"

#include <cmath>

namespace chore {

std::string missing_for_state(const std::string& p, const ObjectAbilities& ab) {
  if (p == "cooked" || p == "burnt" || p == "frozen" || p == "hot") return ab.temperature ? "" : "Temperature";
  if (p == "on_fire") {
    if (!ab.temperature) return "Temperature";
    return std::isfinite(ab.ignition_temperature) ? "" : "an ignition temperature (not flammable)";
  }
  if (p == "soaked" || p == "saturated") return ab.soakable ? "" : "SoakedLevel";
  if (p == "covered" || p == "dusty" || p == "stained") return ab.covered ? "" : "CoveredLevel";
  if (p == "filled" || p == "contains") return ab.holds_liquid ? "" : "a liquid level";
  if (p == "toggled_on") return ab.toggleable ? "" : "ToggledState";
  if (p == "sliced") return ab.sliceable ? "" : "SlicedState";
  if (p == "broken") return ab.breakable ? "" : "BrokenState";
  return "";
}

double ObjectState::level() const {
  double sum = 0;
  for (const auto& [substance, level] : contents) sum += level;
  return sum;
}

std::string ObjectState::main_substance() const {
  std::string most;
  double highest = 0;
  for (const auto& [substance, level] : contents) {
    if (level > highest) most = substance, highest = level;
  }
  return most;
}

void ObjectStates::configure(int object, const ObjectAbilities& abilities) {
  abilities_[object] = abilities;
  states_[object] = ObjectState{};
}

void ObjectStates::add_substance(const Substance& substance) {
  substances_[substance.name] = substance;
}

const ObjectAbilities* ObjectStates::abilities(int object) const {
  const auto it = abilities_.find(object);
  return it == abilities_.end() ? nullptr : &it->second;
}

const Substance* ObjectStates::substance(const std::string& name) const {
  const auto it = substances_.find(name);
  return it == substances_.end() ? nullptr : &it->second;
}

void ObjectStates::add_transition(Transition transition) {
  transitions_.push_back(std::move(transition));
  progress_.push_back(0);
}

void ObjectStates::reset() {
  for (auto& [object, state] : states_) state = ObjectState{};
  progress_.assign(transitions_.size(), 0);
  last_hand_.reset();
}

}  // namespace chore
