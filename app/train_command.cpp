#include "app/train_command.hpp"

#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "base/error.hpp"
#include "base/json_file.hpp"
#include "training/checkpoint.hpp"
#include "training/trainer.hpp"

namespace chore {
namespace fs = std::filesystem;
namespace {

std::string format_duration(double seconds) {
  char text[32];
  const long s = std::lround(std::max(seconds, 0.0));
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, s / 60 % 60);
  } else {
    std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  }
  return text;
}

// A metrics row's env steps (its first cell), or none when it is not a number.
std::optional<int64_t> row_steps(const std::string& line) {
  const size_t comma = line.find(',');
  if (comma == std::string::npos) return std::nullopt;
  int64_t steps = 0;
  const char* end = line.data() + comma;
  const auto [stop, error] = std::from_chars(line.data(), end, steps);
  if (error != std::errc() || stop != end) return std::nullopt;
  return steps;
}

// A new run's folder: made if missing, else one that is empty or already
// chore's (its marker, kRunMarker: a run that stopped before its first
// checkpoint, or a folder reproduce made); chore never writes over files it
// did not make. Until keep(), a failed run removes what it made: the folder
// if it made it, else the files it wrote there.
class RunFolder {
 public:
  explicit RunFolder(const fs::path& dir) : dir_(dir) {
    std::error_code error;
    made_dir_ = !fs::exists(dir, error);
    if (!fs::create_directories(dir, error) && error) {
      throw Error("train: --out " + dir.string() + ": cannot make the folder: " + error.message());
    }
    if (!fs::is_directory(dir)) throw Error("train: --out " + dir.string() + ": not a folder");
    made_marker_ = !fs::exists(dir / kRunMarker);
    if (made_marker_ && !fs::is_empty(dir)) {
      std::string files;
      int shown = 0;
      for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
        if (shown++ < 3) files += (files.empty() ? "" : ", ") + entry.path().filename().string();
      }
      throw Error("train: --out " + dir.string() + ": a folder of other files (" + files + (shown > 3 ? ", ..." : "") +
                  "), not a chore run; give a new or empty folder");
    }
    mark_run_folder(dir);
  }
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;
  ~RunFolder() {
    if (kept_) return;
    std::error_code ignored;
    if (made_dir_) {
      fs::remove_all(dir_, ignored);
    } else {
      for (const char* file : {"config.json", "metrics.csv"}) fs::remove(dir_ / file, ignored);
      if (made_marker_) fs::remove(dir_ / kRunMarker, ignored);
    }
  }
  void keep() { kept_ = true; }

 private:
  fs::path dir_;
  bool made_dir_ = false, made_marker_ = false, kept_ = false;
};

// Keeps metrics.csv's header and the rows up to `steps` (a resumed run redoes
// what came after its checkpoint); writes the header for a new file.
void prepare_metrics(const fs::path& path, const std::string& header, int64_t steps) {
  std::vector<std::string> keep;
  if (std::ifstream in(path); in) {
    std::string line;
    while (std::getline(in, line)) {
      if (keep.empty()) {
        if (line != header) throw Error(path.string() + ": header differs from this trainer's: " + line);
      } else if (const std::optional<int64_t> row = row_steps(line);
                 std::count(line.begin(), line.end(), ',') != std::count(header.begin(), header.end(), ',') || !row ||
                 *row > steps) {
        continue;  // after the checkpoint, cut short by a kill, or not a row
      }
      keep.push_back(line);
    }
  }
  if (keep.empty()) keep.push_back(header);
  std::ofstream out(path, std::ios::trunc);
  for (const std::string& line : keep) out << line << "\n";
  if (!out) throw Error(path.string() + ": cannot write");
}

}  // namespace

