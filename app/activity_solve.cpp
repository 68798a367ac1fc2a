#include "app/activity_solve.hpp"

#include "base/error.hpp"
#include "policies/planned_expert.hpp"

namespace chore {

// Episodes long enough for any plan the search returns, with its retries.
constexpr int kSolveEpisodeSteps = 1000;

nlohmann::json solve_activity(EnvConfig config, uint64_t seed, ExecutionMode mode) {
  config.action_space = "primitives";
  config.primitive_mode = mode;
  config.observations = {"proprio"};
  config.reachable_instances = true;  // the env as a user gets it
  config.max_episode_steps = kSolveEpisodeSteps;
  Env env(config);
  Info info;
  try {
    info = env.reset(seed).info;
  } catch (const Error& e) {
    return {{"found", false}, {"built", false}, {"solved", false}, {"planning_seconds", 0.0}, {"reason", e.what()}};
  }
  PlannedExpert expert(env);
  const Plan& plan = expert.initial_plan();
  nlohmann::json steps = nlohmann::json::array();
  for (const PlanStep& s : plan.steps) steps.push_back(s.primitive ? s.name : "[" + s.name + "]");
  nlohmann::json out = {{"found", plan.found},
                        {"built", true},
                        {"expansions", plan.expansions},
                        {"planning_seconds", plan.seconds},
                        {"plan", steps},
                        {"primitives", plan.primitives()}};
  PrimitiveStatus last = PrimitiveStatus::success;
  std::string reason;
  int taken = 0;
  while (const std::optional<int> action = expert.act(env, last, reason)) {
    const float a = static_cast<float>(*action);
    const Env::StepResult r = env.step({&a, 1});
    ++taken;
    info = r.info;
    last = static_cast<PrimitiveStatus>(info.primitive_status);
    reason = env.last_primitive().reason;
    if (r.terminated || r.truncated) break;
  }
  const bool solved = info.success && info.q >= 1.0;
  out["solved"] = solved;
  out["q"] = info.q;
  out["steps_taken"] = taken;
  out["replans"] = expert.replans();
  if (!solved) {
    out["reason"] = !expert.failure().empty() ? expert.failure()
                    : info.success            ? "success with Q " + std::to_string(info.q)
                                              : "the plan ran to its end with Q " + std::to_string(info.q);
  }
  return out;
}

}  // namespace chore
