#include "app/command_line.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <ostream>
#include <string_view>
#include <tuple>

#include "app/cli_numbers.hpp"
#include "base/error.hpp"
#include "base/random.hpp"
#include "training/trainer.hpp"
#include "world/model_cache.hpp"

namespace chore {
namespace {

// A table's training seeds at most (each is a run of every cell).
constexpr uint64_t kMaxTableSeeds = 1000;
// Instances an activity is solved from at most (each a plan executed).
constexpr uint64_t kMaxSolveSeeds = 1000;

// "A-B" (or "A") as a seed range, each seed in [0, kMaxSeed].
std::pair<uint64_t, uint64_t> seed_range(const std::string& text, const std::string& option) {
  const std::string expected = "': expected a seed or a range A-B of seeds in [0, " + std::to_string(kMaxSeed) + "]";
  // Up to 13 digits each: kMaxSeed has 13, and nothing longer reaches stoull.
  const auto number = [&](std::string_view digits) {
    if (digits.empty() || digits.size() > 13 ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
      throw Error(option + " '" + text + expected);
    }
    return std::stoull(std::string(digits));
  };
  const size_t dash = text.find('-');
  const uint64_t first = number(std::string_view(text).substr(0, dash));
  const uint64_t last = dash == std::string::npos ? first : number(std::string_view(text).substr(dash + 1));
  if (first > kMaxSeed || last > kMaxSeed) throw Error(option + " '" + text + expected);
  if (last < first) throw Error(option + " '" + text + "': B is below A");
  return {first, last};
}

// Seeds and ranges A-B, in order, as a table's training seeds.
std::vector<uint64_t> table_seeds(const std::vector<std::string>& texts, const std::string& option) {
  std::vector<uint64_t> seeds;
  for (const std::string& text : texts) {
    const auto [first, last] = seed_range(text, option);
    if (last - first >= kMaxTableSeeds || seeds.size() + (last - first) >= kMaxTableSeeds)
      throw Error(option + ": at most " + std::to_string(kMaxTableSeeds) + " training seeds");
    for (uint64_t s = first; s <= last; ++s) seeds.push_back(s);
  }
  return seeds;
}

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
      ->check(integer_in(1, 1000000));
  cmd->add_option("--instances", a.instances,
                  "fixed: the activity's instance 0 at every reset; resample: drawn from each episode's seed "
                  "(default: a checkpoint's own, else resample)")
      ->check(CLI::IsMember({"fixed", "resample"}));
}

}  // namespace

// CLI11's app, built once: its options write into `values`, which each parse
// starts from afresh.
struct CommandLineParser::Impl {
  // What the options write to, with the defaults each parse starts from.
  struct Values {
    CommandLine c;
    std::string sample_seeds, expert_mode = "physical", eval_seeds = "0-0", generalisation_seeds = "100-119",
                              solve_mode = "symbolic", solve_seeds = "0";
    std::vector<std::string> reproduce_seeds = {"0", "1", "2"}, reproduce_seeds_for, compare_methods;
    int64_t reproduce_cell = -1;
    int64_t train_steps = 0;
    std::string model_cache = default_model_cache_dir();
  } values;
  CLI::App app{"chore: BEHAVIOR-style household activities as fast RL environments"};
  CLI::App *bench_cmd, *check_cmd, *sample_cmd, *coverage_cmd, *solve_cmd, *scene_list_cmd, *scene_build_cmd,
      *expert_cmd, *eval_cmd, *video_cmd, *observe_cmd, *plot_cmd, *train_cmd, *reproduce_cmd;
  CLI::Option* train_steps_option;

  Impl();
  ParsedCommandLine parse(int argc, const char* const* argv, std::ostream& out, std::ostream& err);
};

