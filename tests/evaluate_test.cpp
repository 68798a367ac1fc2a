// Evaluation over seeds (policies/evaluate.hpp) and policy plugins
// (policies/plugin.hpp): results independent of threads, plugins load, act and
// fail with clear errors.
#include <gtest/gtest.h>

#include <sstream>

#include "policies/evaluate.hpp"
#include "policies/plugin.hpp"
#include "test_util.hpp"

namespace chore {
namespace {

EvalOptions seeds(uint64_t first, uint64_t last, int episodes, int threads) {
  EvalOptions o;
  o.first_seed = first;
  o.last_seed = last;
  o.episodes = episodes;
  o.threads = threads;
  return o;
}

TEST(Evaluate, ResultsDoNotDependOnTheThreadCount) {
  std::ostringstream log;
  const PolicySource expert = expert_source("collect_trash", ExecutionMode::symbolic, 60);
  const nlohmann::json one = evaluate(expert, seeds(4, 4, 3, 1), log);
  const nlohmann::json two = evaluate(expert, seeds(4, 4, 3, 2), log);
  EXPECT_EQ(one["per_episode"], two["per_episode"]);
  EXPECT_EQ(one["failed_primitives"], two["failed_primitives"]);
}

// Low-level control: 14 values per row; an idle policy never succeeds and
// every episode runs to the time limit.
class Idle : public Policy {
  void act(const Batch& batch, std::span<float> actions) override {
    EXPECT_EQ(actions.size(), batch.size() * static_cast<size_t>(kLowLevelActionSize));
    std::fill(actions.begin(), actions.end(), 0.f);
  }
};

TEST(Evaluate, LowLevelEpisodesRunToTheTimeLimit) {
  EnvConfig env;
  env.activity = "collect_trash";
  env.observations = {"proprio"};
  env.max_episode_steps = 5;
  std::ostringstream log;
  const nlohmann::json r =
      evaluate({"idle", env, [](const VectorEnv&) { return std::make_unique<Idle>(); }}, seeds(0, 1, 3, 2), log);
  EXPECT_EQ(r["env_steps"].get<int>(), 2 * 3 * 5);
  EXPECT_EQ(r["episodes_ended_by"]["time_limit"].get<int>(), 6);
  EXPECT_EQ(r["success_rate"]["mean"].get<double>(), 0.0);
  EXPECT_EQ(r["episode_length"]["mean"].get<double>(), 5.0);
  EXPECT_EQ(r["mode"], "");
}

TEST(Evaluate, BadOptionsAreErrors) {
  std::ostringstream log;
  const PolicySource expert = expert_source("store_decoration", ExecutionMode::symbolic, 60);
  EXPECT_EQ(test::error_of([&] { evaluate(expert, seeds(0, 0, 0, 1), log); }), "eval: --episodes must be at least 1");
  EXPECT_EQ(test::error_of([&] { evaluate(expert, seeds(2, 1, 1, 1), log); }), "eval: --seeds A-B needs A <= B");
}

EnvConfig plugin_env(const std::string& action_space) {
  EnvConfig env;
  env.activity = "store_decoration";
  env.action_space = action_space;
  env.primitive_mode = ExecutionMode::symbolic;
  env.observations = {"is_grasping"};
  if (action_space == "primitives") env.observations.push_back("action_mask");
  env.max_episode_steps = 8;
  return env;
}

TEST(PolicyPlugin, TheMaskedRandomExampleNeverPicksAnInvalidAction) {
  std::ostringstream log;
  const nlohmann::json r =
      evaluate(plugin_source(CHORE_MASKED_RANDOM_PLUGIN, "seed=5", plugin_env("primitives")), seeds(0, 0, 2, 2), log);
  EXPECT_EQ(r["env_steps"].get<int>(), 16);  // two episodes of 8 steps: truncated, never a policy failure
  EXPECT_EQ(r["failed_primitives"]["precondition_failure"].get<int>(), 0);
  EXPECT_EQ(r["episodes_ended_by"]["policy_failure"].get<int>(), 0);
}

TEST(PolicyPlugin, BadPluginsAreClearErrors) {
  const EnvConfig env = plugin_env("primitives");
  VectorEnvConfig vc;
  vc.env = env;
  const VectorEnv envs(vc);
  const PolicySpec spec{&envs.single_observation_space(), &envs.single_action_space(), ""};
  EXPECT_EQ(test::error_of([&] { load_policy_plugin("/no/such/plugin.so", spec); }),
            "policy plugin '/no/such/plugin.so': no such file");
  const std::string text = (test::scratch_dir("plugins") / "not_a_library.so").string();
  test::write_file(text, "just text\n");
  EXPECT_NE(
      test::error_of([&] { load_policy_plugin(text, spec); }).find("policy plugin '" + text + "': cannot load it: "),
      std::string::npos);
  EXPECT_NE(test::error_of([&] {
              load_policy_plugin(CHORE_NO_ENTRY_POINTS_PLUGIN, spec);
            }).find("it does not export chore_create_policy"),
            std::string::npos);
  // Built against another API version (or before versions existed): refused, saying so.
  EXPECT_EQ(test::error_of([&] { load_policy_plugin(CHORE_NEXT_API_VERSION_PLUGIN, spec); }),
            std::string("policy plugin '") + CHORE_NEXT_API_VERSION_PLUGIN +
                "': built against chore's policy API version " + std::to_string(CHORE_POLICY_API_VERSION + 1) +
                ", this chore has version " + std::to_string(CHORE_POLICY_API_VERSION) +
                ": rebuild it against this chore's headers");
  EXPECT_NE(test::error_of([&] {
              load_policy_plugin(CHORE_UNVERSIONED_API_PLUGIN, spec);
            }).find("built against chore's policy API version 1, this chore has version"),
            std::string::npos);
  const PolicySpec bad_options{spec.observation_space, spec.action_space, "seed=x"};
  EXPECT_EQ(test::error_of([&] { load_policy_plugin(CHORE_MASKED_RANDOM_PLUGIN, bad_options); }),
            std::string("policy plugin '") + CHORE_MASKED_RANDOM_PLUGIN +
                "': the factory refused: masked_random: seed=N needs a number, got 'seed=x'");
  vc.env = plugin_env("low_level");
  const VectorEnv low_level(vc);
  const PolicySpec continuous{&low_level.single_observation_space(), &low_level.single_action_space(), ""};
  EXPECT_NE(test::error_of([&] {
              load_policy_plugin(CHORE_MASKED_RANDOM_PLUGIN, continuous);
            }).find("the factory refused: masked_random needs a Discrete action space"),
            std::string::npos);
}

}  // namespace
}  // namespace chore
