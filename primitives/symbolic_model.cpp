#include "primitives/symbolic_model.hpp"

namespace chore {

double SymbolicObject::parameter(const char* property, const char* name, double fallback) const {
  const auto p = properties.find(property);
  if (p == properties.end()) return fallback;
  const auto v = p->second.find(name);
  return v == p->second.end() ? fallback : v->second;
}

SymbolicLiteral literal(const char* predicate, std::vector<int> args) {
  return {predicate, std::move(args)};
}

void end_placements(const std::vector<SymbolicObject>& objects, int object, SymbolicStep& step) {
  for (int other = 0; other < static_cast<int>(objects.size()); ++other) {
    if (other == object) continue;
    for (const char* p : kPlacements) {
      step.deletes.push_back({p, {object, other}});
      step.deletes.push_back({p, {other, object}});
    }
  }
}

SymbolicStep setting_down(int agent, const SymbolicArgs& a, std::vector<SymbolicLiteral> adds) {
  SymbolicStep s;
  s.needs = {literal("grasped", {agent, a.held}), literal(kWithinReach, {a.target}), literal("real", {a.target})};
  s.deletes = {literal("grasped", {agent, a.held})};
  s.adds = {literal(kHandEmpty, {})};
  s.adds.insert(s.adds.end(), adds.begin(), adds.end());
  return s;
}

int agent_index(const std::vector<SymbolicObject>& objects) {
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].kind == SymbolicObject::Kind::agent) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace chore
