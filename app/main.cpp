// The `chore` command line: bench, activity check/sample, expert, eval, video, observe, plot,
// reproduce; train joins with the trainers. Bad arguments and bad input files
// exit with status 2 and a message naming what is wrong.
#include <malloc.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>
#include <regex>
#include <string>
#include <tuple>

#include "app/activity_commands.hpp"
#include "app/bench.hpp"
#include "app/cli_numbers.hpp"
#include "app/expert_command.hpp"
#include "app/observe_command.hpp"
#include "app/plot.hpp"
#include "app/reproduce.hpp"
#include "app/train_command.hpp"
#include "app/video.hpp"
#include "base/error.hpp"
#include "base/random.hpp"
#include "policies/evaluate.hpp"
#include "training/checkpoint.hpp"
#include "training/trainer.hpp"

namespace {

// "A-B" (or "A") as a seed range, each seed in [0, kMaxSeed].
std::pair<uint64_t, uint64_t> seed_range(const std::string& text, const std::string& option) {
  std::smatch m;
  uint64_t first = 0, last = 0;
  const std::string expected =
      "': expected a seed or a range A-B of seeds in [0, " + std::to_string(chore::kMaxSeed) + "]";
  try {
    if (!std::regex_match(text, m, std::regex(R"((\d{1,13})(?:-(\d{1,13}))?)"))) throw std::invalid_argument(text);
    first = std::stoull(m[1]);
    last = m[2].matched ? std::stoull(m[2]) : first;
  } catch (const std::exception&) {
    throw chore::Error(option + " '" + text + expected);
  }
  if (first > chore::kMaxSeed || last > chore::kMaxSeed) throw chore::Error(option + " '" + text + expected);
  if (last < first) throw chore::Error(option + " '" + text + "': B is below A");
  return {first, last};
}

// Where eval and video get their policy and its env.
struct PolicyArgs {
  std::vector<std::string> checkpoints;
  std::string activity, plugin, plugin_options, action_space = "primitives", mode;
  std::vector<std::string> observations;
  int max_steps = 0;
  bool expert = false;
  bool sample = false;  // checkpoints: act by sampling, not greedily
};

void add_policy_options(CLI::App* cmd, PolicyArgs& a) {
  auto* checkpoint =
      cmd->add_option("--checkpoint", a.checkpoints, "Checkpoint(s) of chore train (their env, greedy policy)");
  auto* plugin = cmd->add_option("--policy-plugin", a.plugin, "Shared library defining a policy (CHORE_POLICY_PLUGIN)");
  auto* expert = cmd->add_flag("--expert", a.expert, "The scripted expert (primitive action space)");
  plugin->excludes(expert);
  checkpoint->excludes(plugin)->excludes(expert);
  cmd->add_flag("--sample", a.sample, "Checkpoints: sample actions from the policy's distribution (default: greedy)")
      ->needs(checkpoint);
  cmd->add_option("--policy-options", a.plugin_options, "Text handed to the plugin's factory")->needs(plugin);
  cmd->add_option("--activity", a.activity, "Activity name or .bddl path (a checkpoint's own by default)");
  cmd->add_option("--action-space", a.action_space, "primitives or low_level (plugins)")
      ->check(CLI::IsMember({"primitives", "low_level"}))
      ->needs(plugin)
      ->capture_default_str();
  cmd->add_option("--observations", a.observations,
                  "Observations a plugin sees (default: rgb, depth, proprio, is_grasping, and action_mask for "
                  "primitives)")
      ->delimiter(',')
      ->needs(plugin);
  cmd->add_option("--mode", a.mode,
                  "Primitive execution: physical or symbolic (default: a checkpoint's own, else physical)")
      ->check(CLI::IsMember({"physical", "symbolic"}));
  cmd->add_option("--max-steps", a.max_steps, "Steps per episode (default: 60 primitive, 500 low-level)")
      ->check(chore::integer_in(1, 1000000));
}

std::vector<chore::PolicySource> policy_sources(const PolicyArgs& a, const std::string& command) {
  if (!a.checkpoints.empty()) {
    // Each checkpoint brings its env; --activity, --mode and --max-steps override it.
    chore::set_policy_threads(1);
    std::vector<chore::PolicySource> sources;
    for (const std::string& path : a.checkpoints) {
      auto loaded = std::make_shared<chore::LoadedPolicy>(chore::load_policy(path, a.sample));
      chore::EnvConfig env = loaded->env;
      if (!a.activity.empty()) env.activity = a.activity;
      if (!a.mode.empty()) env.primitive_mode = chore::parse_execution_mode(a.mode);
      if (a.max_steps > 0) env.max_episode_steps = a.max_steps;
      sources.push_back({path, env, [loaded, path](const chore::VectorEnv&) {
                           if (!loaded->policy) throw chore::Error(path + ": its policy is already in use");
                           return std::move(loaded->policy);
                         }});
    }
    return sources;
  }
  if (a.activity.empty()) throw chore::Error(command + ": --activity is required");
  const chore::ExecutionMode mode = chore::parse_execution_mode(a.mode.empty() ? "physical" : a.mode);
  const bool primitives = a.expert || a.action_space == "primitives";
  const int max_steps = a.max_steps > 0 ? a.max_steps : primitives ? 60 : 500;
  if (a.expert) return {chore::expert_source(a.activity, mode, max_steps)};
  if (a.plugin.empty())
    throw chore::Error(command + ": give the policy: --checkpoint PATH, --policy-plugin LIB.so or --expert");
  chore::EnvConfig env;
  env.activity = a.activity;
  env.action_space = a.action_space;
  env.primitive_mode = mode;
  env.max_episode_steps = max_steps;
  if (!a.observations.empty()) {
    env.observations = a.observations;
  } else if (primitives) {
    env.observations.push_back("action_mask");
  }
  return {chore::plugin_source(a.plugin, a.plugin_options, env)};
}

}  // namespace

