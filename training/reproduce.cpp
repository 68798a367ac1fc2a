#include "training/reproduce.hpp"

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

#include "base/error.hpp"
#include "tasks/activity.hpp"
#include "training/checkpoint.hpp"
#include "training/plot.hpp"
#include "training/train_command.hpp"
#include "training/trainer.hpp"

extern char** environ;

namespace chore {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;

const std::array<std::string, 3> kActivities = {"store_decoration", "collect_trash", "clean_table"};
const std::array<std::string, 3> kMethods = {"rl-vmc", "rl-prim", "rl-prim-hist"};

std::string method_title(const std::string& method) {
  if (method == "rl-vmc") return "RL-VMC";
  if (method == "rl-prim") return "RL-Prim.";
  if (method == "rl-prim-hist") return "RL-Prim.Hist.";
  return method;
}

std::string activity_title(const std::string& activity) {
  if (activity == "store_decoration") return "StoreDecoration";
  if (activity == "collect_trash") return "CollectTrash";
  if (activity == "clean_table") return "CleanTable";
  return activity;
}

std::string fixed(double v, int digits = 2) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

std::string hours(double seconds) {
  char text[32];
  if (seconds >= 3600) {
    std::snprintf(text, sizeof text, "%.2f h", seconds / 3600);
  } else {
    std::snprintf(text, sizeof text, "%.1f min", seconds / 60);
  }
  return text;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  if (!in) throw Error(path.string() + ": cannot read");
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(path.string() + ": not JSON (" + e.what() + ")");
  }
}