void mark_run_folder(const fs::path& dir) {
  if (fs::exists(dir / kRunMarker)) return;
  std::ofstream marker(dir / kRunMarker);
  marker << "A chore run folder: `chore train` and `chore reproduce` write here (docs/training.md).\n";
  if (!marker) throw Error("train: cannot write " + (dir / kRunMarker).string());
}

TrainConfig new_run_config(const TrainOptions& o) {
  if (o.activity.empty()) throw Error("train: --activity is required");
  if (o.baseline.empty()) throw Error("train: --baseline is required");
  TrainConfig config = baseline_config(o.baseline, o.activity);
  config.seed = o.seed;
  config.num_envs = o.envs;
  config.threads = o.threads;
  config.total_steps = o.steps.value_or(30000);
  config.checkpoint_every = o.checkpoint_every.value_or(3000);
  config.env.primitive_mode = parse_execution_mode(o.mode);
  if (!o.observations.empty()) config.env.observations = o.observations;
  // Primitive episodes: 60 steps (as the scripted expert's); low-level: the env's 500.
  if (config.env.action_space == "primitives") config.env.max_episode_steps = 60;
  if (o.episode_steps > 0) config.env.max_episode_steps = o.episode_steps;
  if (o.history > 0) {
    if (config.baseline == "rl-prim-hist") {
      config.ppo.frames = o.history;
    } else if (config.baseline == "rl-prim-action-hist") {
      config.ppo.history = o.history;
    } else {
      throw Error("train: --history is for rl-prim-hist and rl-prim-action-hist");
    }
  }
  for (const std::string& setting : o.settings) config = with_setting(config, setting);
  return config;
}

// A rank other than 0: the same updates as rank 0's, in step with it, and
// nothing written (rank 0's checkpoints stand for the run).
void train_beside(Trainer& trainer, int64_t total, const RankInfo& rank, std::ostream& log) {
  trainer.train(total, [](const MetricsRow&) {});
  log << "train: rank " << rank.rank << " of " << rank.world_size << ": " << trainer.env_steps()
      << " steps done (rank 0 writes the run)" << std::endl;
}

