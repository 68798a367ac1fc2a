#include "app/reproduce.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "app/baselines_report.hpp"
#include "app/train_command.hpp"
#include "base/error.hpp"
#include "base/json_file.hpp"
#include "base/temp_file.hpp"
#include "tasks/activity.hpp"
#include "training/checkpoint.hpp"
#include "training/trainer.hpp"

extern char** environ;

namespace chore {
namespace fs = std::filesystem;

const std::vector<uint64_t>& seeds_of(const ReproduceOptions& o, const std::string& method) {
  const auto it = o.seeds_for.find(method);
  return it == o.seeds_for.end() ? o.seeds : it->second;
}

namespace {

using Clock = std::chrono::steady_clock;

// Written whole or not at all: a stop mid-write leaves the old file.
void write_text(const fs::path& path, const std::string& text) {
  const fs::path tmp = temp_path_for(path);
  {
    std::ofstream out(tmp, std::ios::trunc);
    out << text;
    if (!out) throw Error(tmp.string() + ": cannot write");
  }
  fs::rename(tmp, path);
}

std::string tail(const fs::path& path, size_t lines) {
  std::ifstream in(path);
  std::deque<std::string> last;
  for (std::string line; std::getline(in, line);) {
    last.push_back(line);
    if (last.size() > lines) last.pop_front();
  }
  std::string out;
  for (const std::string& l : last) out += l + "\n";
  return out;
}

using Cell = TableCell;

// The --set settings that reach `method`'s trainer.
std::vector<std::string> settings_for(const std::string& method, const std::vector<std::string>& settings) {
  const std::string& mine = algorithm_of(method).name;
  std::vector<std::string> kept;
  for (const std::string& s : settings) {
    const std::string group = s.substr(0, s.find('.'));
    const bool others = group != mine && std::any_of(algorithms().begin(), algorithms().end(),
                                                     [&](const Algorithm& a) { return a.name == group; });
    if (!others) kept.push_back(s);
  }
  return kept;
}

// The cell's `chore train` (a new run).
TrainOptions train_options(const Cell& c, const ReproduceOptions& o) {
  TrainOptions t;
  t.activity = c.activity;
  t.baseline = c.method;
  t.seed = c.seed;
  t.steps = o.steps;
  t.mode = o.mode;
  t.threads = 1;
  t.out = c.dir.string();
  t.settings = settings_for(c.method, o.settings);
  return t;
}

// What a finished cell must match to be skipped (settings only where given,
// so cells from before they existed still match).
nlohmann::json cell_spec(const Cell& c, const ReproduceOptions& o) {
  nlohmann::json spec = {
      {"activity", c.activity},   {"method", c.method},
      {"seed", c.seed},           {"steps", o.steps},
      {"mode", o.mode},           {"eval_episodes", o.eval_episodes},
      {"eval_policy", "sampled"}, {"generalisation_seeds", {o.generalisation_first, o.generalisation_last}}};
  if (o.greedy_eval) spec["eval_greedy"] = true;  // absent from cells evaluated before it was
  if (const auto settings = settings_for(c.method, o.settings); !settings.empty()) spec["settings"] = settings;
  return spec;
}

// A cell's checkpoint is resumed only if it is the run these options would
// start (all but the step count): other settings or code defaults mean another run.
void check_resumable(const Cell& c, const ReproduceOptions& o) {
  const fs::path checkpoint = c.dir / "checkpoint.pt";
  nlohmann::json saved;
  try {
    // Read back through today's reader: fields added since take their defaults.
    saved = to_json(train_config_from_json(read_checkpoint(checkpoint.string()).meta.at("config")));
  } catch (const std::exception&) {
    return;  // unreadable: the run fails on it and the table reports that
  }
  nlohmann::json wanted = to_json(new_run_config(train_options(c, o)));
  saved.erase("total_steps");
  wanted.erase("total_steps");
  if (saved == wanted) return;
  std::string differs;
  for (const nlohmann::json& op : nlohmann::json::diff(saved, wanted)) {
    differs += (differs.empty() ? "" : ", ") + op.at("path").get<std::string>().substr(1);
  }
  throw Error("reproduce: " + checkpoint.string() + " is a run with other settings (" + differs +
              ") than these options; remove it or give another --out");
}

bool cell_done(const Cell& c, const ReproduceOptions& o) {
  const fs::path path = c.dir / "cell.json";
  if (!fs::exists(path)) return false;
  try {
    const nlohmann::json cell = read_json_file(path.string());
    return cell.is_object() && cell.contains("spec") && cell["spec"] == cell_spec(c, o);  // its fields: the report's
  } catch (const Error&) {
    return false;  // unreadable: run it again
  }
}

const std::string& self_path() {
  static const std::string self = fs::read_symlink("/proc/self/exe").string();
  return self;
}

// A child process of `program` (this executable by default): `args` after
// the program name, stdout to `out` (truncated) and stderr appended to `log`.
pid_t spawn(const std::vector<std::string>& args, const fs::path& out, const fs::path& log,
            const std::string& program = self_path()) {
  const std::string& self = program;
  std::vector<std::string> all = {self};
  all.insert(all.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& a : all) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  pid_t pid = 0;
  const int error = self.find('/') == std::string::npos
                        ? posix_spawnp(&pid, self.c_str(), &actions, nullptr, argv.data(), environ)
                        : posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw Error("reproduce: cannot start " + self + ": " + std::strerror(error));
  return pid;
}

// One `chore eval` of a cell's checkpoint, its JSON into `file`.
struct CellEvaluation {
  std::string file, seeds;
  int episodes;
  bool sample;
  std::string instances;  // --instances; empty: the run's own
};

// A cell's evaluations: at the paper's seed sampling (the table's Q) and
// greedily, then one episode on each fresh instance of the generalisation
// seeds (drawn afresh whatever instances the run trained on).
std::vector<CellEvaluation> cell_evaluations(const ReproduceOptions& o) {
  std::vector<CellEvaluation> e = {{"eval_seed0.json", "0-0", o.eval_episodes, true, ""}};
  if (o.greedy_eval) e.push_back({"eval_seed0_greedy.json", "0-0", o.eval_episodes, false, ""});
  e.push_back({"eval_generalisation.json",
               std::to_string(o.generalisation_first) + "-" + std::to_string(o.generalisation_last), 1, true,
               "resample"});
  return e;
}

// The summary of one evaluation file: its totals, not its per-episode lists.
nlohmann::json evaluation_summary(const fs::path& file) {
  return reading_json(file.string(), [&] {
    nlohmann::json summary = read_json_file(file.string()).at(0);
    summary.erase("per_episode");
    summary.erase("per_seed");
    return summary;
  });
}

// Q and success over the first `n` episodes of an evaluation file.
nlohmann::json first_episodes(const fs::path& file, size_t n) {
  return reading_json(file.string(), [&]() -> nlohmann::json {
    const nlohmann::json episodes = read_json_file(file.string()).at(0).at("per_episode");
    double q = 0, success = 0;
    const size_t count = std::min(n, episodes.size());
    for (size_t i = 0; i < count; ++i) {
      q += episodes[i].at("q").get<double>();
      success += episodes[i].at("success").get<bool>();
    }
    return {{"episodes", count},
            {"q", q / std::max<size_t>(count, 1)},
            {"success_rate", success / std::max<size_t>(count, 1)}};
  });
}

// A cell's work, one child after another: train (or resume), the
// evaluations, then cell.json.
class CellRun {
 public:
  CellRun(Cell cell, const ReproduceOptions& o) : cell_(std::move(cell)), o_(o), evaluations_(cell_evaluations(o)) {}
  const Cell& cell() const { return cell_; }