// Written whole or not at all: a stop mid-write leaves the old file.
void write_text(const fs::path& path, const std::string& text) {
  const fs::path tmp = path.string() + ".tmp";
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

// The first line a command prints, or "" (machine and commit for the report).
std::string first_line_of(const std::string& command) {
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    char buffer[256];
    if (fgets(buffer, sizeof buffer, p)) out = buffer;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

nlohmann::json machine() {
  const std::string cpu = first_line_of("grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ *//'");
  const std::string memory_kb = first_line_of("grep -m1 MemTotal /proc/meminfo | tr -s ' ' | cut -d' ' -f2");
  const double gib = memory_kb.empty() ? 0 : std::stod(memory_kb) / (1024.0 * 1024.0);
  const std::string source = fs::path(CHORE_SOURCE_DIR).string();
  const std::string commit = first_line_of("git -C '" + source + "' rev-parse --short HEAD 2>/dev/null");
  const std::string dirty = first_line_of("git -C '" + source + "' status --porcelain --untracked-files=no 2>/dev/null");
  return {{"cpu", cpu.empty() ? "unknown" : cpu},
          {"cores", std::thread::hardware_concurrency()},
          {"memory_gib", std::round(gib * 10) / 10},
          {"commit", commit.empty() ? "unknown" : commit},
          {"local_changes", !dirty.empty()}};
}

// One (activity, method, training seed) of the table.
struct Cell {
  std::string activity, method;
  uint64_t seed = 0;
  fs::path dir;
  std::string label() const { return activity + " " + method + " seed " + std::to_string(seed); }
};

// The --set settings that reach `method`'s trainer.
std::vector<std::string> settings_for(const std::string& method, const std::vector<std::string>& settings) {
  std::vector<std::string> kept;
  for (const std::string& s : settings) {
    if (!s.starts_with(uses_sac(method) ? "ppo." : "sac.")) kept.push_back(s);
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
  nlohmann::json spec = {{"activity", c.activity}, {"method", c.method}, {"seed", c.seed}, {"steps", o.steps},
                         {"mode", o.mode}, {"eval_episodes", o.eval_episodes}, {"eval_policy", "sampled"},
                         {"generalisation_seeds", {o.generalisation_first, o.generalisation_last}}};
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
    return read_json(path)["spec"] == cell_spec(c, o);
  } catch (const Error&) {
    return false;  // unreadable: run it again
  }
}

// The last row's value of `column` in a metrics.csv, or `fallback`.
double last_metric(const fs::path& path, const std::string& column, double fallback) {
  std::ifstream in(path);
  std::string header, line, last;
  if (!std::getline(in, header)) return fallback;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  if (last.empty()) return fallback;
  std::vector<std::string> names, values;
  for (std::stringstream s(header); std::getline(s, line, ',');) names.push_back(line);
  for (std::stringstream s(last); std::getline(s, line, ',');) values.push_back(line);
  const auto it = std::find(names.begin(), names.end(), column);
  const size_t k = static_cast<size_t>(it - names.begin());
  if (it == names.end() || k >= values.size()) return fallback;
  return std::stod(values[k]);
}

// A child process of this executable: `args` after the program name, stdout
// to `out` (truncated) and stderr appended to `log`.
pid_t spawn(const std::vector<std::string>& args, const fs::path& out, const fs::path& log) {
  static const std::string self = fs::read_symlink("/proc/self/exe").string();
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
  const int error = posix_spawn(&pid, self.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw Error("reproduce: cannot start " + self + ": " + std::strerror(error));
  return pid;
}

// A cell's work, one child after another: train (or resume), evaluate at the
// paper's seed, evaluate over the generalisation seeds, then cell.json.
class CellRun {
 public:
  CellRun(Cell cell, const ReproduceOptions& o) : cell_(std::move(cell)), o_(o) {}
  const Cell& cell() const { return cell_; }

  // Starts the next child; false when the cell has nothing left to run.
  // `what` says what the child does.
  bool start_next(std::string& what) {
    const fs::path log = cell_.dir / "train.log";
    const std::string range = std::to_string(o_.generalisation_first) + "-" + std::to_string(o_.generalisation_last);
    const std::string steps = std::to_string(o_.steps);
    switch (stage_++) {
      case 0:
        what = "training (" + log.string() + ")";
        started_ = Clock::now();
        if (fs::exists(cell_.dir / "checkpoint.pt")) {
          pid_ = spawn({"train", "--resume", cell_.dir.string(), "--steps", steps}, "/dev/null", log);
        } else {
          const TrainOptions t = train_options(cell_, o_);
          std::vector<std::string> args = {"train", "--activity", t.activity, "--baseline", t.baseline, "--seed",
                                           std::to_string(t.seed), "--steps", steps, "--mode", t.mode,
                                           "--threads", std::to_string(t.threads), "--out", t.out};
          for (const std::string& setting : t.settings) args.insert(args.end(), {"--set", setting});
          pid_ = spawn(args, "/dev/null", log);
        }
        return true;
      case 1:
        what = "evaluating at seed 0";
        eval_started_ = Clock::now();
        evaluate("0-0", o_.eval_episodes, "eval_seed0.json");
        return true;
      case 2:
        what = "evaluating on seeds " + range;
        fs::rename(cell_.dir / "eval_seed0.json.part", cell_.dir / "eval_seed0.json");
        evaluate(range, 1, "eval_generalisation.json");
        return true;
      case 3: {
        fs::rename(cell_.dir / "eval_generalisation.json.part", cell_.dir / "eval_generalisation.json");
        nlohmann::json summary = {
            {"spec", cell_spec(cell_, o_)},
            {"train_wall_s", last_metric(cell_.dir / "metrics.csv", "wall_s", 0.0)},
            {"eval_wall_s", std::chrono::duration<double>(Clock::now() - eval_started_).count()},
            {"seed0", read_json(cell_.dir / "eval_seed0.json").at(0)},
            {"generalisation", read_json(cell_.dir / "eval_generalisation.json").at(0)}};
        // The per-episode lists stay in the eval files; the summary keeps the totals.
        for (const char* key : {"seed0", "generalisation"}) {
          summary[key].erase("per_episode");
          summary[key].erase("per_seed");
        }
        write_text(cell_.dir / "cell.json", summary.dump(2) + "\n");
        return false;
      }
      default:
        return false;
    }
  }
  pid_t pid() const { return pid_; }
  // The log of the child now running, for a failure's report.
  fs::path current_log() const { return cell_.dir / (stage_ <= 1 ? "train.log" : "eval.log"); }
  double seconds() const { return std::chrono::duration<double>(Clock::now() - started_).count(); }

 private:
  // `chore eval` of the run's checkpoint, sampling, its JSON to `file`.part.
  void evaluate(const std::string& seeds, int episodes, const std::string& file) {
    pid_ = spawn({"eval", "--checkpoint", (cell_.dir / "checkpoint.pt").string(), "--sample", "--seeds", seeds,
                  "--episodes", std::to_string(episodes), "--threads", "1", "--json"},
                 cell_.dir / (file + ".part"), cell_.dir / "eval.log");
  }

  Cell cell_;
  const ReproduceOptions& o_;
  int stage_ = 0;
  pid_t pid_ = -1;
  Clock::time_point started_, eval_started_;
};

void validate(const ReproduceOptions& o) {
  if (o.activities.empty() || o.methods.empty() || o.seeds.empty()) {
    throw Error("reproduce: give at least one activity, method and seed");
  }
  for (const std::string& m : o.methods) {
    if (std::find(kMethods.begin(), kMethods.end(), m) == kMethods.end()) {
      throw Error("reproduce: unknown method '" + m + "' (rl-vmc, rl-prim, rl-prim-hist)");
    }
  }
  for (const std::string& a : o.activities) {
    if (a.empty() || a.find('/') != std::string::npos || a.ends_with(".bddl")) {
      throw Error("reproduce: '" + a + "': give activities by name (a run folder is named after it)");
    }
    resolve_activity_path(a);  // throws naming the known ones
  }
  if (o.mode != "physical" && o.mode != "symbolic") throw Error("reproduce: --mode is physical or symbolic");
  if (o.steps < 1) throw Error("reproduce: --steps must be at least 1");
  if (o.jobs < 1) throw Error("reproduce: --jobs must be at least 1");
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
      for (uint64_t s : o.seeds) {
        cells.push_back({a, m, s, fs::path(o.out) / "runs" / o.mode / a / (m + "_seed" + std::to_string(s))});
      }
    }
  }
  return cells;
}

// Runs the cells that are not done, `jobs` at a time; returns the failures.
nlohmann::json run_cells(const std::vector<Cell>& cells, const ReproduceOptions& o, std::ostream& log) {
  std::deque<Cell> todo;
  for (const Cell& c : cells) {
    if (cell_done(c, o)) {
      log << "reproduce: " << c.label() << ": done already (" << (c.dir / "cell.json").string() << ")\n";
    } else {
      if (fs::exists(c.dir / "checkpoint.pt")) check_resumable(c, o);
      todo.push_back(c);
    }
  }
  nlohmann::json failures = nlohmann::json::array();
  std::map<pid_t, std::unique_ptr<CellRun>> running;
  const size_t total = todo.size();
  size_t finished = 0;
  while (!todo.empty() || !running.empty()) {
    while (!todo.empty() && running.size() < static_cast<size_t>(o.jobs)) {
      auto run = std::make_unique<CellRun>(todo.front(), o);
      todo.pop_front();
      fs::create_directories(run->cell().dir);
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
    log << "reproduce: " << run->cell().label() << ": done in " << hours(run->seconds()) << " (" << finished
        << "/" << total << ")" << std::endl;
  }
  return failures;
}

struct Stat {
  double mean = 0, std = 0;
  int n = 0;
};
Stat mean_std(const std::vector<double>& v) {
  Stat s;
  s.n = static_cast<int>(v.size());
  if (v.empty()) return s;
  for (double x : v) s.mean += x;
  s.mean /= static_cast<double>(v.size());
  for (double x : v) s.std += (x - s.mean) * (x - s.mean);
  s.std = std::sqrt(s.std / static_cast<double>(v.size()));  // population std, over training seeds
  return s;
}
nlohmann::json to_json(const Stat& s) { return {{"mean", s.mean}, {"std", s.std}, {"runs", s.n}}; }
std::string format(const Stat& s) { return s.n == 0 ? "-" : fixed(s.mean) + " ± " + fixed(s.std); }

// The table and everything around it, from the cells done.
nlohmann::json report(const std::vector<Cell>& cells, const ReproduceOptions& o, const nlohmann::json& failures,
                      double wall_s, std::ostream& log) {
  const fs::path out(o.out);
  nlohmann::json rows = nlohmann::json::array(), runs = nlohmann::json::array(), missing = nlohmann::json::array();
  std::map<std::pair<std::string, std::string>, std::vector<nlohmann::json>> by;  // (activity, method) -> cells
  double train_s = 0, eval_s = 0;
  for (const Cell& c : cells) {
    if (!cell_done(c, o)) {
      missing.push_back(c.label());
      continue;
    }
    nlohmann::json summary = read_json(c.dir / "cell.json");
    summary["dir"] = c.dir.string();
    train_s += summary["train_wall_s"].get<double>();
    eval_s += summary["eval_wall_s"].get<double>();
    runs.push_back({{"activity", c.activity}, {"method", c.method}, {"seed", c.seed},
                    {"train_wall_s", summary["train_wall_s"]}, {"eval_wall_s", summary["eval_wall_s"]},
                    {"q_seed0", summary["seed0"]["q"]["mean"]},
                    {"success_seed0", summary["seed0"]["success_rate"]["mean"]},
                    {"q_generalisation", summary["generalisation"]["q"]["mean"]},
                    {"success_generalisation", summary["generalisation"]["success_rate"]["mean"]},
                    {"dir", c.dir.string()}});
    by[{c.activity, c.method}].push_back(std::move(summary));
  }

  // Per (activity, method): mean +- std over training seeds; failures summed.
  for (const std::string& a : o.activities) {
    for (const std::string& m : o.methods) {
      const auto& done = by[{a, m}];
      std::vector<double> q0, s0, qg, sg;
      nlohmann::json failed = nlohmann::json::object(), ended = nlohmann::json::object();
      for (const nlohmann::json& c : done) {
        q0.push_back(c["seed0"]["q"]["mean"]);
        s0.push_back(c["seed0"]["success_rate"]["mean"]);
        qg.push_back(c["generalisation"]["q"]["mean"]);
        sg.push_back(c["generalisation"]["success_rate"]["mean"]);
        for (const char* key : {"seed0", "generalisation"}) {
          for (const auto& [k, v] : c[key]["failed_primitives"].items()) failed[k] = failed.value(k, 0) + v.get<int>();
          for (const auto& [k, v] : c[key]["episodes_ended_by"].items()) ended[k] = ended.value(k, 0) + v.get<int>();
        }
      }
      const PaperQ paper = paper_q(m, a);
      rows.push_back({{"activity", a}, {"method", m}, {"runs", done.size()},
                      {"q_seed0", to_json(mean_std(q0))}, {"success_seed0", to_json(mean_std(s0))},
                      {"q_generalisation", to_json(mean_std(qg))},
                      {"success_generalisation", to_json(mean_std(sg))},
                      {"paper_q", {{"mean", paper.mean}, {"std", paper.std}}},
                      {"failed_primitives", failed}, {"episodes_ended_by", ended}});
    }
  }

  // Curves: Q over training steps per activity, the methods overlaid.
  nlohmann::json curves = nlohmann::json::object();
  fs::create_directories(out / "curves");
  for (const std::string& a : o.activities) {
    PlotOptions plot;
    for (const Cell& c : cells) {
      const fs::path metrics = c.dir / "metrics.csv";
      // A run with at least one report row (a header alone has nothing to draw).
      if (c.activity == a && cell_done(c, o) && last_metric(metrics, "env_steps", -1) >= 0) {
        plot.runs.push_back(method_title(c.method) + "=" + metrics.string());
      }
    }
    if (plot.runs.empty()) continue;
    plot.out = (out / "curves" / (a + ".png")).string();
    plot.y = "mean_q";
    plot.title = activity_title(a) + ": success score Q while training (" + o.mode + " primitives)";
    try {
      plot_curves(plot);
      curves[a] = plot.out;
    } catch (const Error& e) {
      log << "reproduce: no curve for " << a << ": " << e.what() << "\n";
    }
  }

  // Videos: per activity, the run with the best Q at seed 0 whose checkpoint is here;
  // the other activities keep the videos an earlier invocation made.
  nlohmann::json videos = fs::exists(out / "baselines.json")
                              ? read_json(out / "baselines.json").value("videos", nlohmann::json::object())
                              : nlohmann::json::object();
  // ...while their file and their run are still here (a run moved away takes its video's entry along).
  for (auto it = videos.begin(); it != videos.end();) {
    const bool here = fs::exists(it->value("file", "")) && fs::exists(fs::path(it->value("run", "")) / "cell.json");
    it = here ? std::next(it) : videos.erase(it);
  }
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
        videos[a] = {{"file", video.string()}, {"run", dir.string()}, {"method", (*best)["method"]},
                     {"seed", (*best)["seed"]}};
      } else {
        videos.erase(a);
        log << "reproduce: no video for " << a << " (see " << (dir / "video.log").string() << ")\n";
      }
    }
  }

  nlohmann::json result = {
      {"protocol", {{"activities", o.activities}, {"methods", o.methods}, {"training_seeds", o.seeds},
                    {"steps", o.steps}, {"mode", o.mode}, {"eval_seed", 0}, {"eval_episodes", o.eval_episodes},
                    {"eval_policy", "sampled"},
                    {"generalisation_seeds", {o.generalisation_first, o.generalisation_last}},
                    {"generalisation_episodes_per_seed", 1}, {"settings", o.settings}}},
      {"command", o.command_line},
      {"machine", machine()},
      {"rows", rows},
      {"runs", runs},
      {"missing", missing},
      {"failures", failures},
      {"curves", curves},
      {"videos", videos},
      {"train_wall_s", train_s},
      {"eval_wall_s", eval_s},
      {"this_invocation_wall_s", wall_s}};
  write_text(out / "baselines.json", result.dump(2) + "\n");
  return result;
}