int main(int argc, char** argv) {
  // glibc hands large freed blocks (image batches, tensors) back to the kernel
  // and maps them again at the next use; each new page is a fault, and faults
  // are dear on a VM: a StoreDecoration PPO minibatch update took 143-160 ms,
  // 33-40 ms with the memory kept (docs/benchmarks.md#training). Keep it.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, 64 << 20);
  CLI::App app{"chore: BEHAVIOR-style household activities as fast RL environments"};
  app.require_subcommand(1);

  chore::BenchOptions bench;
  bool bench_json = false;
  CLI::App* bench_cmd = app.add_subcommand("bench", "Idle benchmark (seed Table A.10 protocol)");
  bench_cmd->add_option("--scenes", bench.scenes, "Scenes to benchmark")->capture_default_str();
  bench_cmd->add_option("--steps", bench.steps, "Steps per repetition")
      ->check(chore::integer_in(1, 1000000000))
      ->capture_default_str();
  bench_cmd->add_option("--repeats", bench.repeats, "Repetitions (median reported)")
      ->check(chore::integer_in(1, 1000))
      ->capture_default_str();
  bench_cmd->add_option("--width", bench.width, "Image width")
      ->check(chore::integer_in(1, 4096))
      ->capture_default_str();
  bench_cmd->add_option("--height", bench.height, "Image height")
      ->check(chore::integer_in(1, 4096))
      ->capture_default_str();
  bench_cmd->add_option("--envs", bench.vector_envs, "Envs of the vector-env rows")
      ->check(chore::integer_in(2, 256))
      ->capture_default_str();
  bench_cmd
      ->add_option("--primitive-episodes", bench.primitive_episodes,
                   "Expert episodes per activity and mode for the primitive rows (0: none)")
      ->check(chore::integer_in(0, 1000000))
      ->capture_default_str();
  bench_cmd
      ->add_option("--sections", bench.sections,
                   "What to run: table (Table A.10), vector (VectorEnv), primitives, modalities "
                   "(ms per frame of each observation, first scene), memory (MB per env of a vector env)")
      ->check(CLI::IsMember({"table", "vector", "primitives", "modalities", "memory"}))
      ->capture_default_str();
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
  sample_cmd->add_option("--seed", sample_seed, "Seed")->check(chore::seed_number())->capture_default_str();
  std::string sample_seeds;
  auto* out_option = sample_cmd->add_option("--out", sample_out, "PNG to write");
  sample_cmd->add_option("--seeds", sample_seeds, "A range A-B: instantiate each, no picture")->excludes(out_option);

  chore::ExpertOptions expert;
  std::string expert_mode = "physical";
  bool expert_json = false;
  CLI::App* expert_cmd = app.add_subcommand("expert", "Run the scripted expert on an activity (primitive actions)");
  expert_cmd->add_option("--activity", expert.activity, "Activity name or .bddl path")->required();
  expert_cmd->add_option("--episodes", expert.episodes, "Episodes")
      ->check(chore::integer_in(1, 1000000))
      ->capture_default_str();
  expert_cmd->add_option("--seed", expert.seed, "Seed of the first episode (episode i: seed + i)")
      ->check(chore::seed_number())
      ->capture_default_str();
  expert_cmd->add_option("--mode", expert_mode, "Primitive execution: physical or symbolic")
      ->check(CLI::IsMember({"physical", "symbolic"}))
      ->capture_default_str();
  expert_cmd->add_option("--max-steps", expert.max_steps, "Primitive steps per episode")
      ->check(chore::integer_in(1, 1000000))
      ->capture_default_str();
  expert_cmd->add_option("--threads", expert.threads, "Episodes in parallel")
      ->check(chore::integer_in(1, 64))
      ->capture_default_str();
  expert_cmd->add_flag("--json", expert_json, "Print the results as JSON");

  chore::EvalOptions eval;
  PolicyArgs eval_policy;
  std::string eval_seeds = "0-0";
  bool eval_json = false;
  CLI::App* eval_cmd = app.add_subcommand("eval", "Evaluate a policy over seeds: success rate, Q, failures");
  add_policy_options(eval_cmd, eval_policy);
  eval_cmd->add_option("--seeds", eval_seeds, "Evaluation seeds A-B; episode j of seed s: env seed s*1000000+j")
      ->capture_default_str();
  eval_cmd->add_option("--episodes", eval.episodes, "Episodes per seed")
      ->check(chore::integer_in(1, 999999))
      ->capture_default_str();
  eval_cmd->add_option("--threads", eval.threads, "Envs run in parallel")
      ->check(chore::integer_in(1, 64))
      ->capture_default_str();
  eval_cmd->add_flag("--json", eval_json, "Print the results as JSON (per seed and episode too)");

  chore::VideoOptions video;
  PolicyArgs video_policy;
  CLI::App* video_cmd = app.add_subcommand("video", "Record an episode: robot camera and top-down view, to MP4");
  add_policy_options(video_cmd, video_policy);
  video_cmd->add_option("--seed", video.seed, "The episode's env seed")
      ->check(chore::seed_number())
      ->capture_default_str();
  video_cmd->add_option("--out", video.out, "MP4 file to write")->required();
  video_cmd->add_option("--size", video.size, "Pixels of each view")
      ->check(chore::integer_in(16, 2048))
      ->capture_default_str();
  video_cmd->add_option("--fps", video.fps, "Frames per second (default: 2 for primitives, 30 low-level)")
      ->check(chore::real_in(0.1, 240));

  chore::ObserveOptions observe;
  CLI::App* observe_cmd = app.add_subcommand("observe", "Every observation modality of one frame, as a PNG panel");
  observe_cmd->add_option("--activity", observe.activity, "Activity name or .bddl path (its scene)");
  observe_cmd->add_option("--scene", observe.scene, "Scene (default: the activity's, else the apartment)");
  observe_cmd->add_option("--seed", observe.seed, "The episode's env seed")
      ->check(chore::seed_number())
      ->capture_default_str();
  observe_cmd->add_option("--size", observe.size, "Pixels of each tile")
      ->check(chore::integer_in(32, 2048))
      ->capture_default_str();
  observe_cmd->add_option("--steps", observe.steps, "Steps of motion before the frame (flow shows the last)")
      ->check(chore::integer_in(1, 100000))
      ->capture_default_str();
  observe_cmd->add_option("--out", observe.out, "PNG to write")->required();

  chore::PlotOptions plot;
  CLI::App* plot_cmd = app.add_subcommand("plot", "Learning curves from metrics.csv files to PNG");
  plot_cmd
      ->add_option("runs", plot.runs,
                   "metrics.csv files, each optionally LABEL=path (default label: "
                   "the run directory less a _seedN suffix)")
      ->required();
  plot_cmd->add_option("--out", plot.out, "PNG to write")->required();
  plot_cmd->add_option("--x", plot.x, "Column for the x axis")->capture_default_str();
  plot_cmd->add_option("--y", plot.y, "Column for the y axis (success_rate, mean_q, mean_return, ...)")
      ->capture_default_str();
  plot_cmd->add_option("--title", plot.title, "Title (default: Y over X)");
  plot_cmd->add_option("--width", plot.width, "Picture width")
      ->check(chore::integer_in(320, 4096))
      ->capture_default_str();
  plot_cmd->add_option("--height", plot.height, "Picture height")
      ->check(chore::integer_in(240, 4096))
      ->capture_default_str();

  // The baselines' registry (training/trainer.cpp): "rl-vmc (sac), rl-prim (ppo), ...".
  std::vector<std::string> baseline_names;
  std::string baselines_trained_by;
  for (const chore::Baseline& b : chore::baselines()) {
    baseline_names.push_back(b.name);
    baselines_trained_by += (baselines_trained_by.empty() ? "" : ", ") + b.name + " (" + b.algorithm + ")";
  }
  chore::TrainOptions train;
  int64_t train_steps = 0;
  CLI::App* train_cmd = app.add_subcommand("train", "Train a baseline on an activity: " + baselines_trained_by);
  train_cmd->add_option("--activity", train.activity, "Activity name or .bddl path");
  train_cmd->add_option("--baseline", train.baseline, "The baseline")->check(CLI::IsMember(baseline_names));
  train_cmd->add_option("--seed", train.seed, "Seed (env i of the vector env: seed + i)")
      ->check(chore::seed_number())
      ->capture_default_str();
  auto* train_steps_option =
      train_cmd->add_option("--steps", train_steps, "Total env steps (default 30000, or the resumed run's)")
          ->check(chore::integer_in(1, 10000000000));
  train_cmd->add_option("--envs", train.envs, "Envs of the vector env")
      ->check(chore::integer_in(1, 256))
      ->capture_default_str();
  train_cmd->add_option("--threads", train.threads, "Env worker and torch threads")
      ->check(chore::integer_in(1, 64))
      ->capture_default_str();
  train_cmd->add_option("--out", train.out, "Run folder: metrics.csv, checkpoint.pt, checkpoint_STEPS.pt");
  train_cmd->add_option("--resume", train.resume, "Continue the run in this folder from its checkpoint.pt");
  train_cmd->add_option("--mode", train.mode, "Primitive execution: physical (the paper's) or symbolic")
      ->check(CLI::IsMember({"physical", "symbolic"}))
      ->capture_default_str();
  train_cmd->add_option("--observations", train.observations,
                        "Observed fields (default: the baseline's), e.g. rgb is_grasping");
  train_cmd
      ->add_option("--episode-steps", train.episode_steps, "Steps per episode (default: 60 primitives, 500 low-level)")
      ->check(chore::integer_in(1, 1000000));
  train_cmd->add_option("--history", train.history, "rl-prim-hist: past steps the policy sees (default 4)")
      ->check(chore::integer_in(1, 64));
  train_cmd
      ->add_option("--checkpoint-every", train.checkpoint_every,
                   "Env steps between checkpoints (default 3000, or the resumed run's)")
      ->check(chore::integer_in(1, 10000000000));
  train_cmd->add_option(
      "--set", train.settings,
      "KEY=VALUE: a config field of the new run, as named in the run folder's config.json, e.g. ppo.entropy_coef=0.01");

  chore::ReproduceOptions reproduce;
  std::string generalisation_seeds = "100-119";
  CLI::App* reproduce_cmd = app.add_subcommand(
      "reproduce", "The paper's baseline table (A.13) through train and eval: resumable, to OUT/baselines.{json,md}");
  reproduce_cmd->add_option("--activities", reproduce.activities, "Activities")->capture_default_str();
  reproduce_cmd->add_option("--methods", reproduce.methods, "Methods (baselines)")
      ->check(CLI::IsMember(baseline_names))
      ->capture_default_str();
  reproduce_cmd->add_option("--seeds", reproduce.seeds, "Training seeds")
      ->check(chore::seed_number())
      ->capture_default_str();
  reproduce_cmd->add_option("--steps", reproduce.steps, "Training env steps per run")
      ->check(chore::integer_in(1, 10000000000))
      ->capture_default_str();
  reproduce_cmd->add_option("--mode", reproduce.mode, "Primitive execution: physical (the paper's) or symbolic")
      ->check(CLI::IsMember({"physical", "symbolic"}))
      ->capture_default_str();
  reproduce_cmd->add_option("--jobs", reproduce.jobs, "Runs at once (one core each)")
      ->check(chore::integer_in(1, 64))
      ->capture_default_str();
  reproduce_cmd->add_option("--eval-episodes", reproduce.eval_episodes, "Episodes at evaluation seed 0")
      ->check(chore::integer_in(1, 999999))
      ->capture_default_str();
  reproduce_cmd
      ->add_option("--generalisation-seeds", generalisation_seeds, "Seeds A-B of fresh instances, one episode each")
      ->capture_default_str();
  reproduce_cmd->add_option("--out", reproduce.out, "Results folder (runs/ inside)")->capture_default_str();
  reproduce_cmd->add_flag("!--no-videos", reproduce.videos, "Skip the best policies' videos");
  reproduce_cmd->add_flag("--report-only", reproduce.report_only, "Train and evaluate nothing: report the runs done");
  reproduce_cmd->add_option(
      "--set", reproduce.settings,
      "KEY=VALUE for every new run's chore train --set (ppo.* for the PPO methods, sac.* for SAC)");

  // CLI11 would only say "a subcommand is required": name the unknown one.
  if (argc > 1 && argv[1][0] != '-') {
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      known += (known.empty() ? "" : ", ") + sub->get_name();
      found |= sub->get_name() == argv[1];
    }
    if (!found) {
      std::cerr << "chore: error: unknown subcommand '" << argv[1] << "' (known: " << known << ")" << std::endl;
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
      const auto [first, last] = seed_range(sample_seeds, "--seeds");
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
    if (*eval_cmd) {
      std::tie(eval.first_seed, eval.last_seed) = seed_range(eval_seeds, "--seeds");
      nlohmann::json results = nlohmann::json::array();
      for (const chore::PolicySource& source : policy_sources(eval_policy, "eval")) {
        results.push_back(chore::evaluate(source, eval, std::cerr));
        if (!eval_json) std::cout << chore::format_evaluation(results.back());
      }
      if (eval_json) std::cout << results.dump(2) << std::endl;
    }
    if (*video_cmd) {
      const std::vector<chore::PolicySource> sources = policy_sources(video_policy, "video");
      const nlohmann::json r = chore::record_video(sources.front(), video, std::cerr);
      std::cout << "video: " << r["out"].get<std::string>() << ", " << r["frames"] << " frames of " << r["width"] << "x"
                << r["height"] << " at " << r["fps"] << " fps (" << r["codec"].get<std::string>() << "); " << r["steps"]
                << " steps, " << (r["success"].get<bool>() ? "success" : "no success") << ", Q " << r["q"] << "\n";
    }
    if (*observe_cmd) {
      const nlohmann::json r = chore::observe_panel(observe);
      std::cout << "observe: " << r["out"].get<std::string>() << " (" << r["scene"].get<std::string>()
                << "): " << r["instances"] << " instances of " << r["classes"].size() << " classes in view, depth to "
                << r["max_depth_m"] << " m, flow up to " << r["max_flow_px"] << " px\n";
    }
    if (*plot_cmd) {
      const nlohmann::json r = chore::plot_curves(plot);
      std::cout << "plot: " << plot.out << ":";
      for (const auto& g : r["groups"]) {
        std::cout << " " << g["label"].get<std::string>() << " (" << g["runs"] << (g["runs"] == 1 ? " run)" : " runs)");
      }
      std::cout << "\n";
    }
    if (*train_cmd) {
      if (*train_steps_option) train.steps = train_steps;
      chore::run_train(train, std::cerr);
    }
    if (*reproduce_cmd) {
      std::tie(reproduce.generalisation_first, reproduce.generalisation_last) =
          seed_range(generalisation_seeds, "--generalisation-seeds");
      reproduce.command_line = "scripts/reproduce";
      for (int i = 2; i < argc; ++i) reproduce.command_line += std::string(" ") + argv[i];
      const nlohmann::json r = chore::reproduce(reproduce, std::cerr);
      if (!r["failures"].empty()) {
        std::cerr << "chore: " << r["failures"].size() << " run(s) failed; the rest are reported" << std::endl;
        return 1;
      }
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
  } catch (const std::filesystem::filesystem_error& e) {
    // A path given on the command line or in a file: bad input, not a fault.
    std::cerr << "chore: error: " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "chore: internal error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}