CommandLineParser::Impl::Impl() {
  CommandLine& c = values.c;
  app.require_subcommand(1);

  bench_cmd = app.add_subcommand("bench", "Idle benchmark (seed Table A.10 protocol)");
  bench_cmd->add_option("--scenes", c.bench.scenes, "Scenes to benchmark")->capture_default_str();
  bench_cmd->add_option("--steps", c.bench.steps, "Steps per repetition")
      ->check(integer_in(1, 1000000000))
      ->capture_default_str();
  bench_cmd->add_option("--repeats", c.bench.repeats, "Repetitions (median reported)")
      ->check(integer_in(1, 1000))
      ->capture_default_str();
  bench_cmd->add_option("--width", c.bench.width, "Image width")->check(integer_in(1, 4096))->capture_default_str();
  bench_cmd->add_option("--height", c.bench.height, "Image height")->check(integer_in(1, 4096))->capture_default_str();
  bench_cmd->add_option("--envs", c.bench.vector_envs, "Envs of the vector-env rows")
      ->check(integer_in(2, 256))
      ->capture_default_str();
  bench_cmd
      ->add_option("--primitive-episodes", c.bench.primitive_episodes,
                   "Expert episodes per activity and mode for the primitive rows (0: none)")
      ->check(integer_in(0, 1000000))
      ->capture_default_str();
  bench_cmd
      ->add_option("--sections", c.bench.sections,
                   "What to run: table (Table A.10), vector (VectorEnv), primitives, modalities "
                   "(ms per frame of each observation, first scene), memory (MB per env of a vector env)")
      ->check(CLI::IsMember({"table", "vector", "primitives", "modalities", "memory"}))
      ->capture_default_str();
  bench_cmd->add_flag("--json", c.json, "Print the results as JSON");

  CLI::App* activity_cmd = app.add_subcommand("activity", "BDDL activities");
  activity_cmd->require_subcommand(1);
  check_cmd = activity_cmd->add_subcommand("check", "Parse and ground BDDL files");
  check_cmd->add_option("files", c.check_files, "BDDL problem files")->required()->check(CLI::ExistingFile);
  sample_cmd = activity_cmd->add_subcommand("sample", "Instantiate an activity and picture it");
  sample_cmd->add_option("name", c.sample.name, "Activity name or .bddl path")->required();
  sample_cmd->add_option("--scene", c.sample.scene, "Scene (default: the activity's)");
  sample_cmd->add_option("--seed", c.sample.seed, "Seed")->check(seed_number())->capture_default_str();
  auto* out_option = sample_cmd->add_option("--out", c.sample.out, "PNG to write");
  coverage_cmd = activity_cmd->add_subcommand(
      "coverage", "Parse, ground and instantiate every .bddl file under a folder; failures grouped by cause");
  coverage_cmd->add_option("dir", c.coverage.dir, "Folder of BDDL files (searched recursively)")
      ->required()
      ->check(CLI::ExistingDirectory);
  coverage_cmd->add_option("--seed", c.coverage.seed, "Seed of each instance")
      ->check(seed_number())
      ->capture_default_str();
  coverage_cmd->add_option("--threads", c.coverage.threads, "Files at once")
      ->check(integer_in(1, 64))
      ->capture_default_str();
  coverage_cmd
      ->add_option("--steps", c.coverage.steps,
                   "Then run each in a VectorEnv for this many random low-level steps (0: not run)")
      ->check(integer_in(0, 100000))
      ->capture_default_str();
  coverage_cmd
      ->add_option("--primitive-steps", c.coverage.primitive_steps,
                   "Then this many random primitives of the primitive action space, executed physically (0: none)")
      ->check(integer_in(0, 100000))
      ->capture_default_str();
  coverage_cmd->add_flag("--goals-only", c.coverage.goals_only,
                         "Only parse, ground and judge which goal literals the primitives and transition rules could "
                         "make hold (no world, no instantiation)");
  coverage_cmd->add_option("--sheet", c.coverage.sheet,
                           "Contact sheet PNG: head camera and top-down view of every instantiated activity");
  coverage_cmd->add_flag("--json", c.json, "Print the results as JSON (per activity too)");
  solve_cmd = activity_cmd->add_subcommand(
      "solve",
      "Plan each activity over the primitives' symbolic models and execute the plan: solved when it ends at Q = 1");
  solve_cmd->add_option("path", c.coverage.dir, "A .bddl file, or a folder of them (searched recursively)")
      ->required()
      ->check(CLI::ExistingPath);
  solve_cmd->add_option("--mode", values.solve_mode, "Primitive execution of the plans: symbolic or physical")
      ->check(CLI::IsMember({"physical", "symbolic"}))
      ->capture_default_str();
  solve_cmd->add_option("--seeds", values.solve_seeds, "Seeds A-B (or A) of the instances: solved at every one")
      ->capture_default_str();
  solve_cmd->add_option("--threads", c.coverage.threads, "Files at once")
      ->check(integer_in(1, 64))
      ->capture_default_str();
  solve_cmd->add_option("--sheet", c.coverage.sheet,
                        "Contact sheet PNG: each solved activity's final state (head camera and top-down view)");
  solve_cmd->add_flag("--json", c.json, "Print the results as JSON (per activity too, with its plan)");
  CLI::App* scene_cmd = app.add_subcommand("scene", "BEHAVIOR-1K's scenes as analogs generated from their inventories");
  scene_cmd->require_subcommand(1);
  scene_list_cmd = scene_cmd->add_subcommand("list", "The scenes of the inventories: rooms and objects");
  scene_build_cmd = scene_cmd->add_subcommand("build", "Generate a scene's analog, compile it, draw it from above");
  scene_build_cmd->add_option("name", c.scene_build.name, "Scene (chore scene list)")->required();
  scene_build_cmd->add_option("--seed", c.scene_build.seed, "Seed of the layout")
      ->check(seed_number())
      ->capture_default_str();
  scene_build_cmd->add_option("--out", c.scene_build.out, "Top-down picture to write (.png)");
  scene_build_cmd->add_option("--cache", values.model_cache, "Folder compiled models are kept in (empty: none)")
      ->capture_default_str();
  scene_build_cmd->add_flag("--json", c.json, "Print the results as JSON");
  sample_cmd->add_option("--seeds", values.sample_seeds, "A range A-B: instantiate each, no picture")
      ->excludes(out_option);

  expert_cmd = app.add_subcommand("expert", "Run the scripted expert on an activity (primitive actions)");
  expert_cmd->add_option("--activity", c.expert.activity, "Activity name or .bddl path")->required();
  expert_cmd->add_option("--episodes", c.expert.episodes, "Episodes")
      ->check(integer_in(1, 1000000))
      ->capture_default_str();
  expert_cmd->add_option("--seed", c.expert.seed, "Seed of the first episode (episode i: seed + i)")
      ->check(seed_number())
      ->capture_default_str();
  expert_cmd->add_option("--mode", values.expert_mode, "Primitive execution: physical or symbolic")
      ->check(CLI::IsMember({"physical", "symbolic"}))
      ->capture_default_str();
  expert_cmd->add_option("--max-steps", c.expert.max_steps, "Primitive steps per episode")
      ->check(integer_in(1, 1000000))
      ->capture_default_str();
  expert_cmd->add_option("--threads", c.expert.threads, "Episodes in parallel")
      ->check(integer_in(1, 64))
      ->capture_default_str();
  expert_cmd->add_flag("--planner", c.expert.planner,
                       "The task planner's expert (plans over the primitives' symbolic models) also where the scripted "
                       "one knows the goal (the paper's three activities); elsewhere the planner acts without it");
  expert_cmd->add_flag("--json", c.json, "Print the results as JSON");

  eval_cmd = app.add_subcommand("eval", "Evaluate a policy over seeds: success rate, Q, failures");
  add_policy_options(eval_cmd, c.policy);
  eval_cmd->add_option("--seeds", values.eval_seeds, "Evaluation seeds A-B; episode j of seed s: env seed s*1000000+j")
      ->capture_default_str();
  eval_cmd->add_option("--episodes", c.eval.episodes, "Episodes per seed")
      ->check(integer_in(1, 999999))
      ->capture_default_str();
  eval_cmd->add_option("--threads", c.eval.threads, "Envs run in parallel")
      ->check(integer_in(1, 64))
      ->capture_default_str();
  eval_cmd->add_flag("--json", c.json, "Print the results as JSON (per seed and episode too)");

  video_cmd = app.add_subcommand("video", "Record an episode: robot camera and top-down view, to MP4");
  add_policy_options(video_cmd, c.policy);
  video_cmd->add_option("--seed", c.video.seed, "The episode's env seed")->check(seed_number())->capture_default_str();
  video_cmd->add_option("--out", c.video.out, "MP4 file to write")->required();
  video_cmd->add_option("--size", c.video.size, "Pixels of each view")
      ->check(integer_in(16, 2048))
      ->capture_default_str();
  video_cmd->add_option("--fps", c.video.fps, "Frames per second (default: 2 for primitives, 30 low-level)")
      ->check(real_in(0.1, 240));

  observe_cmd = app.add_subcommand("observe", "Every observation modality of one frame, as a PNG panel");
  observe_cmd->add_option("--activity", c.observe.activity, "Activity name or .bddl path (its scene)");
  observe_cmd->add_option("--scene", c.observe.scene, "Scene (default: the activity's, else the apartment)");
  observe_cmd->add_option("--seed", c.observe.seed, "The episode's env seed")
      ->check(seed_number())
      ->capture_default_str();
  observe_cmd->add_option("--size", c.observe.size, "Pixels of each tile")
      ->check(integer_in(32, 2048))
      ->capture_default_str();
  observe_cmd->add_option("--steps", c.observe.steps, "Steps of motion before the frame (flow shows the last)")
      ->check(integer_in(1, 100000))
      ->capture_default_str();
  observe_cmd->add_option("--out", c.observe.out, "PNG to write")->required();

  plot_cmd = app.add_subcommand("plot", "Learning curves from metrics.csv files to PNG");
  plot_cmd
      ->add_option("runs", c.plot.runs,
                   "metrics.csv files, each optionally LABEL=path (default label: "
                   "the run directory less a _seedN suffix)")
      ->required();
  plot_cmd->add_option("--out", c.plot.out, "PNG to write")->required();
  plot_cmd->add_option("--x", c.plot.x, "Column for the x axis")->capture_default_str();
  plot_cmd->add_option("--y", c.plot.y, "Column for the y axis (success_rate, mean_q, mean_return, ...)")
      ->capture_default_str();
  plot_cmd->add_option("--title", c.plot.title, "Title (default: Y over X)");
  plot_cmd->add_option("--width", c.plot.width, "Picture width")->check(integer_in(320, 4096))->capture_default_str();
  plot_cmd->add_option("--height", c.plot.height, "Picture height")
      ->check(integer_in(240, 4096))
      ->capture_default_str();

  // The baselines' registry (training/baselines.cpp): "rl-vmc (sac), rl-prim (ppo), ...".
  std::vector<std::string> baseline_names;
  std::string baselines_trained_by;
  for (const Baseline& b : baselines()) {
    baseline_names.push_back(b.name);
    baselines_trained_by += (baselines_trained_by.empty() ? "" : ", ") + b.name + " (" + b.algorithm + ")";
  }
  train_cmd = app.add_subcommand("train", "Train a baseline on an activity: " + baselines_trained_by);
  train_cmd->add_option("--activity", c.train.activity, "Activity name or .bddl path");
  train_cmd->add_option("--baseline", c.train.baseline, "The baseline")->check(CLI::IsMember(baseline_names));
  train_cmd->add_option("--seed", c.train.seed, "Seed (env i of the vector env: seed + i)")
      ->check(seed_number())
      ->capture_default_str();
  train_steps_option =
      train_cmd->add_option("--steps", values.train_steps, "Total env steps (default 30000, or the resumed run's)")
          ->check(integer_in(1, 10000000000));
  train_cmd->add_option("--envs", c.train.envs, "Envs of the vector env")
      ->check(integer_in(1, 256))
      ->capture_default_str();
  train_cmd->add_option("--threads", c.train.threads, "Env worker and torch threads")
      ->check(integer_in(1, 64))
      ->capture_default_str();
  train_cmd->add_option("--out", c.train.out, "Run folder: metrics.csv, checkpoint.pt, checkpoint_STEPS.pt");
  train_cmd->add_option("--resume", c.train.resume, "Continue the run in this folder from its checkpoint.pt");
  train_cmd->add_option("--mode", c.train.mode, "Primitive execution: physical (the paper's) or symbolic")
      ->check(CLI::IsMember({"physical", "symbolic"}))
      ->capture_default_str();
  train_cmd->add_option("--observations", c.train.observations,
                        "Observed fields (default: the baseline's), e.g. rgb is_grasping");
  train_cmd
      ->add_option("--episode-steps", c.train.episode_steps,
                   "Steps per episode (default: 60 primitives, 500 low-level)")
      ->check(integer_in(1, 1000000));
  train_cmd
      ->add_option("--history", c.train.history,
                   "rl-prim-hist: observations the policy sees; rl-prim-action-hist: past primitives (default 4)")
      ->check(integer_in(1, 64));
  train_cmd
      ->add_option("--checkpoint-every", c.train.checkpoint_every,
                   "Env steps between checkpoints (default 3000, or the resumed run's)")
      ->check(integer_in(1, 10000000000));
  train_cmd->add_option(
      "--set", c.train.settings,
      "KEY=VALUE: a config field of the new run, as named in the run folder's config.json, e.g. ppo.entropy_coef=0.01");

  reproduce_cmd = app.add_subcommand(
      "reproduce", "The paper's baseline table (A.13) through train and eval: resumable, to OUT/baselines.{json,md}");
  reproduce_cmd->add_option("--activities", c.reproduce.activities, "Activities")->capture_default_str();
  reproduce_cmd->add_option("--methods", c.reproduce.methods, "Methods (baselines)")
      ->check(CLI::IsMember(baseline_names))
      ->capture_default_str();
  reproduce_cmd->add_option("--seeds", values.reproduce_seeds, "Training seeds: seeds or ranges A-B (0-9)")
      ->capture_default_str();
  reproduce_cmd->add_option("--seeds-for", values.reproduce_seeds_for,
                            "METHOD=SEEDS: that method's own training seeds (rl-vmc=0-2)");
  reproduce_cmd->add_option("--steps", c.reproduce.steps, "Training env steps per run")
      ->check(integer_in(1, 10000000000))
      ->capture_default_str();
  reproduce_cmd->add_option("--mode", c.reproduce.mode, "Primitive execution: physical (the paper's) or symbolic")
      ->check(CLI::IsMember({"physical", "symbolic"}))
      ->capture_default_str();
  reproduce_cmd->add_option("--jobs", c.reproduce.jobs, "Runs at once (one core each)")
      ->check(integer_in(1, 64))
      ->capture_default_str();
  reproduce_cmd->add_option("--eval-episodes", c.reproduce.eval_episodes, "Episodes at evaluation seed 0")
      ->check(integer_in(1, 999999))
      ->capture_default_str();
  reproduce_cmd
      ->add_option("--generalisation-seeds", values.generalisation_seeds,
                   "Seeds A-B of fresh instances, one episode each")
      ->capture_default_str();
  reproduce_cmd->add_option("--out", c.reproduce.out, "Results folder (runs/ inside)")->capture_default_str();
  reproduce_cmd->add_flag("!--no-videos", c.reproduce.videos, "Skip the best policies' videos");
  reproduce_cmd->add_flag("!--no-greedy-eval", c.reproduce.greedy_eval,
                          "Evaluate at seed 0 by sampling only (tables run before issue 53)");
  reproduce_cmd->add_flag("--report-only", c.reproduce.report_only, "Train and evaluate nothing: report the runs done");
  reproduce_cmd
      ->add_option("--compare-with", c.reproduce.compare_with,
                   "Another table's OUT: per cell, P(a run here scores above a run there)")
      ->check(CLI::ExistingDirectory);
  reproduce_cmd->add_option("--compare-method", values.compare_methods,
                            "METHOD=OTHER: compare this table's METHOD with OTHER of --compare-with's table");
  reproduce_cmd->add_option(
      "--set", c.reproduce.settings,
      "KEY=VALUE for every new run's chore train --set (ppo.* for the PPO methods, sac.* for SAC)");
  reproduce_cmd
      ->add_option(
          "--launcher", c.reproduce.launcher,
          "local: runs here, --jobs at a time; slurm: one Slurm job array of the runs not done (sbatch --wait), "
          "then the report")
      ->check(CLI::IsMember({"local", "slurm"}))
      ->capture_default_str();
  reproduce_cmd->add_option(
      "--sbatch", c.reproduce.sbatch_args,
      "With --launcher slurm: an argument for sbatch as it is (--partition=cpu, --time=04:00:00)");
  reproduce_cmd->add_option("--cell", values.reproduce_cell, "One run of the table alone (a Slurm array task's)")
      ->group("");
}