std::string markdown(const nlohmann::json& r, const ReproduceOptions& o) {
  std::ostringstream md;
  const nlohmann::json& m = r["machine"];
  md << "# BEHAVIOR-1K baselines (Table A.13), reproduced with chore\n\n"
     << "Written by `scripts/reproduce` from the runs under `" << (fs::path(o.out) / "runs" / o.mode).string()
     << "`; do not edit by hand.\n\n"
     << "- Command: `" << r["command"].get<std::string>() << "`\n"
     << "- Code: commit " << m["commit"].get<std::string>()
     << (m["local_changes"].get<bool>() ? " with local changes" : "") << "\n"
     << "- Machine: " << m["cpu"].get<std::string>() << ", " << m["cores"] << " cores, " << m["memory_gib"]
     << " GiB, no GPU\n"
     << "- Protocol: " << o.steps << " training steps per run, training seeds";
  for (uint64_t s : o.seeds) md << " " << s;
  md << "; " << o.mode << " primitive execution; evaluation at seed 0 (" << o.eval_episodes
     << " episodes) and over seeds " << o.generalisation_first << "-" << o.generalisation_last
     << " (one episode each, instances never trained on); the policies act by sampling their action distribution, as in "
        "training. Mean ± std over the training seeds.\n";
  if (!o.settings.empty()) {
    md << "- Settings beyond the paper's (`chore train --set`, ppo.* for RL-Prim. and RL-Prim.Hist., sac.* for RL-VMC):";
    for (const std::string& s : o.settings) md << " `" << s << "`";
    md << "\n";
  }
  md << "- Wall-clock: training " << hours(r["train_wall_s"].get<double>()) << " and evaluation "
     << hours(r["eval_wall_s"].get<double>()) << " summed over runs (one core each, " << o.jobs
     << " at a time)\n\n";

  const auto table = [&](const std::string& title, const std::string& key, bool with_paper) {
    md << "## " << title << "\n\n| Method |";
    for (const std::string& a : o.activities) md << " " << activity_title(a) << " |";
    md << "\n|---|";
    for (size_t i = 0; i < o.activities.size(); ++i) md << "---|";
    md << "\n";
    for (const std::string& method : o.methods) {
      md << "| " << method_title(method) << " |";
      for (const std::string& a : o.activities) {
        for (const nlohmann::json& row : r["rows"]) {
          if (row["activity"] != a || row["method"] != method) continue;
          Stat s{row[key]["mean"].get<double>(), row[key]["std"].get<double>(), row[key]["runs"].get<int>()};
          md << " " << (s.n ? "**" + format(s) + "**" : std::string("not run"));
          if (s.n && s.n < static_cast<int>(o.seeds.size())) md << " (" << s.n << " of " << o.seeds.size() << " seeds)";
          if (with_paper && row["paper_q"]["mean"].is_number() && !std::isnan(row["paper_q"]["mean"].get<double>())) {
            md << " (paper " << fixed(row["paper_q"]["mean"].get<double>()) << " ± "
               << fixed(row["paper_q"]["std"].get<double>()) << ")";
          }
          md << " |";
        }
      }
      md << "\n";
    }
    md << "\n";
  };
  table("Success score Q at evaluation seed 0 (chore, and the paper's Table A.13)", "q_seed0", true);
  table("Success rate at evaluation seed 0", "success_seed0", false);
  table("Success score Q over fresh instances (seeds " + std::to_string(o.generalisation_first) + "-" +
            std::to_string(o.generalisation_last) + ")",
        "q_generalisation", false);

  md << "## How episodes ended and which primitives failed (all evaluation episodes, summed over runs)\n\n"
     << "| Activity | Method | success | policy failure (same invalid action 3x) | time limit | motion planning "
        "| grasp | place | precondition |\n|---|---|---|---|---|---|---|---|---|\n";
  for (const nlohmann::json& row : r["rows"]) {
    if (row["runs"].get<int>() == 0) continue;
    const nlohmann::json& e = row["episodes_ended_by"];
    const nlohmann::json& f = row["failed_primitives"];
    md << "| " << activity_title(row["activity"]) << " | " << method_title(row["method"]) << " | "
       << e.value("success", 0) << " | " << e.value("policy_failure", 0) << " | " << e.value("time_limit", 0)
       << " | " << f.value("motion_planning_failure", 0) << " | " << f.value("grasp_failure", 0) << " | "
       << f.value("place_failure", 0) << " | " << f.value("precondition_failure", 0) << " |\n";
  }
  md << "\nRL-VMC acts in the low-level action space: it has no primitives to fail.\n\n";

  md << "## Runs\n\n| Activity | Method | Seed | Train wall-clock | Eval wall-clock | Q seed 0 | Q fresh |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const nlohmann::json& run : r["runs"]) {
    md << "| " << activity_title(run["activity"]) << " | " << method_title(run["method"]) << " | "
       << run["seed"] << " | " << hours(run["train_wall_s"].get<double>()) << " | "
       << hours(run["eval_wall_s"].get<double>()) << " | " << fixed(run["q_seed0"].get<double>()) << " | "
       << fixed(run["q_generalisation"].get<double>()) << " |\n";
  }
  if (!r["missing"].empty()) {
    md << "\nNot done yet (run `scripts/reproduce` with the same options to continue):";
    for (const auto& c : r["missing"]) md << " " << c.get<std::string>() << ";";
    md << "\n";
  }
  if (!r["curves"].empty()) {
    md << "\n## Learning curves\n\n";
    for (const auto& [a, file] : r["curves"].items()) {
      md << "![" << activity_title(a) << "](" << fs::relative(file.get<std::string>(), o.out).string() << ")\n";
    }
  }
  if (!r["videos"].empty()) {
    md << "\n## Videos (the best run's policy at evaluation seed 0)\n\n";
    for (const auto& [a, v] : r["videos"].items()) {
      md << "- " << activity_title(a) << ": [" << fs::relative(v["file"].get<std::string>(), o.out).string()
         << "](" << fs::relative(v["file"].get<std::string>(), o.out).string() << ") ("
         << method_title(v["method"]) << ", seed " << v["seed"] << ")\n";
    }
  }
  return md.str();
}

}  // namespace

