#include "policies/planned_expert.hpp"

#include "base/error.hpp"
#include "env/env.hpp"
#include "planner/symbolic_problem.hpp"
#include "primitives/primitive.hpp"
#include "tasks/activity.hpp"
#include "tasks/vocabulary.hpp"

namespace chore {

PlannedExpert::PlannedExpert(const EnvState& env, const PlanOptions& options) {
  if (env.config().action_space != "primitives")
    throw Error("planned expert: the env must use the primitive action space");
  const Activity* activity = env.activity();
  if (!activity) throw Error("planned expert: the env has no activity");
  const auto kb = dialect_knowledge_base(activity->problem().domain);
  SymbolicProblem problem = symbolic_problem(activity->problem(), *kb, behavior_transition_rules());
  // What the knowledge base calls openable but the scene's object has no
  // joint to open (a bin without a lid) is open as it stands.
  for (int i = 0; i < problem.declared; ++i) {
    SymbolicObject& o = problem.objects[i];
    const Binding& b = activity->binding(o.name);
    if (b.kind == Binding::Kind::object && env.world().scene().objects()[b.index].joints.empty())
      o.properties.erase("openable");
  }
  PlanOptions within = options;  // what the env's action space offers
  for (const PrimitiveAction& a : env.primitive_actions()) within.actions.insert(to_string(a));
  plan_ = plan_task(problem, activity->goal(), within);
  if (!plan_.found) {
    unusable_ = "no plan: " + plan_.reason;
    return;
  }
  const std::vector<PrimitiveAction>& actions = env.primitive_actions();
  for (size_t i = 0; i < plan_.steps.size(); ++i) {
    const PlanStep& s = plan_.steps[i];
    int index = -1;
    for (size_t a = 0; s.primitive && a < actions.size() && index < 0; ++a) {
      if (to_string(actions[a]) == s.name) index = static_cast<int>(a);
    }
    if (s.primitive && index < 0) {
      unusable_ = "step " + std::to_string(i + 1) + ", " + s.name + ": not in the env's primitive action space";
      return;
    }
    actions_.push_back(index);
    if (s.primitive) steps_.push_back(i);
  }
}

void PlannedExpert::restart() {
  next_ = 0;
  tries_ = 0;
  failure_.clear();
}

std::optional<int> PlannedExpert::act(const EnvState& env, PrimitiveStatus last, const std::string& last_reason) {
  if (!unusable_.empty() || !failure_.empty()) return std::nullopt;
  if (next_ > 0 && last != PrimitiveStatus::success) {
    const size_t step = steps_[next_ - 1];
    if (tries_ <= kRetries) {
      ++tries_;
      return actions_[step];
    }
    failure_ = "step " + std::to_string(step + 1) + ", " + plan_.steps[step].name + ": " + to_string(last) + ": " +
               last_reason;
    return std::nullopt;
  }
  const std::vector<PrimitiveAction>& actions = env.primitive_actions();
  while (next_ < steps_.size()) {
    const PrimitiveAction& a = actions[actions_[steps_[next_]]];
    if (a.type != PrimitiveType::navigate || !within_reach(env.world(), a.object)) break;
    ++next_;
  }
  if (next_ >= steps_.size()) return std::nullopt;
  tries_ = 1;
  return actions_[steps_[next_++]];
}

}  // namespace chore