  // Starts the next child; false when the cell has nothing left to run.
  // `what` says what the child does.
  bool start_next(std::string& what) {
    const size_t stage = stage_++;
    if (stage == 0) {
      train(what);
      return true;
    }
    if (stage >= 2) {  // the evaluation before this one finished
      const std::string done = evaluations_[stage - 2].file;
      fs::rename(cell_.dir / (done + ".part"), cell_.dir / done);
    }
    if (stage == 1) eval_started_ = Clock::now();
    if (stage <= evaluations_.size()) {
      const CellEvaluation& e = evaluations_[stage - 1];
      what = std::string("evaluating ") + (e.sample ? "sampled" : "greedy") + " on seeds " + e.seeds;
      evaluate(e);
      return true;
    }
    if (stage == evaluations_.size() + 1) write_summary();
    return false;
  }
  pid_t pid() const { return pid_; }
  // The log of the child now running, for a failure's report.
  fs::path current_log() const { return cell_.dir / (stage_ <= 1 ? "train.log" : "eval.log"); }
  double seconds() const { return std::chrono::duration<double>(Clock::now() - started_).count(); }

 private:
  void train(std::string& what) {
    const fs::path log = cell_.dir / "train.log";
    const std::string steps = std::to_string(o_.steps);
    what = "training (" + log.string() + ")";
    started_ = Clock::now();
    if (fs::exists(cell_.dir / "checkpoint.pt")) {
      pid_ = spawn({"train", "--resume", cell_.dir.string(), "--steps", steps}, "/dev/null", log);
      return;
    }
    const TrainOptions t = train_options(cell_, o_);
    std::vector<std::string> args = {"train",
                                     "--activity",
                                     t.activity,
                                     "--baseline",
                                     t.baseline,
                                     "--seed",
                                     std::to_string(t.seed),
                                     "--steps",
                                     steps,
                                     "--mode",
                                     t.mode,
                                     "--threads",
                                     std::to_string(t.threads),
                                     "--out",
                                     t.out};
    for (const std::string& setting : t.settings) args.insert(args.end(), {"--set", setting});
    pid_ = spawn(args, "/dev/null", log);
  }