PaperQ paper_q(const std::string& method, const std::string& activity) {
  // Table A.13: StoreDecoration, CollectTrash, CleanTable.
  static const std::map<std::string, std::array<PaperQ, 3>> table = {
      {"rl-vmc", {{{0.0, 0.0}, {0.0, 0.0}, {0.0, 0.0}}}},
      {"rl-prim", {{{0.50, 0.05}, {0.49, 0.04}, {0.77, 0.08}}}},
      {"rl-prim-hist", {{{0.59, 0.03}, {0.68, 0.02}, {0.88, 0.02}}}}};
  const auto a = std::find(kActivities.begin(), kActivities.end(), activity);
  const auto m = table.find(method);
  if (a == kActivities.end() || m == table.end()) return {std::nan(""), std::nan("")};
  return m->second[static_cast<size_t>(a - kActivities.begin())];
}

nlohmann::json reproduce(const ReproduceOptions& o, std::ostream& log) {
  validate(o);
  const auto start = Clock::now();
  const std::vector<Cell> cells = cells_of(o);
  nlohmann::json failures = nlohmann::json::array();
  if (!o.report_only) failures = run_cells(cells, o, log);
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();
  nlohmann::json result = report(cells, o, failures, wall, log);
  write_text(fs::path(o.out) / "baselines.md", markdown(result, o));
  log << "reproduce: " << (cells.size() - result["missing"].size()) << "/" << cells.size() << " runs done; "
      << (fs::path(o.out) / "baselines.md").string() << ", " << (fs::path(o.out) / "baselines.json").string()
      << std::endl;
  return result;
}

}  // namespace chore
