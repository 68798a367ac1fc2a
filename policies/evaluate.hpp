// Evaluation of a policy over seeds (`chore eval`) and where policies come
// from (the scripted expert, a plugin library; checkpoints from the trainers).
//
// "Seeds A-B with N episodes each": for every evaluation seed s in A..B, N
// episodes; episode j of seed s is the env reset with seed
// s * kEpisodeSeedStride + j. Seed s's first episodes are thus the same
// instances whatever N is, seeds never share an episode, and
// `chore expert --seed <s * 1000000> --episodes N` plays the same instances.
// Success rate, Q and episode length are averaged over each seed's episodes,
// then reported as mean and standard deviation over the seeds (population
// std, numpy's default: 0 for one seed). Episodes run on a VectorEnv of
// `threads` envs; results do not depend on the thread count for a policy
// whose action for a row depends only on that row (and the env's state).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <ostream>
#include <string>

#include "env/env.hpp"
#include "env/vector_env.hpp"
#include "policies/policy.hpp"

namespace chore {

inline constexpr uint64_t kEpisodeSeedStride = 1000000;

// Makes the policy for the vector env it will act in (its spaces; the expert
// reads its envs' state).
using PolicyFactory = std::function<std::unique_ptr<Policy>(const VectorEnv&)>;

// A policy and the env it acts in, named for reports. A checkpoint makes one
// from load_policy(path): {path, loaded.env, a factory handing over loaded.policy}.
struct PolicySource {
  std::string label;
  EnvConfig env;
  PolicyFactory make;
};

// The scripted expert on an activity, primitive action space in `mode`, state
// observations only (it needs no pictures). `max_steps` primitive steps per episode.
PolicySource expert_source(const std::string& activity, ExecutionMode mode, int max_steps);
// A plugin's policy (policies/plugin.hpp) in the env `env`, told `options`.
PolicySource plugin_source(const std::string& library, const std::string& options, const EnvConfig& env);

struct EvalOptions {
  uint64_t first_seed = 0, last_seed = 0;
  int episodes = 10;  // per seed
  int threads = 1;
};

// Runs the episodes; progress goes to `log`. chore::Error for bad options.
nlohmann::json evaluate(const PolicySource& source, const EvalOptions& options, std::ostream& log);
// The human-readable report of one evaluate() result.
std::string format_evaluation(const nlohmann::json& result);

}  // namespace chore
