#include "app/activity_solve.hpp"

#include "app/activity_commands.hpp"
#include "base/error.hpp"
#include "policies/planned_expert.hpp"

namespace chore {

// Episodes long enough for any plan the search returns, with its retries.
constexpr int kSolveEpisodeSteps = 1000;

nlohmann::json solve_activity(EnvConfig config, uint64_t seed, ExecutionMode mode, cv::Mat* final_state,
                              int picture_size) {
  config.action_space = "primitives";
  config.primitive_mode = mode;
  config.observations = {final_state ? "rgb" : "proprio"};  // the head camera only for the picture
  if (final_state) config.width = config.height = picture_size;
  config.reachable_instances = true;  // the env as a user gets it
  config.max_episode_steps = kSolveEpisodeSteps;
  Env env(config);
  Info info;
  const ArrayDict* obs = nullptr;  // the env's, valid while it lives
  try {
    const Env::ResetResult reset = env.reset(seed);
    info = reset.info;
    obs = &reset.obs;
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
    obs = &r.obs;
    last = static_cast<PrimitiveStatus>(info.primitive_status);
    reason = env.last_primitive().reason;
    if (r.terminated || r.truncated) break;
  }
  const bool solved = info.success && info.q >= 1.0;
  if (final_state && solved) *final_state = instance_picture(env, *obs, picture_size, picture_size);
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
