#include "planner/reachability.hpp"

#include "primitives/primitive.hpp"

namespace chore {
namespace {

using Kind = SymbolicObject::Kind;

// Every primitive's steps on these objects.
std::vector<SymbolicStep> primitive_steps(const std::vector<SymbolicObject>& objects) {
  std::vector<int> held = {-1}, substances = {-1};
  for (int i = 0; i < static_cast<int>(objects.size()); ++i) {
    if (objects[i].movable()) held.push_back(i);
    if (objects[i].kind == Kind::substance) substances.push_back(i);
  }
  std::vector<SymbolicStep> out;
  for (int t = 0; t < kPrimitiveTypes; ++t) {
    const auto type = static_cast<PrimitiveType>(t);
    const bool about_substance = primitive_about_substance(type);
    for (int target = 0; target < static_cast<int>(objects.size()); ++target) {
      for (const int h : held) {
        for (const int s : substances) {
          if (about_substance != (s >= 0)) continue;
          for (SymbolicStep& step : primitive_model(type, objects, {target, h, s})) out.push_back(std::move(step));
        }
      }
    }
  }
  return out;
}

std::string text(const Literal& l) {
  std::string out = "(" + l.predicate;
  for (const std::string& a : l.args) out += " " + a;
  out += ")";
  return l.negated ? "(not " + out + ")" : out;
}

}  // namespace

GroundSteps ground_steps(const SymbolicProblem& problem) {
  GroundSteps out{primitive_steps(problem.objects), 0};
  out.primitives = out.steps.size();
  out.steps.insert(out.steps.end(), problem.world_steps.begin(), problem.world_steps.end());
  return out;
}

Reachability reachability(const SymbolicProblem& problem) {
  const std::vector<SymbolicStep> steps = ground_steps(problem).steps;
  Reachability r;
  r.reachable = problem.init;
  std::vector<bool> fired(steps.size(), false);
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 0; i < steps.size(); ++i) {
      if (fired[i]) continue;
      const SymbolicStep& s = steps[i];
      bool ready = true;
      for (const SymbolicLiteral& need : s.needs) {
        if (!r.reachable.count(need)) {
          ready = false;
          break;
        }
      }
      if (!ready) continue;
      fired[i] = changed = true;
      for (const SymbolicLiteral& add : s.adds) {
        if (r.reachable.insert(add).second) r.achiever.emplace(add, s.name);
      }
      r.deletable.insert(s.deletes.begin(), s.deletes.end());
    }
  }
  return r;
}

bool Reachability::achievable(const SymbolicProblem& problem, const Literal& literal) const {
  const auto l = symbolic_literal(problem, literal);
  if (!l) return false;
  if (!literal.negated) return reachable.count(*l) > 0;
  return !problem.init.count(*l) || deletable.count(*l);
}

GoalReach goal_reach(const SymbolicProblem& problem, const Reachability& reach, const GroundGoal& goal,
                     const KnowledgeBase& kb, const TransitionRules& rules) {
  GoalReach out;
  for (const GroundLiteral& l : goal.literals) {
    ++out.literals;
    if (reach.achievable(problem, l)) {
      ++out.achievable;
    } else {
      out.unachievable[(l.negated ? "not " : "") + l.predicate].push_back(text(l));
    }
  }
  for (int i = 0; i < problem.declared; ++i) {
    if (!problem.init.count({"future", {i}})) continue;
    ++out.future;
    const SymbolicObject& o = problem.objects[i];
    bool made = false;
    for (const TransitionRule& r : rules.rules()) {
      for (const SynsetCount& output : r.outputs) {
        made = made || output.synset == o.synset ||
               (kb.contains(output.synset) && kb.contains(o.synset) && kb.is_a(output.synset, o.synset));
      }
    }
    if (!made) out.future_without_rule.push_back(o.name);
    if (!reach.reachable.count({"real", {i}})) out.future_unreachable.push_back(o.name);
  }
  return out;
}

}  // namespace chore