  // `chore eval` of the run's checkpoint, its JSON to `file`.part.
  void evaluate(const CellEvaluation& e) {
    std::vector<std::string> args = {"eval", "--checkpoint", (cell_.dir / "checkpoint.pt").string()};
    if (e.sample) args.push_back("--sample");
    if (!e.instances.empty()) args.insert(args.end(), {"--instances", e.instances});
    args.insert(args.end(), {"--seeds", e.seeds, "--episodes", std::to_string(e.episodes), "--threads", "1", "--json"});
    pid_ = spawn(args, cell_.dir / (e.file + ".part"), cell_.dir / "eval.log");
  }

  void write_summary() {
    nlohmann::json summary = {{"spec", cell_spec(cell_, o_)},
                              {"train_wall_s", last_metric(cell_.dir / "metrics.csv", "wall_s", 0.0)},
                              {"eval_wall_s", std::chrono::duration<double>(Clock::now() - eval_started_).count()},
                              {"seed0", evaluation_summary(cell_.dir / "eval_seed0.json")},
                              {"generalisation", evaluation_summary(cell_.dir / "eval_generalisation.json")}};
    if (o_.greedy_eval) summary["seed0_greedy"] = evaluation_summary(cell_.dir / "eval_seed0_greedy.json");
    // The appendix's protocol as chore read it before issue 53: ten sampled episodes.
    summary["seed0_first10"] = first_episodes(cell_.dir / "eval_seed0.json", 10);
    write_text(cell_.dir / "cell.json", json_text(summary, 2) + "\n");
  }

