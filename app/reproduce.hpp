// `chore reproduce` (scripts/reproduce): the BEHAVIOR-1K appendix's baseline
// experiment (Table A.13) through `chore train` and `chore eval`.
//
// Every (activity, method, training seed) cell is one run folder,
//   OUT/runs/MODE/ACTIVITY/METHOD_seedS/
// holding what `chore train` writes (metrics.csv, checkpoints), train.log, the
// evaluations' JSON (eval_seed0.json: the paper's evaluation seed;
// eval_generalisation.json: fresh instances, seeds 100-119) and cell.json, its
// summary, written last. A cell whose cell.json matches the options is done and
// skipped; one with a checkpoint resumes from it (`chore train --resume`), so
// the whole table may be stopped at any moment and run again. Cells run as
// child processes of this executable, `jobs` at a time, one thread each.
//
// At the end (and with --report-only, from whatever cells are done) it writes
// OUT/baselines.json and OUT/baselines.md (baselines_report.hpp: the table
// beside the paper's, the failure breakdown, wall-clock per run, the machine
// and the commit), OUT/curves/ACTIVITY.png (Q over training steps, mean and
// spread over seeds per method) and OUT/videos/ACTIVITY.mp4 (the best policy's
// episode at evaluation seed 0).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace chore {

struct ReproduceOptions {
  std::vector<std::string> activities = {"store_decoration", "collect_trash", "clean_table"};
  std::vector<std::string> methods = {"rl-vmc", "rl-prim", "rl-prim-hist"};
  std::vector<uint64_t> seeds = {0, 1, 2};
  // A method's own training seeds where they differ from `seeds` (`--seeds-for
  // rl-vmc=0-2`: a method whose runs all score 0 may stay at fewer seeds).
  std::map<std::string, std::vector<uint64_t>> seeds_for;
  int64_t steps = 30000;          // training env steps per run (the paper's)
  std::string mode = "physical";  // primitive execution (the paper's)
  int jobs = 2;                   // runs at once
  int eval_episodes = 100;        // episodes at evaluation seed 0, each policy
  bool greedy_eval = true;        // evaluate at seed 0 greedily as well as sampling (the table's Q)
  uint64_t generalisation_first = 100, generalisation_last = 119;  // one episode each
  std::string out = "results";
  bool videos = true;
  bool report_only = false;  // no training or evaluation: report the cells done
  // `chore train --set KEY=VALUE` for every new run; ppo.* reach only the PPO
  // methods and sac.* only SAC's, so a method's runs are shared between tables
  // whose settings differ only for the other algorithm.
  std::vector<std::string> settings;
  // Another table's OUT to set this one against (a protocol study's variant
  // against its reference): per activity and method, P(a run here scores
  // above a run there) with its interval and verdict. A method is compared
  // with its namesake there, or with the one `compare_methods` maps it to.
  std::string compare_with;
  std::map<std::string, std::string> compare_methods;
  std::string command_line;  // as typed, for the report
  // Where the runs run: "local" (this host, `jobs` at a time) or "slurm" (the
  // runs not done as one Slurm job array, `sbatch --wait`ed, each task one
  // run; resubmitted, the command runs only those still not done), with
  // `sbatch_args` given to sbatch as they are (--partition=..., --time=...).
  std::string launcher = "local";
  std::vector<std::string> sbatch_args;
  // An array task's run: cells_of(options)[cell] alone, no report (internal:
  // the script --launcher slurm writes passes it).
  std::optional<size_t> cell;
};

// The training seeds of `method`'s runs.
const std::vector<uint64_t>& seeds_of(const ReproduceOptions& options, const std::string& method);

// Runs the cells not done yet, then writes the report; returns baselines.json's
// content. chore::Error for bad options; a failed run is reported (its log's
// last lines) and left out of the table, not thrown.
nlohmann::json reproduce(const ReproduceOptions& options, std::ostream& log);

}  // namespace chore
