#include "app/expert_command.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>
#include <numeric>
#include <thread>

#include "base/error.hpp"
#include "env/env.hpp"
#include "policies/expert.hpp"
#include "policies/planned_expert.hpp"

namespace chore {
namespace {

struct Episode {
  bool success = false, policy_failure = false, stuck = false, diverged = false;
  double q = 0;
  int steps = 0;
  int64_t physics_steps = 0;
  std::array<int, kPrimitiveStatuses> counts{};
  std::vector<std::string> failures;  // "pick(cup.n.01_1): grasp_failure: ..."
  double seconds = 0;
};

// With `planned`, the planner's expert acts; else the scripted one.
Episode run_episode(Env& env, uint64_t seed, PlannedExpert* planned) {
  const auto start = std::chrono::steady_clock::now();
  const ScriptedExpert expert(env);
  Episode e;
  env.reset(seed);
  if (planned) planned->restart(env);
  for (bool done = false; !done;) {
    const std::optional<int> a =
        planned ? planned->act(env, e.steps > 0 ? env.last_primitive().status : PrimitiveStatus::success,
                               env.last_primitive().reason)
                : expert.act(env);
    if (!a) {
      e.stuck = true;
      break;
    }
    const float value = static_cast<float>(*a);
    const Env::StepResult r = env.step({&value, 1});
    const PrimitiveAction& action = env.primitive_actions()[*a];
    if (r.info.primitive_status > 0) {
      e.failures.push_back(to_string(action) + ": " + to_string(static_cast<PrimitiveStatus>(r.info.primitive_status)) +
                           ": " + env.last_primitive().reason);
    }
    e.steps = static_cast<int>(r.info.elapsed_steps);
    e.physics_steps += r.info.physics_steps;
    e.success = r.info.success;
    e.q = r.info.q;
    e.counts = r.info.primitive_counts;
    e.policy_failure = r.info.policy_failure;
    e.diverged = r.info.diverged;
    done = r.terminated || r.truncated;
  }
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return e;
}

}  // namespace

nlohmann::json run_expert(const ExpertOptions& options, std::ostream& log) {
  if (options.episodes < 1) throw Error("expert: --episodes must be at least 1");
  if (options.threads < 1) throw Error("expert: --threads must be at least 1");
  EnvConfig config;
  config.activity = options.activity;
  config.observations = {"is_grasping"};  // the expert reads the state, not pictures
  config.action_space = "primitives";
  config.primitive_mode = options.mode;
  config.max_episode_steps = options.max_steps;
  const EnvAssets assets = load_assets(config);

  std::vector<Episode> episodes(options.episodes);
  std::atomic<int> next{0};
  std::mutex log_mutex;
  const auto start = std::chrono::steady_clock::now();
  std::exception_ptr error;  // the first a worker met; it stops the others and is rethrown here
  // The planner where asked, or where the script does not know the goal.
  std::atomic<bool> planner{options.planner};
  auto worker = [&] {
    try {
      Env env(config, assets);
      if (!ScriptedExpert::knows(*env.activity())) planner = true;
      std::optional<PlannedExpert> planned;  // planned once: the plan is :init's, the same every episode
      for (int i = next++; i < options.episodes; i = next++) {
        if (planner && !planned) {
          env.reset(options.seed + static_cast<uint64_t>(i));
          planned.emplace(env);
        }
        episodes[i] = run_episode(env, options.seed + static_cast<uint64_t>(i), planned ? &*planned : nullptr);
        const std::lock_guard<std::mutex> lock(log_mutex);
        log << "episode " << i << " (seed " << options.seed + i
            << "): " << (episodes[i].success ? "success" : "failure") << ", " << episodes[i].steps << " steps, Q "
            << episodes[i].q << "\n";
      }
    } catch (...) {
      const std::lock_guard<std::mutex> lock(log_mutex);
      if (!error) error = std::current_exception();
      next = options.episodes;
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < std::min(options.threads, options.episodes); ++t) threads.emplace_back(worker);
  for (std::thread& t : threads) t.join();
  if (error) std::rethrow_exception(error);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  nlohmann::json failures = nlohmann::json::object();
  for (int s = 1; s < kPrimitiveStatuses; ++s) failures[to_string(static_cast<PrimitiveStatus>(s))] = 0;
  int successes = 0, policy_failures = 0, stuck = 0, diverged = 0;
  int64_t steps = 0, physics_steps = 0;
  double q = 0;
  nlohmann::json per_episode = nlohmann::json::array();
  for (const Episode& e : episodes) {
    successes += e.success;
    policy_failures += e.policy_failure;
    stuck += e.stuck;
    diverged += e.diverged;
    steps += e.steps;
    physics_steps += e.physics_steps;
    q += e.q;
    for (int s = 1; s < kPrimitiveStatuses; ++s) {
      failures[to_string(static_cast<PrimitiveStatus>(s))] =
          failures[to_string(static_cast<PrimitiveStatus>(s))].get<int>() + e.counts[s];
    }
    per_episode.push_back({{"success", e.success}, {"q", e.q}, {"steps", e.steps}, {"failed_primitives", e.failures}});
  }
  const double n = options.episodes;
  return {{"activity", options.activity},
          {"expert", planner ? "planner" : "scripted"},
          {"mode", to_string(options.mode)},
          {"episodes", options.episodes},
          {"seed", options.seed},
          {"success_rate", successes / n},
          {"mean_q", q / n},
          {"mean_episode_length", steps / n},
          {"primitive_failures", failures},
          {"policy_failures", policy_failures},
          {"expert_stuck", stuck},
          {"diverged", diverged},
          {"primitive_steps_per_second", steps / seconds},
          {"simulated_seconds_per_primitive", steps ? physics_steps / 120.0 / steps : 0.0},
          {"wall_seconds", seconds},
          {"threads", options.threads},
          {"per_episode", per_episode}};
}

std::string format_expert(const nlohmann::json& r) {
  char line[256];
  std::string out;
  std::snprintf(line, sizeof line, ", %s mode, the %s expert, %d episodes from seed %llu\n",
                r["mode"].get<std::string>().c_str(), r["expert"] == "planner" ? "planner's" : "scripted",
                r["episodes"].get<int>(), static_cast<unsigned long long>(r["seed"].get<uint64_t>()));
  out += r["activity"].get<std::string>() + line;
  std::snprintf(line, sizeof line,
                "  success rate         %.1f%%\n  mean Q               %.3f\n"
                "  mean episode length  %.1f primitive steps\n",
                100 * r["success_rate"].get<double>(), r["mean_q"].get<double>(),
                r["mean_episode_length"].get<double>());
  out += line;
  out += "  failed primitives   ";
  for (const auto& [name, count] : r["primitive_failures"].items())
    out += " " + name + " " + std::to_string(count.get<int>());
  std::snprintf(line, sizeof line, "\n  policy failures %d, expert stuck %d, diverged %d\n",
                r["policy_failures"].get<int>(), r["expert_stuck"].get<int>(), r["diverged"].get<int>());
  out += line;
  std::snprintf(line, sizeof line, "  %.1f primitive steps/s (%d threads), %.1f s simulated per primitive\n",
                r["primitive_steps_per_second"].get<double>(), r["threads"].get<int>(),
                r["simulated_seconds_per_primitive"].get<double>());
  out += line;
  return out;
}

}  // namespace chore