  Cell cell_;
  const ReproduceOptions& o_;
  std::vector<CellEvaluation> evaluations_;
  size_t stage_ = 0;
  pid_t pid_ = -1;
  Clock::time_point started_, eval_started_;
};

void validate(const ReproduceOptions& o) {
  if (o.activities.empty() || o.methods.empty() || o.seeds.empty()) {
    throw Error("reproduce: give at least one activity, method and seed");
  }
  for (const std::string& m : o.methods) {
    try {
      algorithm_of(m);
    } catch (const Error& e) {
      throw Error(std::string("reproduce: ") + e.what());
    }
  }
  for (const std::string& a : o.activities) {
    if (a.empty() || a.find('/') != std::string::npos || a.ends_with(".bddl")) {
      throw Error("reproduce: '" + a + "': give activities by name (a run folder is named after it)");
    }
    resolve_activity_path(a);  // throws naming the known ones
  }
  for (const auto& [m, seeds] : o.seeds_for) {
    if (std::find(o.methods.begin(), o.methods.end(), m) == o.methods.end()) {
      throw Error("reproduce: --seeds-for " + m + ": not one of the table's --methods");
    }
    if (seeds.empty()) throw Error("reproduce: --seeds-for " + m + ": give at least one seed");
  }
  if (o.mode != "physical" && o.mode != "symbolic") throw Error("reproduce: --mode is physical or symbolic");
  if (o.steps < 1) throw Error("reproduce: --steps must be at least 1");
  if (o.jobs < 1) throw Error("reproduce: --jobs must be at least 1");
  if (o.launcher != "local" && o.launcher != "slurm") throw Error("reproduce: --launcher is local or slurm");
  if (!o.sbatch_args.empty() && o.launcher != "slurm") throw Error("reproduce: --sbatch is for --launcher slurm");
  if (o.eval_episodes < 1) throw Error("reproduce: --eval-episodes must be at least 1");
  if (o.generalisation_last < o.generalisation_first) throw Error("reproduce: --generalisation-seeds: B is below A");
  for (const std::string& m : o.methods) {
    for (const std::string& setting : settings_for(m, o.settings)) {
      with_setting(baseline_config(m, ""), setting);  // throws naming a bad one
    }
  }
}

std::vector<Cell> cells_of(const ReproduceOptions& o) {
  std::vector<Cell> cells;
  for (const std::string& a : o.activities) {
    for (const std::string& m : o.methods) {
      for (uint64_t s : seeds_of(o, m)) {
        cells.push_back({a, m, s, fs::path(o.out) / "runs" / o.mode / a / (m + "_seed" + std::to_string(s))});
      }
    }
  }
  return cells;
}

// The cells that are not done; their folders checked (a run to resume must be
// this table's, a folder chore did not make is left alone).
std::deque<Cell> cells_to_run(const std::vector<Cell>& cells, const ReproduceOptions& o, std::ostream& log) {
  std::deque<Cell> todo;
  for (const Cell& c : cells) {
    if (cell_done(c, o)) {
      log << "reproduce: " << c.label() << ": done already (" << (c.dir / "cell.json").string() << ")\n";
    } else {
      if (fs::exists(c.dir / "checkpoint.pt")) {
        check_resumable(c, o);
      } else if (fs::exists(c.dir) && !fs::exists(c.dir / kRunMarker) && !fs::is_empty(c.dir)) {
        throw Error("reproduce: " + c.dir.string() + " holds files chore did not make (no " + kRunMarker +
                    "); move them away or give another --out");
      }
      todo.push_back(c);
    }
  }
  return todo;
}

// Runs the cells that are not done, `jobs` at a time; returns the failures.
nlohmann::json run_cells(const std::vector<Cell>& cells, const ReproduceOptions& o, std::ostream& log) {
  std::deque<Cell> todo = cells_to_run(cells, o, log);
  nlohmann::json failures = nlohmann::json::array();
  std::map<pid_t, std::unique_ptr<CellRun>> running;
  const size_t total = todo.size();
  size_t finished = 0;
  while (!todo.empty() || !running.empty()) {
    while (!todo.empty() && running.size() < static_cast<size_t>(o.jobs)) {
      auto run = std::make_unique<CellRun>(todo.front(), o);
      todo.pop_front();
      fs::create_directories(run->cell().dir);
      mark_run_folder(run->cell().dir);
      std::string what;
      run->start_next(what);
      log << "reproduce: " << run->cell().label() << ": " << what << std::endl;
      running.emplace(run->pid(), std::move(run));
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, 0);
    if (pid < 0) throw Error(std::string("reproduce: waitpid: ") + std::strerror(errno));
    auto it = running.find(pid);
    if (it == running.end()) continue;
    std::unique_ptr<CellRun> run = std::move(it->second);
    running.erase(it);
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    if (!ok) {
      const std::string last = tail(run->current_log(), 5);
      log << "reproduce: " << run->cell().label() << ": FAILED (see " << run->current_log().string() << "):\n"
          << last << std::flush;
      failures.push_back({{"cell", run->cell().label()}, {"log", run->current_log().string()}, {"last_lines", last}});
      ++finished;
      continue;
    }
    if (std::string what; run->start_next(what)) {
      log << "reproduce: " << run->cell().label() << ": " << what << std::endl;
      running.emplace(run->pid(), std::move(run));
      continue;
    }
    ++finished;
    log << "reproduce: " << run->cell().label() << ": done in " << format_hours(run->seconds()) << " (" << finished
        << "/" << total << ")" << std::endl;
  }
  return failures;
}

// The arguments of `chore reproduce` that make this table again: a Slurm
// array task derives its cell from them (cells_of is a function of them).
std::vector<std::string> table_arguments(const ReproduceOptions& o) {
  std::vector<std::string> a = {"reproduce", "--activities"};
  a.insert(a.end(), o.activities.begin(), o.activities.end());
  a.push_back("--methods");
  a.insert(a.end(), o.methods.begin(), o.methods.end());
  a.push_back("--seeds");
  for (const uint64_t seed : o.seeds) a.push_back(std::to_string(seed));
  for (const auto& [method, seeds] : o.seeds_for) {
    std::string list;
    for (const uint64_t seed : seeds) list += (list.empty() ? "" : ",") + std::to_string(seed);
    a.insert(a.end(), {"--seeds-for", method + "=" + list});
  }
  a.insert(a.end(), {"--steps", std::to_string(o.steps), "--mode", o.mode, "--eval-episodes",
                     std::to_string(o.eval_episodes), "--generalisation-seeds",
                     std::to_string(o.generalisation_first) + "-" + std::to_string(o.generalisation_last), "--out",
                     fs::absolute(o.out).string(), "--jobs", "1"});
  if (!o.videos) a.push_back("--no-videos");
  if (!o.greedy_eval) a.push_back("--no-greedy-eval");
  for (const std::string& setting : o.settings) a.insert(a.end(), {"--set", setting});
  return a;
}

std::string shell_quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

// --launcher slurm: the cells not done as one Slurm job array (each task
// `chore reproduce ... --cell I`, I its index in cells_of), submitted with
// sbatch --wait; returns the failures (the cells still not done after it).
nlohmann::json run_cells_on_slurm(const std::vector<Cell>& cells, const ReproduceOptions& o, std::ostream& log) {
  const std::deque<Cell> todo = cells_to_run(cells, o, log);
  nlohmann::json failures = nlohmann::json::array();
  if (todo.empty()) return failures;
  const fs::path dir = fs::absolute(o.out) / "slurm";
  fs::create_directories(dir);
  std::string indices;
  for (const Cell& c : todo) {
    const size_t i = static_cast<size_t>(
        std::find_if(cells.begin(), cells.end(), [&](const Cell& d) { return d.dir == c.dir; }) - cells.begin());
    indices += (indices.empty() ? "" : ",") + std::to_string(i);
    fs::create_directories(c.dir);
    mark_run_folder(c.dir);
  }
  // Each task one core (a run's torch and env threads are one); requeued
  // after a preemption or a node's failure, it resumes from its checkpoint.
  std::string script =
      "#!/bin/bash\n#SBATCH --job-name=chore-reproduce\n#SBATCH --array=" + indices +
      "\n#SBATCH --cpus-per-task=1\n#SBATCH --requeue\n#SBATCH --output=" + (dir / "cell_%a.log").string() + "\nexec " +
      shell_quoted(self_path());
  for (const std::string& a : table_arguments(o)) script += " " + shell_quoted(a);
  script += " --cell \"$SLURM_ARRAY_TASK_ID\"\n";
  const fs::path file = dir / "reproduce_array.sh";
  write_text(file, script);
  std::vector<std::string> args = {"--wait", "--parsable"};
  args.insert(args.end(), o.sbatch_args.begin(), o.sbatch_args.end());
  args.push_back(file.string());
  log << "reproduce: " << todo.size() << " run(s) as a Slurm job array (" << file.string() << "), waiting for it"
      << std::endl;
  const pid_t pid = spawn(args, dir / "sbatch.out", dir / "sbatch.log", "sbatch");
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) throw Error(std::string("reproduce: waitpid: ") + std::strerror(errno));
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
    throw Error("reproduce: --launcher slurm: no sbatch on PATH (Slurm's client; see " + (dir / "sbatch.log").string() +
                ")");
  for (const Cell& c : todo) {
    if (cell_done(c, o)) continue;
    const size_t i = static_cast<size_t>(
        std::find_if(cells.begin(), cells.end(), [&](const Cell& d) { return d.dir == c.dir; }) - cells.begin());
    const fs::path task_log = dir / ("cell_" + std::to_string(i) + ".log");
    const std::string last = fs::exists(task_log) ? tail(task_log, 5) : tail(dir / "sbatch.log", 5);
    log << "reproduce: " << c.label() << ": FAILED (see " << task_log.string() << "):\n" << last << std::flush;
    failures.push_back({{"cell", c.label()}, {"log", task_log.string()}, {"last_lines", last}});
  }
  return failures;
}

// Videos: per activity, the run with the best Q at seed 0 whose checkpoint is here;
// the other activities keep the videos an earlier invocation made.
nlohmann::json make_videos(const nlohmann::json& runs, const ReproduceOptions& o, std::ostream& log) {
  const fs::path out(o.out);
  const std::string table = (out / "baselines.json").string();
  nlohmann::json videos =
      fs::exists(table)
          ? reading_json(table,
                         [&] {
                           nlohmann::json earlier = read_json_file(table).value("videos", nlohmann::json::object());
                           // ...while their file and their run are still here (a run moved away takes its video's entry
                           // along).
                           for (auto it = earlier.begin(); it != earlier.end();) {
                             const bool here = fs::exists(it->value("file", "")) &&
                                               fs::exists(fs::path(it->value("run", "")) / "cell.json");
                             it = here ? std::next(it) : earlier.erase(it);
                           }
                           return earlier;
                         })
          : nlohmann::json::object();
  if (o.videos && !o.report_only) {
    fs::create_directories(out / "videos");
    for (const std::string& a : o.activities) {
      const nlohmann::json* best = nullptr;
      for (const nlohmann::json& r : runs) {
        if (r["activity"] != a || !fs::exists(fs::path(r["dir"].get<std::string>()) / "checkpoint.pt")) continue;
        if (!best || r["q_seed0"].get<double>() > (*best)["q_seed0"].get<double>()) best = &r;
      }
      if (!best) continue;
      const fs::path video = out / "videos" / (a + ".mp4");
      const fs::path dir = (*best)["dir"].get<std::string>();
      const pid_t pid = spawn({"video", "--checkpoint", (dir / "checkpoint.pt").string(), "--sample", "--seed", "0",
                               "--out", video.string()},
                              "/dev/null", dir / "video.log");
      int status = 0;
      waitpid(pid, &status, 0);
      if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
        videos[a] = {
            {"file", video.string()}, {"run", dir.string()}, {"method", (*best)["method"]}, {"seed", (*best)["seed"]}};
      } else {
        videos.erase(a);
        log << "reproduce: no video for " << a << " (see " << (dir / "video.log").string() << ")\n";
      }
    }
  }

