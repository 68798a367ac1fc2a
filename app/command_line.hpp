// The `chore` command line read into what one command is to do, apart from
// doing it (app/main.cpp runs it): every argument is validated here, numbers
// against the ranges their --help states, seed ranges included, so that a bad
// argument is found before any work starts (and the parser can be fuzzed).
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/activity_coverage.hpp"
#include "app/bench.hpp"
#include "app/expert_command.hpp"
#include "app/observe_command.hpp"
#include "app/plot.hpp"
#include "app/reproduce.hpp"
#include "app/scene_commands.hpp"
#include "app/train_command.hpp"
#include "app/video.hpp"
#include "policies/evaluate.hpp"

namespace chore {

enum class Command {
  bench,
  activity_check,
  activity_sample,
  activity_coverage,
  activity_solve,
  scene_list,
  scene_build,
  expert,
  eval,
  video,
  observe,
  plot,
  train,
  reproduce
};

// Where eval and video get their policy and its env.
struct PolicyArgs {
  std::vector<std::string> checkpoints;
  std::string activity, plugin, plugin_options, action_space = "primitives", mode;
  std::string instances;  // "fixed" or "resample"; empty: a checkpoint's own, else resample
  std::vector<std::string> observations;
  int max_steps = 0;
  bool expert = false;
  bool sample = false;  // checkpoints: act by sampling, not greedily
};

struct SampleArgs {
  std::string name, scene, out;  // out: the picture of one seed
  uint64_t seed = 0;
  std::optional<std::pair<uint64_t, uint64_t>> seeds;  // --seeds A-B: instantiate each, no picture
};

// The command and its options; only those of `command` are set.
struct CommandLine {
  Command command = Command::bench;
  bool json = false;  // bench, expert, eval, activity coverage, scene build: print JSON
  BenchOptions bench;
  std::vector<std::string> check_files;
  SampleArgs sample;
  CoverageOptions coverage;
  SceneBuildOptions scene_build;
  ExpertOptions expert;
  EvalOptions eval;
  PolicyArgs policy;  // eval, video
  VideoOptions video;
  ObserveOptions observe;
  PlotOptions plot;
  TrainOptions train;
  ReproduceOptions reproduce;
};

// The command, or, when there is nothing to run, the exit status: 0 after
// --help (written to `out`), 2 after a bad argument (its message on `err`).
struct ParsedCommandLine {
  std::optional<CommandLine> command;
  int exit_status = 0;
};
ParsedCommandLine parse_command_line(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

// The same, for many command lines: CLI11's ~150 options are built once, and
// each parse starts from the defaults (the fuzz target parses millions).
class CommandLineParser {
 public:
  CommandLineParser();
  ~CommandLineParser();
  ParsedCommandLine parse(int argc, const char* const* argv, std::ostream& out, std::ostream& err);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace chore
