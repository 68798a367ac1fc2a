// The `chore` command line: bench, activity check/sample, expert; train, eval and
// video join as their layers land. Bad arguments and bad input files
// exit with status 2 and a message naming what is wrong.
#include <CLI/CLI.hpp>

#include <iostream>
#include <string>

#include "env/world/error.hpp"
#include "training/activity_commands.hpp"
#include "training/bench.hpp"
#include "training/expert_command.hpp"
#include "training/train_command.hpp"

int main(int argc, char** argv) {
  CLI::App app{"chore: BEHAVIOR-style household activities as fast RL environments"};
  app.require_subcommand(1);

  chore::BenchOptions bench;
  bool bench_json = false;
  CLI::App* bench_cmd = app.add_subcommand("bench", "Idle benchmark (seed Table A.10 protocol)");
  bench_cmd->add_option("--scenes", bench.scenes, "Scenes to benchmark")->capture_default_str();
  bench_cmd->add_option("--steps", bench.steps, "Steps per repetition")->check(CLI::PositiveNumber)->capture_default_str();
  bench_cmd->add_option("--repeats", bench.repeats, "Repetitions (median reported)")->check(CLI::PositiveNumber)->capture_default_str();
  bench_cmd->add_option("--width", bench.width, "Image width")->check(CLI::Range(1, 4096))->capture_default_str();
  bench_cmd->add_option("--height", bench.height, "Image height")->check(CLI::Range(1, 4096))->capture_default_str();
  bench_cmd->add_option("--envs", bench.vector_envs, "Envs of the vector-env rows")->check(CLI::Range(2, 256))->capture_default_str();
  bench_cmd->add_option("--primitive-episodes", bench.primitive_episodes,
                        "Expert episodes per activity and mode for the primitive rows (0: none)")
      ->check(CLI::NonNegativeNumber)->capture_default_str();
  bench_cmd->add_flag("--json", bench_json, "Print the results as JSON");

  CLI::App* activity_cmd = app.add_subcommand("activity", "BDDL activities");
  activity_cmd->require_subcommand(1);
  std::vector<std::string> check_files;
  CLI::App* check_cmd = activity_cmd->add_subcommand("check", "Parse and ground BDDL files");
  check_cmd->add_option("files", check_files, "BDDL problem files")->required()->check(CLI::ExistingFile);
  std::string sample_name, sample_scene, sample_out;
  uint64_t sample_seed = 0;
  CLI::App* sample_cmd = activity_cmd->add_subcommand("sample", "Instantiate an activity and picture it");
  sample_cmd->add_option("name", sample_name, "Activity name or .bddl path")->required();
  sample_cmd->add_option("--scene", sample_scene, "Scene (default: the activity's)");
  sample_cmd->add_option("--seed", sample_seed, "Seed")->capture_default_str();
  std::string sample_seeds;
  auto* out_option = sample_cmd->add_option("--out", sample_out, "PNG to write");
  sample_cmd->add_option("--seeds", sample_seeds, "A range A-B: instantiate each, no picture")
      ->excludes(out_option);

  chore::ExpertOptions expert;
  std::string expert_mode = "physical";
  bool expert_json = false;
  CLI::App* expert_cmd = app.add_subcommand("expert", "Run the scripted expert on an activity (primitive actions)");
  expert_cmd->add_option("--activity", expert.activity, "Activity name or .bddl path")->required();
  expert_cmd->add_option("--episodes", expert.episodes, "Episodes")->check(CLI::PositiveNumber)->capture_default_str();
  expert_cmd->add_option("--seed", expert.seed, "Seed of the first episode (episode i: seed + i)")->capture_default_str();
  expert_cmd->add_option("--mode", expert_mode, "Primitive execution: physical or symbolic")
      ->check(CLI::IsMember({"physical", "symbolic"}))->capture_default_str();
  expert_cmd->add_option("--max-steps", expert.max_steps, "Primitive steps per episode")->check(CLI::PositiveNumber)->capture_default_str();
  expert_cmd->add_option("--threads", expert.threads, "Episodes in parallel")->check(CLI::Range(1, 64))->capture_default_str();
  expert_cmd->add_flag("--json", expert_json, "Print the results as JSON");

  chore::TrainOptions train;
  int64_t train_steps = 0;
  CLI::App* train_cmd = app.add_subcommand("train", "Train a baseline (SAC rl-vmc, PPO rl-prim / rl-prim-hist) on an activity");
  train_cmd->add_option("--activity", train.activity, "Activity name or .bddl path");
  train_cmd->add_option("--baseline", train.baseline, "rl-vmc, rl-prim or rl-prim-hist")
      ->check(CLI::IsMember({"rl-vmc", "rl-prim", "rl-prim-hist"}));
  train_cmd->add_option("--seed", train.seed, "Seed (env i of the vector env: seed + i)")->capture_default_str();
  auto* train_steps_option = train_cmd->add_option("--steps", train_steps, "Total env steps (default 30000, or the resumed run's)")
      ->check(CLI::PositiveNumber);
  train_cmd->add_option("--envs", train.envs, "Envs of the vector env")->check(CLI::Range(1, 256))->capture_default_str();
  train_cmd->add_option("--threads", train.threads, "Env worker and torch threads")->check(CLI::Range(1, 64))->capture_default_str();
  train_cmd->add_option("--out", train.out, "Run folder: metrics.csv, checkpoint.pt, checkpoint_STEPS.pt");
  train_cmd->add_option("--resume", train.resume, "Continue the run in this folder from its checkpoint.pt");
  train_cmd->add_option("--mode", train.mode, "Primitive execution: physical (the paper's) or symbolic")
      ->check(CLI::IsMember({"physical", "symbolic"}))->capture_default_str();
  train_cmd->add_option("--observations", train.observations, "Observed fields (default: the baseline's), e.g. rgb is_grasping");
  train_cmd->add_option("--episode-steps", train.episode_steps, "Steps per episode (default: 60 primitives, 500 low-level)")
      ->check(CLI::PositiveNumber);
  train_cmd->add_option("--history", train.history, "rl-prim-hist: past steps the policy sees (default 4)")
      ->check(CLI::Range(1, 64));
  train_cmd->add_option("--checkpoint-every", train.checkpoint_every, "Env steps between checkpoints")
      ->check(CLI::PositiveNumber)->capture_default_str();

  // CLI11 would only say "a subcommand is required": name the unknown one.
  if (argc > 1 && argv[1][0] != '-') {
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      known += (known.empty() ? "" : ", ") + sub->get_name();
      found |= sub->get_name() == argv[1];
    }
    if (!found) {
      std::cerr << "chore: error: unknown subcommand '" << argv[1] << "' (known: " << known
                << ")" << std::endl;
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }

  try {
    if (*check_cmd) chore::check_activities(check_files, std::cout);
    if (*sample_cmd && !sample_seeds.empty()) {
      const auto dash = sample_seeds.find('-');
      uint64_t first = 0, last = 0;
      try {
        if (dash == std::string::npos) throw std::invalid_argument(sample_seeds);
        first = std::stoull(sample_seeds.substr(0, dash));
        last = std::stoull(sample_seeds.substr(dash + 1));
      } catch (const std::exception&) {
        throw chore::Error("--seeds '" + sample_seeds + "': expected a range A-B");
      }
      if (last < first) throw chore::Error("--seeds '" + sample_seeds + "': B is below A");
      chore::sample_activity_seeds(sample_name, sample_scene, first, last, std::cout);
    } else if (*sample_cmd) {
      if (sample_out.empty()) throw chore::Error("activity sample: give --out FILE.png or --seeds A-B");
      chore::sample_activity(sample_name, sample_scene, sample_seed, sample_out, std::cout);
    }
    if (*expert_cmd) {
      expert.mode = chore::parse_execution_mode(expert_mode);
      const nlohmann::json results = chore::run_expert(expert, std::cerr);
      std::cout << (expert_json ? results.dump(2) + "\n" : chore::format_expert(results));
    }
    if (*train_cmd) {
      if (*train_steps_option) train.steps = train_steps;
      chore::run_train(train, std::cerr);
    }
    if (*bench_cmd) {
      const nlohmann::json results = chore::run_bench(bench, std::cerr);
      if (bench_json) {
        std::cout << results.dump(2) << std::endl;
      } else {
        std::cout << chore::format_bench(results);
      }
    }
  } catch (const chore::Error& e) {
    std::cerr << "chore: error: " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "chore: internal error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
