// `chore train`: trains a baseline (rl-vmc, rl-prim, rl-prim-hist) on an
// activity; metrics to DIR/metrics.csv, checkpoints to DIR, a progress line
// on the log; --resume continues a run from its last checkpoint.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "training/trainer.hpp"

namespace chore {

struct TrainOptions {
  std::string activity, baseline;
  uint64_t seed = 0;
  std::optional<int64_t> steps;  // total env steps; default 30000, or the resumed run's
  int envs = 1, threads = 1;
  std::string out;                          // run folder; defaults to `resume`
  std::string resume;                       // a run folder holding checkpoint.pt
  std::string mode = "physical";            // primitive execution (rl-prim, rl-prim-hist)
  std::vector<std::string> observations;    // empty: the baseline's
  int episode_steps = 0;                    // 0: the baseline's
  int history = 0;                          // rl-prim-hist's K; 0: PpoConfig's default
  std::optional<int64_t> checkpoint_every;  // env steps; default 3000, or the resumed run's
  std::vector<std::string> settings;        // KEY=VALUE overrides of the config (with_setting)
};

// The file that marks a folder as a chore run's, which a new run may write
// into (empty or not): train writes it into the folder of a new run, and
// reproduce into its cells' before it starts their logs.
inline constexpr const char* kRunMarker = ".chore-run";
void mark_run_folder(const std::filesystem::path& dir);

// The config of a new run from the options (not --resume's); throws chore::Error.
TrainConfig new_run_config(const TrainOptions& options);

// Runs (or resumes) the training; throws chore::Error for bad options or files.
void run_train(const TrainOptions& options, std::ostream& log);

}  // namespace chore
