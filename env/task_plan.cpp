#include "env/task_plan.hpp"

#include "planner/task_planner.hpp"
#include "tasks/transition_rules.hpp"
#include "tasks/vocabulary.hpp"

namespace chore {

SymbolicProblem symbolic_problem(const Activity& activity, const Scene& scene) {
  const auto kb = dialect_knowledge_base(activity.problem().domain);
  SymbolicProblem problem = symbolic_problem(activity.problem(), *kb, behavior_transition_rules());
  for (int i = 0; i < problem.declared; ++i) {
    SymbolicObject& o = problem.objects[i];
    const Binding& b = activity.binding(o.name);
    if (b.kind == Binding::Kind::object && scene.objects()[b.index].joints.empty()) o.properties.erase("openable");
  }
  return problem;
}

std::optional<std::set<std::string>> actions_a_plan_needs(const Activity& activity, const Scene& scene) {
  const Plan plan =
      plan_task(symbolic_problem(activity, scene), activity.goal(), {.max_expansions = kNeededActionsBudget});
  std::set<std::string> needed;
  if (plan.found) {
    for (const PlanStep& s : plan.steps) {
      if (s.primitive) needed.insert(s.name);
    }
    return needed;
  }
  if (plan.relaxed.empty()) return std::nullopt;
  return std::set<std::string>(plan.relaxed.begin(), plan.relaxed.end());
}

}  // namespace chore
