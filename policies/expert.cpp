#include "policies/expert.hpp"

#include <algorithm>

#include "base/error.hpp"
#include "env/env.hpp"
#include "world/predicates.hpp"

namespace chore {

ScriptedExpert::ScriptedExpert(const EnvState& env) : actions_(&env.primitive_actions()) {
  if (env.config().action_space != "primitives") {
    throw Error("scripted expert: the env must use the primitive action space");
  }
}

std::optional<int> ScriptedExpert::action(PrimitiveType type, int object) const {
  for (size_t i = 0; i < actions_->size(); ++i) {
    if ((*actions_)[i].type == type && (*actions_)[i].object == object) return static_cast<int>(i);
  }
  return std::nullopt;
}

// Navigate first unless the hand already reaches the object from here.
std::optional<int> ScriptedExpert::go_and(const EnvState& env, PrimitiveType type, int object) const {
  if (!within_reach(env.world(), object)) return action(PrimitiveType::navigate, object);
  return action(type, object);
}

std::optional<int> ScriptedExpert::put(const EnvState& env, int item, int target) const {
  const World& w = env.world();
  const int held = w.grasped_object();
  if (held == item) return go_and(env, PrimitiveType::place, target);
  if (held >= 0) return go_and(env, PrimitiveType::place, target);  // put down what is in the way
  if (primitive_applies(w, PrimitiveType::push, target) && !is_open(w, target)) {
    return go_and(env, PrimitiveType::push, target);
  }
  return go_and(env, PrimitiveType::pick, item);
}

std::optional<int> ScriptedExpert::clean(const EnvState& env, int surface, bool needs_soaked_tool) const {
  const World& w = env.world();
  const ObjectStates& states = w.states();
  // The tool: a cleaning tool of the action space, the one in hand first.
  int tool = -1, container = -1;
  for (const PrimitiveAction& a : *actions_) {
    const ObjectAbilities* ab = states.abilities(a.object);
    if (a.type == PrimitiveType::pick && ab && ab->cleaning_tool && (tool < 0 || a.object == w.grasped_object())) {
      tool = a.object;
    }
    if (a.type == PrimitiveType::dip && container < 0) container = a.object;
  }
  if (tool < 0) return std::nullopt;
  if (w.grasped_object() != tool) return go_and(env, PrimitiveType::pick, tool);
  if (needs_soaked_tool && container >= 0) {
    const auto& soaked = states.state(tool).soaked;
    const std::string liquid = states.state(container).main_substance();
    if (!soaked.count(liquid) || soaked.at(liquid) < ObjectStates::kSoakedLevel) {
      return go_and(env, PrimitiveType::dip, container);
    }
  }
  return go_and(env, PrimitiveType::wipe, surface);
}

std::optional<int> ScriptedExpert::act(const EnvState& env) const {
  const Activity* activity = env.activity();
  const World& w = env.world();
  const GroundGoal& goal = activity->goal();
  if (goal.options.empty()) return std::nullopt;
  for (LiteralId id : goal.options.front()) {
    const GroundLiteral& l = goal.literals[id];
    if (activity->holds(w, l)) continue;
    const auto object = [&](size_t k) { return activity->object(l.args.at(k)); };
    if ((l.predicate == "inside" || l.predicate == "ontop") && !l.negated) return put(env, object(0), object(1));
    if ((l.predicate == "stained" || l.predicate == "dusty") && l.negated) {
      return clean(env, object(0), l.predicate == "stained");
    }
    return std::nullopt;  // a literal this script does not know
  }
  return std::nullopt;
}

bool ScriptedExpert::knows(const Activity& activity) {
  const GroundGoal& goal = activity.goal();
  if (goal.options.empty()) return false;
  return std::all_of(goal.options.front().begin(), goal.options.front().end(), [&](LiteralId id) {
    const GroundLiteral& l = goal.literals[id];
    return l.negated ? l.predicate == "stained" || l.predicate == "dusty"
                     : l.predicate == "inside" || l.predicate == "ontop";
  });
}

ExpertPolicy::ExpertPolicy(const VectorEnv& envs)
    : envs_(envs),
      expert_(envs.state(0)),
      planned_(envs.state(0).activity() && !ScriptedExpert::knows(*envs.state(0).activity())),
      planners_(envs.num_envs()) {}

void ExpertPolicy::reset(std::span<const int> env_ids) {
  if (!planned_) return;
  for (const int id : env_ids) {
    std::optional<PlannedExpert>& planner = planners_.at(id);
    if (planner) {
      planner->restart(envs_.state(id));
    } else {
      planner.emplace(envs_.state(id));  // :init's plan, the same every episode
    }
  }
}

void ExpertPolicy::act(const Batch& batch, std::span<float> actions) {
  for (int row = 0; row < batch.size(); ++row) {
    const int id = batch.env_ids[row];
    const EnvState& env = envs_.state(id);
    // (A planner is made at reset; one made here serves a caller that does not reset the policy.)
    if (planned_ && !planners_.at(id)) planners_[id].emplace(env);
    const Info& info = batch.infos[row];
    const PrimitiveStatus last =
        info.primitive_status > 0 ? static_cast<PrimitiveStatus>(info.primitive_status) : PrimitiveStatus::success;
    std::optional<int> a = planned_ ? planners_[id]->act(env, last, "") : expert_.act(env);
    for (size_t i = 0; !a && i < env.primitive_actions().size(); ++i) {
      const PrimitiveAction& p = env.primitive_actions()[i];
      if (!unmet_precondition(env.world(), p.type, p.object).empty()) a = static_cast<int>(i);
    }
    actions[row] = static_cast<float>(a.value_or(0));
  }
}

}  // namespace chore
