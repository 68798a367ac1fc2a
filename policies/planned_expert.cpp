#include "policies/planned_expert.hpp"

#include <set>

#include "base/error.hpp"
#include "env/env.hpp"
#include "env/task_plan.hpp"
#include "planner/reachability.hpp"
#include "planner/symbolic_problem.hpp"
#include "primitives/primitive.hpp"
#include "tasks/activity.hpp"

namespace chore {
namespace {

// A literal of the planner's read from the world: the robot's predicates,
// and the activity's own checks for BDDL's; nullopt where the world cannot
// say (a room, something the planner made up on the way), which keeps what
// the planner had.
std::optional<bool> observe(const EnvState& env, const SymbolicProblem& p, const SymbolicLiteral& l) {
  const World& w = env.world();
  const Activity& activity = *env.activity();
  const auto object = [&](int i) -> int {
    if (i >= p.declared) return -1;
    const Binding& b = activity.binding(p.objects[i].name);
    return b.kind == Binding::Kind::object ? b.index : -1;
  };
  if (l.predicate == kHandEmpty) return w.grasped_object() < 0;
  if (l.predicate == kHeated || l.predicate == kChilled) return false;  // the world's steps derive them
  if (l.predicate == "inroom") return std::nullopt;                     // never changes
  const int first = l.args.empty() ? -1 : object(l.args[0]);
  if (l.predicate == kWithinReach) return first >= 0 ? std::optional<bool>(within_reach(w, first)) : std::nullopt;
  if (l.predicate == "real") return first >= 0 ? std::optional<bool>(w.real(first)) : std::nullopt;
  if (l.predicate == "future") return first >= 0 ? std::optional<bool>(!w.real(first)) : std::nullopt;
  if (l.predicate == "grasped" && l.args.size() == 2) {
    const int held = object(l.args[1]);
    return held >= 0 ? std::optional<bool>(w.grasped_object() == held) : std::nullopt;
  }
  // BDDL's: on the activity's instances; BEHAVIOR-100's dirt and soaking in
  // its own words (the planner's covered / saturated with a substance).
  GroundLiteral bddl{l.predicate, {}, false};
  for (size_t k = 0; k < l.args.size(); ++k) {
    const int a = l.args[k];
    if (a >= p.declared) {
      const std::string& s = p.objects[a].synset;
      if (l.args.size() != 2 || k != 1) return std::nullopt;
      if (l.predicate == "covered" && s == "stain.n.01")
        bddl.predicate = "stained";
      else if (l.predicate == "covered" && s == "dust.n.01")
        bddl.predicate = "dusty";
      else if (l.predicate == "saturated" && s == "water.n.06")
        bddl.predicate = "soaked";
      else
        return std::nullopt;
      continue;
    }
    bddl.args.push_back(p.objects[a].name);
  }
  try {
    return activity.holds(w, bddl);
  } catch (const Error&) {
    return std::nullopt;  // a predicate or argument the checks do not take
  }
}

// What the hand holds, as the planner says it: (grasped agent X), or
// (handempty); nullopt for a held object the planner does not know.
std::optional<SymbolicLiteral> hand(const EnvState& env, const SymbolicProblem& p) {
  const int held = env.world().grasped_object();
  if (held < 0) return literal(kHandEmpty, {});
  for (int i = 0; i < p.declared; ++i) {
    const Binding& b = env.activity()->binding(p.objects[i].name);
    if (b.kind == Binding::Kind::object && b.index == held) return literal("grasped", {agent_index(p.objects), i});
  }
  return std::nullopt;
}

}  // namespace

PlannedExpert::PlannedExpert(const EnvState& env, const PlanOptions& options) : options_(options) {
  if (env.config().action_space != "primitives")
    throw Error("planned expert: the env must use the primitive action space");
  const Activity* activity = env.activity();
  if (!activity) throw Error("planned expert: the env has no activity");
  goal_ = &activity->goal();
  problem_ = symbolic_problem(*activity, env.world().scene());
  for (const PrimitiveAction& a : env.primitive_actions()) options_.actions.insert(to_string(a));
  steps_of_problem_ = ground_steps(problem_);
  std::set<SymbolicLiteral> known(problem_.init.begin(), problem_.init.end());
  for (const SymbolicStep& s : steps_of_problem_.steps) {
    for (const auto* list : {&s.needs, &s.needs_not, &s.adds, &s.deletes}) known.insert(list->begin(), list->end());
  }
  literals_.assign(known.begin(), known.end());
  initial_ = plan_task(problem_, steps_of_problem_, *goal_, options_);
  if (!initial_.found) {
    unusable_ = "no plan: " + initial_.reason;
    plan_ = initial_;
    return;
  }
  if (!follow(env, initial_)) unusable_ = failure_;
}

bool PlannedExpert::follow(const EnvState& env, Plan plan) {
  plan_ = std::move(plan);
  actions_.clear();
  steps_.clear();
  next_ = 0;
  tries_ = 0;
  still_.clear();
  const std::vector<PrimitiveAction>& actions = env.primitive_actions();
  for (size_t i = 0; i < plan_.steps.size(); ++i) {
    const PlanStep& s = plan_.steps[i];
    int index = -1;
    for (size_t a = 0; s.primitive && a < actions.size() && index < 0; ++a) {
      if (to_string(actions[a]) == s.name) index = static_cast<int>(a);
    }
    if (s.primitive && index < 0) {
      failure_ = "step " + std::to_string(i + 1) + ", " + s.name + ": not in the env's primitive action space";
      return false;
    }
    actions_.push_back(index);
    if (s.primitive) steps_.push_back(i);
  }
  return true;
}

bool PlannedExpert::replan(const EnvState& env, const std::string& why) {
  if (replans_ >= kReplans) {
    failure_ = why + " (after " + std::to_string(replans_) + " plans from the world)";
    return false;
  }
  ++replans_;
  SymbolicProblem now = problem_;
  now.init.clear();
  for (const SymbolicLiteral& l : literals_) {
    const std::optional<bool> holds = observe(env, problem_, l);
    if (holds ? *holds : problem_.init.count(l) > 0) now.init.insert(l);
  }
  // The steps with the bars on; a copy only when some step is barred.
  std::optional<GroundSteps> barred;
  for (const auto& [step_and_hand, plans] : failed_) {
    if (plans < kBarAfter) continue;
    if (!barred) barred = steps_of_problem_;
    for (size_t i = 0; i < barred->primitives; ++i)
      if (barred->steps[i].name == step_and_hand.first) barred->steps[i].needs_not.push_back(step_and_hand.second);
  }
  Plan plan = plan_task(now, barred ? *barred : steps_of_problem_, *goal_, options_);
  // No other way: the step again (from elsewhere it may work: a primitive
  // that failed out of reach here, after a navigate).
  if (!plan.found && barred) plan = plan_task(now, steps_of_problem_, *goal_, options_);
  if (!plan.found) {
    failure_ = why + "; from the world as it is, no plan: " + plan.reason;
    return false;
  }
  return follow(env, std::move(plan));
}

std::optional<int> PlannedExpert::wait_for_world(const EnvState& env) const {
  if (waits_ >= kWaits) return std::nullopt;
  const std::vector<PrimitiveAction>& actions = env.primitive_actions();
  // Whether what a world step makes does not hold yet (what the world says
  // of its literals; the planner's own heated and chilled it cannot say).
  const auto pending = [&](const std::string& name) {
    for (const SymbolicStep& step : steps_of_problem_.steps) {
      if (step.name != name) continue;
      for (const SymbolicLiteral& l : step.adds) {
        if (l.predicate != kHeated && l.predicate != kChilled && observe(env, problem_, l) == false) return true;
      }
      for (const SymbolicLiteral& l : step.deletes) {
        if (observe(env, problem_, l) == true) return true;
      }
    }
    return false;
  };
  for (auto s = plan_.steps.rbegin(); s != plan_.steps.rend(); ++s) {
    // A world step's name: "heat(raw_egg.n.01_1)", its objects in brackets.
    const size_t open = s->name.find('('), close = s->name.rfind(')');
    if (s->primitive || open == std::string::npos || close == std::string::npos || close < open || !pending(s->name))
      continue;
    std::string args = s->name.substr(open + 1, close - open - 1);
    for (size_t from = 0; from <= args.size();) {
      const size_t comma = std::min(args.find(',', from), args.size());
      std::string arg = args.substr(from, comma - from);
      arg.erase(0, arg.find_first_not_of(' '));
      for (size_t a = 0; a < actions.size(); ++a) {
        if (actions[a].type == PrimitiveType::wait && actions[a].instance == arg && !still_.count(static_cast<int>(a)))
          return static_cast<int>(a);
      }
      from = comma + 1;
    }
  }
  return std::nullopt;
}

void PlannedExpert::restart(const EnvState& env) {
  failure_.clear();
  replans_ = 0;
  waits_ = 0;
  waiting_ = -1;
  failed_.clear();
  if (unusable_.empty()) follow(env, initial_);
}

std::optional<int> PlannedExpert::act(const EnvState& env, PrimitiveStatus last, const std::string& last_reason) {
  if (!unusable_.empty() || !failure_.empty()) return std::nullopt;
  if (env.activity()->score(env.world()).success) return std::nullopt;
  if (waiting_ >= 0) {
    // A wait at the plan's end: where nothing changed, not that one again.
    if (last != PrimitiveStatus::success) still_.insert(waiting_);
    waiting_ = -1;
  } else if (next_ > 0 && last != PrimitiveStatus::success) {
    const size_t step = steps_[next_ - 1];
    if (tries_ <= kRetries) {
      ++tries_;
      return actions_[step];
    }
    if (const std::optional<SymbolicLiteral> held = hand(env, problem_)) ++failed_[{plan_.steps[step].name, *held}];
    if (!replan(env, "step " + std::to_string(step + 1) + ", " + plan_.steps[step].name + ": " + to_string(last) +
                         ": " + last_reason))
      return std::nullopt;
  }
  const std::vector<PrimitiveAction>& actions = env.primitive_actions();
  for (;;) {
    while (next_ < steps_.size()) {
      const PrimitiveAction& a = actions[actions_[steps_[next_]]];
      if (a.type != PrimitiveType::navigate || !within_reach(env.world(), a.object)) break;
      ++next_;
    }
    if (next_ < steps_.size()) {
      tries_ = 1;
      return actions_[steps_[next_++]];
    }
    // The plan is done and the goal does not hold: what the world still has
    // to do may take time; else plan again (bounded: waits and replans count).
    if (const std::optional<int> wait = wait_for_world(env)) {
      ++waits_;
      waiting_ = *wait;
      return *wait;
    }
    if (!replan(env, "the plan ran to its end and the goal does not hold")) return std::nullopt;
  }
}

}  // namespace chore
