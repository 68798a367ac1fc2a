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

std::vector<SymbolicStep> only_while_open(const std::vector<SymbolicObject>& objects, int object,
                                          const SymbolicStep& step) {
  std::vector<SymbolicStep> out = {step};
  for (int c = 0; c < static_cast<int>(objects.size()); ++c) {
    if (c == object || objects[c].kind != SymbolicObject::Kind::object || !objects[c].has("openable")) continue;
    out[0].needs_not.push_back(literal("inside", {object, c}));
    SymbolicStep from = step;
    from.needs.push_back(literal("inside", {object, c}));
    from.needs.push_back(literal("open", {c}));
    out.push_back(from);
  }
  return out;
}

int agent_index(const std::vector<SymbolicObject>& objects) {
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].kind == SymbolicObject::Kind::agent) return static_cast<int>(i);
  }
  return -1;
}

}  // namespace chore
