#include "env/primitive_actions.hpp"

#include <algorithm>
#include <set>

namespace chore {
namespace {

// Instances (or variable types, as "?type") that something is put on or in.
void placement_targets(const Formula& f, std::set<std::string>& names,
                       std::vector<const Variable*>& scope) {
  if (f.op == Op::literal) {
    const Literal& l = f.literal;
    if ((l.predicate == "ontop" || l.predicate == "inside") && l.args.size() == 2 && !l.negated) {
      const std::string& target = l.args[1];
      const auto var = std::find_if(scope.rbegin(), scope.rend(),
                                    [&](const Variable* v) { return v->name == target; });
      names.insert(var != scope.rend() ? "?" + (*var)->type : target);
    }
    return;
  }
  for (const Variable& v : f.variables) scope.push_back(&v);
  for (const Formula& child : f.children) placement_targets(child, names, scope);
  scope.resize(scope.size() - f.variables.size());
}

}  // namespace

std::string to_string(const PrimitiveAction& action) {
  return std::string(to_string(action.type)) + "(" + action.instance + ")";
}

std::vector<PrimitiveAction> primitive_actions(const Activity& activity, const World& world) {
  const Problem& problem = activity.problem();
  std::set<std::string> targets;
  for (const Literal& l : problem.init) {
    Formula f;
    f.literal = l;
    std::vector<const Variable*> scope;
    placement_targets(f, targets, scope);
  }
  std::vector<const Variable*> scope;
  placement_targets(problem.goal, targets, scope);

  std::vector<PrimitiveAction> actions;
  for (const ObjectDecl& decl : problem.objects) {
    const Binding& b = activity.binding(decl.name);
    if (b.kind != Binding::Kind::object) continue;
    const bool target = targets.count(decl.name) || targets.count("?" + decl.type);
    for (int t = 0; t < kPrimitiveTypes; ++t) {
      const auto type = static_cast<PrimitiveType>(t);
      const bool applies = type == PrimitiveType::place ? target : primitive_applies(world, type, b.index);
      if (applies) actions.push_back({type, b.index, decl.name});
    }
  }
  return actions;
}

}  // namespace chore
