#include "policies/evaluate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "base/error.hpp"
#include "policies/expert.hpp"
#include "policies/plugin.hpp"

namespace chore {
namespace {

struct Episode {
  uint64_t seed = 0, env_seed = 0;
  bool success = false, policy_failure = false, truncated = false, diverged = false;
  double q = 0;
  int64_t length = 0;
  std::array<int, kPrimitiveStatuses> primitives{};  // by status
};

// Mean and population standard deviation.
nlohmann::json mean_std(const std::vector<double>& values) {
  const double n = static_cast<double>(values.size());
  const double mean = std::accumulate(values.begin(), values.end(), 0.0) / n;
  double squares = 0;
  for (double v : values) squares += (v - mean) * (v - mean);
  return {{"mean", mean}, {"std", std::sqrt(squares / n)}};
}

Episode finish(const Info& info, bool truncated, uint64_t seed, uint64_t env_seed) {
  Episode e;
  e.seed = seed;
  e.env_seed = env_seed;
  e.success = info.success;
  e.q = info.q;
  e.length = info.elapsed_steps;
  e.primitives = info.primitive_counts;
  e.policy_failure = info.policy_failure;
  e.diverged = info.diverged;
  e.truncated = truncated && !info.diverged;
  return e;
}

}  // namespace

PolicySource expert_source(const std::string& activity, ExecutionMode mode, int max_steps) {
  EnvConfig env;
  env.activity = activity;
  env.action_space = "primitives";
  env.primitive_mode = mode;
  env.observations = {"is_grasping"};
  env.max_episode_steps = max_steps;
  return {"expert", env, [](const VectorEnv& envs) { return std::make_unique<ExpertPolicy>(envs); }};
}

PolicySource plugin_source(const std::string& library, const std::string& options, const EnvConfig& env) {
  return {library, env, [library, options](const VectorEnv& envs) {
            const PolicySpec spec{&envs.single_observation_space(), &envs.single_action_space(), options.c_str()};
            return load_policy_plugin(library, spec);
          }};
}

nlohmann::json evaluate(const PolicySource& source, const EvalOptions& options, std::ostream& log) {
  if (options.episodes < 1) throw Error("eval: --episodes must be at least 1");
  if (options.episodes >= static_cast<int64_t>(kEpisodeSeedStride)) {
    throw Error("eval: --episodes must be below " + std::to_string(kEpisodeSeedStride));
  }
  if (options.threads < 1) throw Error("eval: --threads must be at least 1");
  if (options.last_seed < options.first_seed) throw Error("eval: --seeds A-B needs A <= B");
  VectorEnvConfig config;
  config.env = source.env;
  config.num_envs = std::min(options.threads, options.episodes);
  config.num_threads = config.num_envs;
  config.batch_size = 1;  // act on each env as soon as its step is done
  VectorEnv envs(config);
  const std::unique_ptr<Policy> policy = source.make(envs);
  const size_t action_size = std::max<size_t>(1, envs.single_action_space().element_count());
  std::vector<float> actions(envs.num_envs() * action_size);

  std::vector<Episode> episodes;
  int64_t env_steps = 0;
  const auto start = std::chrono::steady_clock::now();
  for (uint64_t seed = options.first_seed; seed <= options.last_seed; ++seed) {
    // Rounds of num_envs episodes: reset(base) seeds env i with base + i.
    for (int first = 0; first < options.episodes; first += envs.num_envs()) {
      const uint64_t base = seed * kEpisodeSeedStride + first;
      const int count = std::min(envs.num_envs(), options.episodes - first);
      std::vector<int> ids(count);
      std::iota(ids.begin(), ids.end(), 0);
      const Batch reset = envs.reset(base);
      policy->reset(ids);
      policy->act(reset, actions);
      envs.send(std::span(actions).first(count * action_size), ids);
      for (int running = count; running > 0;) {
        const Batch b = envs.recv();
        const int e = b.env_ids[0];
        ++env_steps;
        if (b.terminated[0] || b.truncated[0]) {
          episodes.push_back(finish(b.infos[0], b.truncated[0], seed, base + e));
          --running;
          continue;
        }
        policy->act(b, std::span(actions).first(action_size));
        envs.send(std::span(actions).first(action_size), b.env_ids);
      }
    }
    const auto of_seed =
        std::count_if(episodes.begin(), episodes.end(), [&](const Episode& e) { return e.seed == seed && e.success; });
    log << source.label << ": seed " << seed << ": " << of_seed << "/" << options.episodes << " successes\n";
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  envs.close();

  // Episodes finish out of order within a round: report them in seed order.
  std::sort(episodes.begin(), episodes.end(),
            [](const Episode& a, const Episode& b) { return a.env_seed < b.env_seed; });
  std::vector<double> success, q, length;
  nlohmann::json per_seed = nlohmann::json::array(), per_episode = nlohmann::json::array();
  std::array<int, kPrimitiveStatuses> primitives{};
  int successes = 0, policy_failures = 0, time_limits = 0, diverged = 0;
  for (size_t first = 0; first < episodes.size(); first += options.episodes) {
    double s = 0, sq = 0, sl = 0;
    for (size_t i = first; i < first + options.episodes; ++i) {
      const Episode& e = episodes[i];
      s += e.success;
      successes += e.success;
      sq += e.q;
      sl += static_cast<double>(e.length);
      for (int k = 0; k < kPrimitiveStatuses; ++k) primitives[k] += e.primitives[k];
      policy_failures += e.policy_failure;
      time_limits += e.truncated;
      diverged += e.diverged;
      per_episode.push_back({{"seed", e.seed},
                             {"env_seed", e.env_seed},
                             {"success", e.success},
                             {"q", e.q},
                             {"length", e.length},
                             {"policy_failure", e.policy_failure},
                             {"time_limit", e.truncated},
                             {"diverged", e.diverged}});
    }
    const double n = options.episodes;
    success.push_back(s / n);
    q.push_back(sq / n);
    length.push_back(sl / n);
    per_seed.push_back(
        {{"seed", episodes[first].seed}, {"success_rate", s / n}, {"q", sq / n}, {"episode_length", sl / n}});
  }
  nlohmann::json failures = nlohmann::json::object();
  for (int k = 1; k < kPrimitiveStatuses; ++k) failures[to_string(static_cast<PrimitiveStatus>(k))] = primitives[k];
  const EnvConfig& env = source.env;
  return {{"policy", source.label},
          {"activity", env.activity},
          {"action_space", env.action_space},
          {"mode", env.action_space == "primitives" ? to_string(env.primitive_mode) : ""},
          {"seeds", {options.first_seed, options.last_seed}},
          {"episodes_per_seed", options.episodes},
          {"success_rate", mean_std(success)},
          {"q", mean_std(q)},
          {"episode_length", mean_std(length)},
          {"failed_primitives", failures},
          {"episodes_ended_by",
           {{"success", successes},
            {"policy_failure", policy_failures},
            {"time_limit", time_limits},
            {"diverged", diverged}}},
          {"per_seed", per_seed},
          {"per_episode", per_episode},
          {"env_steps", env_steps},
          {"wall_seconds", seconds},
          {"threads", options.threads}};
}

std::string format_evaluation(const nlohmann::json& r) {
  char line[512];
  std::string out;
  const auto ms = [&](const char* key) { return std::pair{r[key]["mean"].get<double>(), r[key]["std"].get<double>()}; };
  const std::string mode = r["mode"].get<std::string>();
  std::snprintf(line, sizeof line, "%s: %s, %s action space%s, seeds %llu-%llu x %d episodes\n",
                r["policy"].get<std::string>().c_str(), r["activity"].get<std::string>().c_str(),
                r["action_space"].get<std::string>().c_str(), mode.empty() ? "" : (" (" + mode + ")").c_str(),
                static_cast<unsigned long long>(r["seeds"][0].get<uint64_t>()),
                static_cast<unsigned long long>(r["seeds"][1].get<uint64_t>()), r["episodes_per_seed"].get<int>());
  out += line;
  const auto [s, s_std] = ms("success_rate");
  const auto [q, q_std] = ms("q");
  const auto [l, l_std] = ms("episode_length");
  std::snprintf(line, sizeof line,
                "  success rate     %5.1f%% +- %.1f%%  (mean +- std over seeds)\n"
                "  Q                %6.3f +- %.3f\n"
                "  episode length   %6.1f +- %.1f steps\n",
                100 * s, 100 * s_std, q, q_std, l, l_std);
  out += line;
  out += "  failed primitives:";
  for (const auto& [name, count] : r["failed_primitives"].items())
    out += " " + name + " " + std::to_string(count.get<int>());
  const nlohmann::json& ended = r["episodes_ended_by"];
  std::snprintf(line, sizeof line,
                "\n  episodes ended by: success %d, policy failure %d, time limit %d, divergence %d\n"
                "  %lld env steps in %.1f s (%d threads)\n",
                ended["success"].get<int>(), ended["policy_failure"].get<int>(), ended["time_limit"].get<int>(),
                ended["diverged"].get<int>(), static_cast<long long>(r["env_steps"].get<int64_t>()),
                r["wall_seconds"].get<double>(), r["threads"].get<int>());
  out += line;
  return out;
}

}  // namespace chore
