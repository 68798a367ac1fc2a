#include "world/object_states.hpp"

namespace chore {

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

void ObjectStates::reset() {
  for (auto& [object, state] : states_) state = ObjectState{};
}

}  // namespace chore