void run_train(const TrainOptions& o, std::ostream& log) {
  const std::string dir = o.out.empty() ? o.resume : o.out;
  if (dir.empty()) throw Error("train: give --out DIR (or --resume DIR)");
  if (o.envs < 1) throw Error("train: --envs must be at least 1");
  if (o.threads < 1) throw Error("train: --threads must be at least 1");
  if (o.steps && *o.steps < 1) throw Error("train: --steps must be at least 1");
  if (o.checkpoint_every && *o.checkpoint_every < 1) throw Error("train: --checkpoint-every must be at least 1");
  const fs::path checkpoint = fs::path(dir) / "checkpoint.pt";
  // One rank of a data-parallel run when the launcher says so (torchrun's
  // or Slurm's variables): rank 0 keeps the run folder (config, metrics,
  // checkpoints), the others train beside it and write nothing.
  const RankInfo rank = rank_from_environment();
  const bool writes = rank.rank == 0;

  std::unique_ptr<Trainer> trainer;
  std::optional<RunFolder> made;  // what a new run made, removed if it fails before its first checkpoint
  if (!o.resume.empty()) {
    if (!o.out.empty() && fs::path(o.out) != fs::path(o.resume)) {
      throw Error("train: --resume continues in its own folder; drop --out or make it the same");
    }
    if (!fs::exists(checkpoint)) throw Error("train: --resume " + o.resume + ": no checkpoint.pt there");
    if (writes) remove_stale_checkpoint_temps(dir);
    trainer = resume_trainer(checkpoint.string(), rank);
    // The run's own config holds; only --steps may change (extend) it.
    if (!o.settings.empty()) throw Error("train: --set changes a new run; --resume continues one as it was");
    const TrainConfig& saved = trainer->config();
    if ((!o.activity.empty() && o.activity != saved.env.activity) ||
        (!o.baseline.empty() && o.baseline != saved.baseline) ||
        (o.checkpoint_every && *o.checkpoint_every != saved.checkpoint_every)) {
      throw Error("train: " + o.resume + " holds a " + saved.baseline + " run on " + saved.env.activity +
                  ", checkpointed every " + std::to_string(saved.checkpoint_every) +
                  " steps; --resume continues it as it was");
    }
  } else {
    if (writes && fs::exists(checkpoint)) {
      throw Error("train: " + dir + " already holds a run (checkpoint.pt); --resume " + dir +
                  " continues it, or choose another --out");
    }
    // The trainer (its envs, the activity) first: a bad setting leaves no folder behind.
    TrainConfig config = new_run_config(o);
    config.rank = rank;
    trainer = make_trainer(config);
    if (!writes) return train_beside(*trainer, o.steps.value_or(config.total_steps), rank, log);
    made.emplace(dir);
    remove_stale_checkpoint_temps(dir);
    // The run's settings, readable without the checkpoint (the names --set takes).
    std::ofstream config_file(fs::path(dir) / "config.json");
    config_file << json_text(to_json(config), 2) << "\n";
    if (!config_file) throw Error("train: cannot write " + (fs::path(dir) / "config.json").string());
  }
  TrainConfig config = trainer->config();
  const int64_t total = o.steps.value_or(config.total_steps);
  if (!writes) return train_beside(*trainer, total, rank, log);

  std::string header = kMetricsHeader;
  for (const std::string& name : trainer->extra_metric_names()) header += "," + name;
  const fs::path metrics_path = fs::path(dir) / "metrics.csv";
  prepare_metrics(metrics_path, header, trainer->env_steps());
  std::ofstream metrics(metrics_path, std::ios::app);

  // A TTY gets one line redrawn in place; a log file a line every 30 s.
  const bool tty = isatty(STDERR_FILENO);
  const int64_t first_step = trainer->env_steps();
  const auto start = std::chrono::steady_clock::now();
  auto last_line = start - std::chrono::hours(1);
  auto report = [&](const MetricsRow& row) {
    metrics << row.env_steps << "," << row.wall_s << "," << row.episodes << "," << row.success_rate << "," << row.mean_q
            << "," << row.mean_return << "," << row.mean_length;
    for (double v : row.extras) metrics << "," << v;
    metrics << std::endl;
    const auto now = std::chrono::steady_clock::now();
    if (!tty && now - last_line < std::chrono::seconds(30) && row.env_steps < total) return;
    last_line = now;
    const double elapsed = std::chrono::duration<double>(now - start).count();
    const double rate = (row.env_steps - first_step) / std::max(elapsed, 1e-9);
    char line[256];
    std::snprintf(line, sizeof line,
                  "train %s: %lld/%lld steps (%.1f%%), %.1f steps/s, %lld episodes, success %.2f, "
                  "return %.3f, ETA %s",
                  config.baseline.c_str(), static_cast<long long>(row.env_steps), static_cast<long long>(total),
                  100.0 * row.env_steps / total, rate, static_cast<long long>(row.episodes), row.success_rate,
                  row.mean_return, format_duration((total - row.env_steps) / std::max(rate, 1e-9)).c_str());
    log << (tty ? "\r\033[K" : "") << line << (tty ? "" : "\n") << std::flush;
  };

  const int64_t every = config.checkpoint_every;
  while (trainer->env_steps() < total) {
    const int64_t next = std::min(total, (trainer->env_steps() / every + 1) * every);
    trainer->train(next, report);
    trainer->save(checkpoint.string());
    if (made) made->keep();
    trainer->save((fs::path(dir) / ("checkpoint_" + std::to_string(trainer->env_steps()) + ".pt")).string());
  }
  if (tty) log << "\n";
  log << "train: " << trainer->env_steps() << " steps done; checkpoint " << checkpoint.string() << ", metrics "
      << metrics_path.string() << std::endl;
}

}  // namespace chore