ParsedCommandLine CommandLineParser::Impl::parse(int argc, const char* const* argv, std::ostream& out,
                                                 std::ostream& err) {
  values = Values{};
  app.clear();
  CommandLine& c = values.c;
  // CLI11 would only say "a subcommand is required": name the unknown one.
  if (argc > 1 && argv[1][0] != '-') {
    std::string known;
    bool found = false;
    for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
      known += (known.empty() ? "" : ", ") + sub->get_name();
      found |= sub->get_name() == argv[1];
    }
    if (!found) {
      err << "chore: error: unknown subcommand '" << argv[1] << "' (known: " << known << ")" << std::endl;
      return {std::nullopt, 2};
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return {std::nullopt, app.exit(e, out, err)};
  } catch (const CLI::ParseError& e) {
    app.exit(e, out, err);
    return {std::nullopt, 2};
  }

  // What CLI11 cannot check alone.
  try {
    if (*check_cmd) c.command = Command::activity_check;
    if (*coverage_cmd) c.command = Command::activity_coverage;
    if (*solve_cmd) {
      c.command = Command::activity_solve;
      c.coverage.solve = parse_execution_mode(values.solve_mode);
      const auto [first, last] = seed_range(values.solve_seeds, "--seeds");
      if (last - first >= kMaxSolveSeeds) {
        throw Error("--seeds: at most " + std::to_string(kMaxSolveSeeds) + " seeds per activity");
      }
      c.coverage.seed = first, c.coverage.last_seed = last;
    }
    if (*scene_list_cmd) c.command = Command::scene_list;
    if (*scene_build_cmd) {
      c.command = Command::scene_build;
      c.scene_build.model_cache = values.model_cache;
    }
    if (*sample_cmd) {
      c.command = Command::activity_sample;
      if (!values.sample_seeds.empty()) c.sample.seeds = seed_range(values.sample_seeds, "--seeds");
      if (!c.sample.seeds && c.sample.out.empty()) throw Error("activity sample: give --out FILE.png or --seeds A-B");
    }
    if (*expert_cmd) {
      c.command = Command::expert;
      c.expert.mode = parse_execution_mode(values.expert_mode);
    }
    if (*eval_cmd) {
      c.command = Command::eval;
      std::tie(c.eval.first_seed, c.eval.last_seed) = seed_range(values.eval_seeds, "--seeds");
    }
    if (*video_cmd) c.command = Command::video;
    if (*observe_cmd) c.command = Command::observe;
    if (*plot_cmd) c.command = Command::plot;
    if (*train_cmd) {
      c.command = Command::train;
      if (*train_steps_option) c.train.steps = values.train_steps;
    }
    if (*reproduce_cmd) {
      c.command = Command::reproduce;
      c.reproduce.seeds = table_seeds(values.reproduce_seeds, "--seeds");
      for (const std::string& text : values.reproduce_seeds_for) {
        const size_t eq = text.find('=');
        if (eq == std::string::npos) throw Error("--seeds-for '" + text + "': expected METHOD=SEEDS, e.g. rl-vmc=0-2");
        const std::string method = text.substr(0, eq);
        if (c.reproduce.seeds_for.contains(method)) throw Error("--seeds-for " + method + ": given twice");
        // Seeds and ranges, comma-separated (rl-vmc=0-2,5).
        std::vector<std::string> seeds;
        for (size_t from = eq + 1; from <= text.size();) {
          const size_t comma = std::min(text.find(',', from), text.size());
          seeds.push_back(text.substr(from, comma - from));
          from = comma + 1;
        }
        c.reproduce.seeds_for[method] = table_seeds(seeds, "--seeds-for " + method);
      }
      if (values.reproduce_cell >= 0) c.reproduce.cell = static_cast<size_t>(values.reproduce_cell);
      for (const std::string& text : values.compare_methods) {
        const size_t eq = text.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == text.size()) {
          throw Error("--compare-method '" + text + "': expected METHOD=OTHER, e.g. rl-prim-action-hist=rl-prim-hist");
        }
        c.reproduce.compare_methods[text.substr(0, eq)] = text.substr(eq + 1);
      }
      if (!c.reproduce.compare_methods.empty() && c.reproduce.compare_with.empty()) {
        throw Error("--compare-method needs --compare-with");
      }
      std::tie(c.reproduce.generalisation_first, c.reproduce.generalisation_last) =
          seed_range(values.generalisation_seeds, "--generalisation-seeds");
      c.reproduce.command_line = "scripts/reproduce";
      for (int i = 2; i < argc; ++i) c.reproduce.command_line += std::string(" ") + argv[i];
    }
    if (*bench_cmd) c.command = Command::bench;
  } catch (const Error& e) {
    err << "chore: error: " << e.what() << std::endl;
    return {std::nullopt, 2};
  }
  return {std::move(c), 0};
}

CommandLineParser::CommandLineParser() : impl_(std::make_unique<Impl>()) {}
CommandLineParser::~CommandLineParser() = default;

ParsedCommandLine CommandLineParser::parse(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  return impl_->parse(argc, argv, out, err);
}

ParsedCommandLine parse_command_line(int argc, const char* const* argv, std::ostream& out, std::ostream& err) {
  return CommandLineParser().parse(argc, argv, out, err);
}

}  // namespace chore