  return videos;
}

// The scripted expert on the episodes the policies are evaluated on (seed 0,
// the runs' instances), once per activity: how often its primitives fail,
// beside the policies' (baselines_report reads OUT/expert/ACTIVITY.json).
void run_expert(const ReproduceOptions& o, const EnvConfig& env, std::ostream& log) {
  for (const std::string& a : o.activities) {
    const fs::path file = fs::path(o.out) / "expert" / (a + ".json");
    if (fs::exists(file)) {
      try {
        const nlohmann::json e = read_json_file(file.string()).at(0);
        if (e.at("mode") == o.mode && e.at("episodes_per_seed") == o.eval_episodes) continue;
      } catch (const std::exception&) {
      }  // another table's or unreadable: run it again
    }
    fs::create_directories(file.parent_path());
    log << "reproduce: the scripted expert on " << a << std::endl;
    const fs::path part = file.string() + ".part", elog = file.string() + ".log";
    const pid_t pid =
        spawn({"eval", "--expert", "--activity", a, "--mode", o.mode, "--instances", env.instances, "--seeds", "0-0",
               "--episodes", std::to_string(o.eval_episodes), "--threads", "1", "--json"},
              part, elog);
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
      fs::rename(part, file);
    } else {
      log << "reproduce: the scripted expert failed on " << a << " (see " << elog.string() << ")\n";
    }
  }
}

}  // namespace

nlohmann::json reproduce(const ReproduceOptions& o, std::ostream& log) {
  validate(o);
  const auto start = Clock::now();
  std::vector<Cell> cells = cells_of(o);
  nlohmann::json failures = nlohmann::json::array();
  if (o.cell) {  // a Slurm array task: its run alone
    if (*o.cell >= cells.size())
      throw Error("reproduce: --cell " + std::to_string(*o.cell) + ": the table has " + std::to_string(cells.size()) +
                  " runs");
    return {{"failures", run_cells({cells[*o.cell]}, o, log)}};
  }
  // The rule and instances as the runs' own config builder sets them
  // (defaults, then --set): the same for every cell of a table.
  const EnvConfig env = new_run_config(train_options(cells.front(), o)).env;
  if (!o.report_only) {
    failures = o.launcher == "slurm" ? run_cells_on_slurm(cells, o, log) : run_cells(cells, o, log);
    run_expert(o, env, log);
  }
  for (Cell& c : cells) c.done = cell_done(c, o);
  nlohmann::json result = baselines_report(cells, o, log);
  result["protocol"]["policy_failure"] = {{"rule", env.policy_failure_rule}, {"repeats", env.policy_failure_repeats}};
  result["failures"] = failures;
  result["videos"] = make_videos(result["runs"], o, log);
  result["this_invocation_wall_s"] = std::chrono::duration<double>(Clock::now() - start).count();
  write_text(fs::path(o.out) / "baselines.json", json_text(result, 2) + "\n");
  write_text(fs::path(o.out) / "baselines.md", baselines_markdown(result, o));
  log << "reproduce: " << (cells.size() - result["missing"].size()) << "/" << cells.size() << " runs done; "
      << (fs::path(o.out) / "baselines.md").string() << ", " << (fs::path(o.out) / "baselines.json").string()
      << std::endl;
  return result;
}

}  // namespace chore
