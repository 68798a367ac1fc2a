#include "app/baselines_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

#include "app/interval_estimates.hpp"
#include "app/plot.hpp"
#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/json_file.hpp"
#include "world/scene.hpp"

namespace chore {
namespace fs = std::filesystem;
namespace {

std::string fixed(double v, int digits = 2) {
  char text[32];
  std::snprintf(text, sizeof text, "%.*f", digits, v);
  return text;
}

// The paper's table (assets/paper/table_a13.json), read once.
const nlohmann::json& paper_table() {
  static const nlohmann::json table = read_json_file(default_assets_dir() + "/paper/table_a13.json");
  return table;
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
  const std::string dirty =
      first_line_of("git -C '" + source + "' status --porcelain --untracked-files=no 2>/dev/null");
  return {{"cpu", cpu.empty() ? "unknown" : cpu},
          {"cores", std::thread::hardware_concurrency()},
          {"memory_gib", std::round(gib * 10) / 10},
          {"commit", commit.empty() ? "unknown" : commit},
          {"local_changes", !dirty.empty()}};
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
nlohmann::json to_json(const Stat& s) {
  return {{"mean", s.mean}, {"std", s.std}, {"runs", s.n}};
}
std::string format(const Stat& s) {
  return s.n == 0 ? "-" : fixed(s.mean) + " ± " + fixed(s.std);
}

// What ends an episode as a policy failure, in the report's words (EnvConfig
// says what each rule counts).
std::string policy_failure_words(const nlohmann::json& p) {
  const std::string repeats = std::to_string(p["repeats"].get<int>()) + "x";
  if (p["rule"] == "none") return "not applied";
  return p["rule"] == "paper" ? "same failed primitive " + repeats : "same invalid action " + repeats;
}

// The evaluations a cell.json may hold: at seed 0 sampling, greedily (cells
// from before issue 53 have none), and over the fresh instances.
constexpr const char* kEvaluations[] = {"seed0", "seed0_greedy", "generalisation"};

}  // namespace

nlohmann::json read_cell_summary(const fs::path& path) {
  nlohmann::json summary = read_json_file(path.string());
  const JsonReader cell(summary, path.string());
  cell.at("spec");
  cell.number("train_wall_s", {0, 1e9});
  cell.number("eval_wall_s", {0, 1e9});
  for (const char* key : kEvaluations) {
    if (std::string(key) == "seed0_greedy" && !summary.contains(key)) continue;
    const JsonReader eval = cell.at(key);
    eval.at("q").number("mean", {0, 1});
    eval.at("success_rate").number("mean", {0, 1});
    for (const char* counts : {"failed_primitives", "episodes_ended_by"}) {
      const JsonReader reader = eval.at(counts);
      const nlohmann::json& value = summary[key][counts];
      if (!value.is_object()) reader.fail("expected an object of counts");
      for (const auto& [name, count] : value.items()) {
        if (!count.is_number_integer() || count.get<int64_t>() < 0 || count.get<int64_t>() > 1000000000) {
          reader.fail("'" + name + "' = " + json_text(count) + " is not a count");
        }
      }
    }
  }
  if (summary.contains("seed0_first10")) cell.at("seed0_first10").number("q", {0, 1});
  return summary;
}

nlohmann::json to_json(const Interval& i) {
  return {{"point", i.point}, {"lo", i.lo}, {"hi", i.hi}};
}

// A bootstrap's seed of its own per quantity, so each reads the same in every report.
uint64_t stream(const std::string& name) {
  return fnv1a(name);
}

// IQM and mean with 95% bootstrap intervals of one cell's runs ({} without runs).
nlohmann::json intervals(const std::vector<double>& runs, const std::string& name) {
  if (runs.empty()) return nullptr;
  return {{"iqm", to_json(bootstrap_interval(runs, interquartile_mean, stream(name + "/iqm")))},
          {"mean", to_json(bootstrap_interval(runs, mean, stream(name + "/mean")))}};
}

// The paper's ordering (Table A.13: RL-Prim.Hist. above RL-Prim. above RL-VMC),
// pair by pair, in the words the intervals allow.
const std::vector<std::pair<std::string, std::string>> kOrdering = {{"rl-prim-hist", "rl-prim"}, {"rl-prim", "rl-vmc"}};

// Fraction of runs above each Q in [0, 1], per method, as a CSV the curve plot reads.
void write_profile(const fs::path& path, const std::vector<double>& runs) {
  std::ofstream csv(path);
  csv << "Q,fraction_of_runs\n";
  std::vector<double> thresholds;
  for (int i = 0; i <= 100; ++i) thresholds.push_back(i / 100.0);
  const std::vector<double> f = performance_profile(runs, thresholds);
  for (size_t i = 0; i < f.size(); ++i) csv << thresholds[i] << "," << f[i] << "\n";
  if (!csv) throw Error(path.string() + ": cannot write the performance profile");
}

nlohmann::json baselines_report(const std::vector<TableCell>& cells, const ReproduceOptions& o, std::ostream& log) {
  const fs::path out(o.out);
  nlohmann::json rows = nlohmann::json::array(), runs = nlohmann::json::array(), missing = nlohmann::json::array();
  std::map<std::pair<std::string, std::string>, std::vector<nlohmann::json>> by;  // (activity, method) -> cells
  double train_s = 0, eval_s = 0;
  for (const TableCell& c : cells) {
    if (!c.done) {
      missing.push_back(c.label());
      continue;
    }
    nlohmann::json summary = read_cell_summary(c.dir / "cell.json");
    summary["dir"] = c.dir.string();
    train_s += summary["train_wall_s"].get<double>();
    eval_s += summary["eval_wall_s"].get<double>();
    runs.push_back({{"activity", c.activity},
                    {"method", c.method},
                    {"seed", c.seed},
                    {"train_wall_s", summary["train_wall_s"]},
                    {"eval_wall_s", summary["eval_wall_s"]},
                    {"q_seed0", summary["seed0"]["q"]["mean"]},
                    {"success_seed0", summary["seed0"]["success_rate"]["mean"]},
                    {"q_seed0_greedy", summary.contains("seed0_greedy") ? summary["seed0_greedy"]["q"]["mean"]
                                                                         : nlohmann::json()},
                    {"q_seed0_first10", summary.contains("seed0_first10") ? summary["seed0_first10"]["q"]
                                                                           : nlohmann::json()},
                    {"q_generalisation", summary["generalisation"]["q"]["mean"]},
                    {"success_generalisation", summary["generalisation"]["success_rate"]["mean"]},
                    {"dir", c.dir.string()}});
    by[{c.activity, c.method}].push_back(std::move(summary));
  }

  // Per (activity, method): mean +- std over training seeds; failures summed.
  for (const std::string& a : o.activities) {
    for (const std::string& m : o.methods) {
      const auto& done = by[{a, m}];
      std::vector<double> q0, s0, qg, sg, q0_greedy, q0_first10;
      int64_t primitives = 0;  // chosen in all evaluation episodes (env steps)
      nlohmann::json failed = nlohmann::json::object(), ended = nlohmann::json::object();
      for (const nlohmann::json& c : done) {
        q0.push_back(c["seed0"]["q"]["mean"]);
        s0.push_back(c["seed0"]["success_rate"]["mean"]);
        qg.push_back(c["generalisation"]["q"]["mean"]);
        sg.push_back(c["generalisation"]["success_rate"]["mean"]);
        if (c.contains("seed0_greedy")) q0_greedy.push_back(c["seed0_greedy"]["q"]["mean"]);
        if (c.contains("seed0_first10")) q0_first10.push_back(c["seed0_first10"]["q"]);
        for (const char* key : kEvaluations) {
          if (!c.contains(key)) continue;
          primitives += c[key].value("env_steps", 0);
          for (const auto& [k, v] : c[key]["failed_primitives"].items()) failed[k] = failed.value(k, 0) + v.get<int>();
          for (const auto& [k, v] : c[key]["episodes_ended_by"].items()) ended[k] = ended.value(k, 0) + v.get<int>();
        }
      }
      const PaperQ paper = paper_q(m, a);
      rows.push_back({{"activity", a},
                      {"method", m},
                      {"runs", done.size()},
                      {"q_seed0", to_json(mean_std(q0))},
                      {"success_seed0", to_json(mean_std(s0))},
                      {"q_seed0_greedy", to_json(mean_std(q0_greedy))},
                      {"q_seed0_first10", to_json(mean_std(q0_first10))},
                      {"q_generalisation", to_json(mean_std(qg))},
                      {"success_generalisation", to_json(mean_std(sg))},
                      {"q_seed0_intervals", intervals(q0, a + "/" + m + "/q_seed0")},
                      {"q_generalisation_intervals", intervals(qg, a + "/" + m + "/q_generalisation")},
                      {"paper_q", {{"mean", paper.mean}, {"std", paper.std}}},
                      {"failed_primitives", failed},
                      {"episodes_ended_by", ended},
                      {"primitives", primitives}});
    }
  }

  // Per activity, the paper's ordering pair by pair: P(first > second) of Q at
  // evaluation seed 0 over runs, its interval and the verdict; and the
  // performance profiles (fraction of runs above each Q) of the methods.
  nlohmann::json orderings = nlohmann::json::array(), profiles = nlohmann::json::object();
  const auto q_runs = [&](const std::string& a, const std::string& m) {
    std::vector<double> q;
    for (const nlohmann::json& c : by[{a, m}]) q.push_back(c["seed0"]["q"]["mean"]);
    return q;
  };
  for (const std::string& a : o.activities) {
    for (const auto& [better, worse] : kOrdering) {
      const std::vector<double> x = q_runs(a, better), y = q_runs(a, worse);
      if (x.empty() || y.empty()) continue;
      const Interval p = probability_of_improvement(x, y, stream(a + "/" + better + ">" + worse));
      orderings.push_back({{"activity", a},
                           {"better", better},
                           {"worse", worse},
                           {"probability_of_improvement", to_json(p)},
                           {"verdict", improvement_verdict(p, std::min(x.size(), y.size()))}});
    }
    PlotOptions plot;
    fs::create_directories(out / "profiles");
    for (const std::string& m : o.methods) {
      const std::vector<double> q = q_runs(a, m);
      if (q.empty()) continue;
      const fs::path csv = out / "profiles" / (a + "_" + m + ".csv");
      write_profile(csv, q);
      plot.runs.push_back(method_title(m) + "=" + csv.string());
    }
    if (plot.runs.empty()) continue;
    plot.out = (out / "profiles" / (a + ".png")).string();
    plot.x = "Q";
    plot.y = "fraction_of_runs";
    plot.count_runs = false;  // a file per method, each over all its runs
    plot.title = activity_title(a) + ": fraction of runs with Q at evaluation seed 0 above each Q";
    plot_curves(plot);
    profiles[a] = plot.out;
  }

  // Curves: Q over training steps per activity, the methods overlaid.
  nlohmann::json curves = nlohmann::json::object();
  fs::create_directories(out / "curves");
  for (const std::string& a : o.activities) {
    PlotOptions plot;
    for (const TableCell& c : cells) {
      const fs::path metrics = c.dir / "metrics.csv";
      // A run with at least one report row (a header alone has nothing to draw).
      if (c.activity == a && c.done && last_metric(metrics, "env_steps", -1) >= 0) {
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

  // Against another table (a protocol study's reference): per activity and
  // method, P(a run here > a run there) of Q at evaluation seed 0.
  nlohmann::json comparisons = nlohmann::json::array();
  if (!o.compare_with.empty()) {
    const fs::path other_file = fs::path(o.compare_with) / "baselines.json";
    const nlohmann::json other = read_json_file(other_file.string());
    const JsonReader reader(other, other_file.string());
    if (!other.is_object() || !other.contains("runs") || !other["runs"].is_array()) reader.fail("no runs");
    for (const std::string& a : o.activities) {
      for (const std::string& m : o.methods) {
        const auto mapped = o.compare_methods.find(m);
        const std::string theirs = mapped == o.compare_methods.end() ? m : mapped->second;
        std::vector<double> y;
        for (size_t i = 0; i < other["runs"].size(); ++i) {
          const JsonReader run = reader.at("runs").at(i);
          if (run.string("activity", "") == a && run.string("method", "") == theirs) y.push_back(run.number("q_seed0"));
        }
        const std::vector<double> x = q_runs(a, m);
        if (x.empty() || y.empty()) continue;
        const Interval p = probability_of_improvement(x, y, stream(a + "/" + m + ">" + o.compare_with + "/" + theirs));
        comparisons.push_back({{"activity", a},
                               {"method", m},
                               {"other_method", theirs},
                               {"mean", mean(x)},
                               {"other_mean", mean(y)},
                               {"probability_of_improvement", to_json(p)},
                               {"verdict", improvement_verdict(p, std::min(x.size(), y.size()))}});
      }
    }
  }

  // The scripted expert's evaluation per activity, where reproduce ran it.
  nlohmann::json expert = nlohmann::json::object();
  for (const std::string& a : o.activities) {
    const fs::path file = out / "expert" / (a + ".json");
    if (!fs::exists(file)) continue;
    expert[a] = reading_json(file.string(), [&]() -> nlohmann::json {
      const nlohmann::json e = read_json_file(file.string()).at(0);
      return {{"q", e.at("q").at("mean")},
              {"success_rate", e.at("success_rate").at("mean")},
              {"primitives", e.at("env_steps")},
              {"episodes", e.at("per_episode").size()},
              {"failed_primitives", e.at("failed_primitives")},
              {"episodes_ended_by", e.at("episodes_ended_by")}};
    });
  }

  nlohmann::json seeds_by_method = nlohmann::json::object();
  for (const std::string& m : o.methods) seeds_by_method[m] = seeds_of(o, m);
  nlohmann::json result = {{"protocol",
                            {{"activities", o.activities},
                             {"methods", o.methods},
                             {"training_seeds", o.seeds},
                             {"training_seeds_by_method", seeds_by_method},
                             {"steps", o.steps},
                             {"mode", o.mode},
                             {"eval_seed", 0},
                             {"eval_episodes", o.eval_episodes},
                             {"eval_policy", "sampled"},
                             {"eval_greedy", o.greedy_eval},
                             {"generalisation_seeds", {o.generalisation_first, o.generalisation_last}},
                             {"generalisation_episodes_per_seed", 1},
                             {"settings", o.settings}}},
                           {"command", o.command_line},
                           {"machine", machine()},
                           {"rows", rows},
                           {"runs", runs},
                           {"missing", missing},
                           {"curves", curves},
                           {"orderings", orderings},
                           {"profiles", profiles},
                           {"expert", expert},
                           {"compared_with", o.compare_with.empty() ? nlohmann::json() : nlohmann::json(o.compare_with)},
                           {"comparisons", comparisons},
                           {"train_wall_s", train_s},
                           {"eval_wall_s", eval_s}};
  return result;
}

std::string method_title(const std::string& method) {
  return paper_table()["methods"].contains(method) ? paper_table()["methods"][method]["title"].get<std::string>()
                                                   : method;
}

std::string activity_title(const std::string& activity) {
  return paper_table()["activities"].value(activity, activity);
}

PaperQ paper_q(const std::string& method, const std::string& activity) {
  const nlohmann::json& methods = paper_table()["methods"];
  if (!methods.contains(method) || !methods[method]["q"].contains(activity)) return {std::nan(""), std::nan("")};
  const nlohmann::json& q = methods[method]["q"][activity];
  return {q.at(0).get<double>(), q.at(1).get<double>()};
}

std::string format_hours(double seconds) {
  char text[32];
  if (seconds >= 3600) {
    std::snprintf(text, sizeof text, "%.2f h", seconds / 3600);
  } else {
    std::snprintf(text, sizeof text, "%.1f min", seconds / 60);
  }
  return text;
}

double last_metric(const fs::path& path, const std::string& column, double fallback) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return fallback;  // a FIFO would block
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
  try {
    return std::stod(values[k]);
  } catch (const std::exception&) {  // a row cut short by a kill
    return fallback;
  }
}

std::string baselines_markdown(const nlohmann::json& r, const ReproduceOptions& o) {
  std::ostringstream md;
  const nlohmann::json& m = r["machine"];
  md << "# BEHAVIOR-1K baselines (Table A.13), reproduced with chore\n\n"
     << "Written by `scripts/reproduce` from the runs under `" << (fs::path(o.out) / "runs" / o.mode).string()
     << "`; do not edit by hand.\n\n"
     << "- Command: `" << r["command"].get<std::string>() << "`\n"
     << (o.report_only ? "- Report written at commit " : "- Code: commit ") << m["commit"].get<std::string>()
     << (m["local_changes"].get<bool>() ? " with local changes" : "")
     << (o.report_only ? " (`--report-only`: the runs are those of earlier invocations, each with its own code)" : "")
     << "\n"
     << "- Machine: " << m["cpu"].get<std::string>() << ", " << m["cores"] << " cores, " << m["memory_gib"]
     << " GiB, no GPU\n"
     << "- Protocol: " << o.steps << " training steps per run, training seeds";
  for (uint64_t s : o.seeds) md << " " << s;
  for (const auto& [method, seeds] : o.seeds_for) {
    md << " (" << method_title(method) << ":";
    for (uint64_t s : seeds) md << " " << s;
    md << ")";
  }
  md << "; " << o.mode << " primitive execution; evaluation at seed 0 (" << o.eval_episodes
     << " episodes) and over seeds " << o.generalisation_first << "-" << o.generalisation_last
     << " (one episode each, instances drawn afresh); Q is the policies' acting by sampling their action "
        "distribution, as in training"
     << (o.greedy_eval ? ", with greedy acting (the most probable primitive) beside it" : "")
     << ". Mean ± std over the training seeds.\n";
  if (!o.settings.empty()) {
    md << "- Settings beyond the paper's (`chore train --set`, ppo.* for RL-Prim. and RL-Prim.Hist., sac.* for "
          "RL-VMC):";
    for (const std::string& s : o.settings) md << " `" << s << "`";
    md << "\n";
  }
  md << "- Wall-clock: training " << format_hours(r["train_wall_s"].get<double>()) << " and evaluation "
     << format_hours(r["eval_wall_s"].get<double>()) << " summed over runs (one core each, " << o.jobs
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
          const size_t seeds = seeds_of(o, method).size();
          if (s.n && s.n < static_cast<int>(seeds)) md << " (" << s.n << " of " << seeds << " seeds)";
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
  if (o.greedy_eval) table("Success score Q at evaluation seed 0, acting greedily", "q_seed0_greedy", false);
  if (o.eval_episodes > 10) {
    table("Success score Q over the first 10 sampled episodes at evaluation seed 0 (chore's protocol before issue 53)",
          "q_seed0_first10", false);
  }
  table("Success score Q over fresh instances (seeds " + std::to_string(o.generalisation_first) + "-" +
            std::to_string(o.generalisation_last) + ")",
        "q_generalisation", false);

  // Interval estimates (Agarwal et al., NeurIPS 2021): what the runs can tell.
  md << "## Interval estimates of Q at evaluation seed 0\n\n"
     << "Interquartile mean (IQM) and mean over training runs, each with its 95% bootstrap confidence interval "
        "(runs resampled with replacement, "
     << kBootstrapReps
     << " times, percentile interval; Agarwal et al., \"Deep Reinforcement Learning at the Edge of the Statistical "
        "Precipice\", NeurIPS 2021, as their rliable library computes them).\n\n| Method |";
  for (const std::string& a : o.activities) md << " " << activity_title(a) << " |";
  md << "\n|---|";
  for (size_t i = 0; i < o.activities.size(); ++i) md << "---|";
  md << "\n";
  const auto bracket = [](const nlohmann::json& i) {
    return fixed(i["point"].get<double>()) + " [" + fixed(i["lo"].get<double>()) + ", " + fixed(i["hi"].get<double>()) +
           "]";
  };
  for (const std::string& method : o.methods) {
    md << "| " << method_title(method) << " |";
    for (const std::string& a : o.activities) {
      for (const nlohmann::json& row : r["rows"]) {
        if (row["activity"] != a || row["method"] != method) continue;
        const nlohmann::json& i = row["q_seed0_intervals"];
        md << " "
           << (i.is_null() ? std::string("not run") : "IQM " + bracket(i["iqm"]) + "; mean " + bracket(i["mean"]))
           << " |";
      }
    }
    md << "\n";
  }
  if (!r["orderings"].empty()) {
    md << "\nThe paper's ordering, pair by pair: the probability that a run of the first method scores a higher Q "
          "at evaluation seed 0 than a run of the second (ties count one half), its 95% bootstrap interval, and "
          "the verdict (holds: the interval lies above 0.5; does not hold: below; else the runs cannot tell; a method "
          "with fewer than 3 runs: too few runs to tell).\n\n"
          "| Activity | Ordering | P(first > second) | Verdict |\n|---|---|---|---|\n";
    for (const nlohmann::json& c : r["orderings"]) {
      md << "| " << activity_title(c["activity"]) << " | " << method_title(c["better"]) << " > "
         << method_title(c["worse"]) << " | " << bracket(c["probability_of_improvement"]) << " | "
         << c["verdict"].get<std::string>() << " |\n";
    }
  }
  if (!r["comparisons"].empty()) {
    md << "\nAgainst the table in `" << r["compared_with"].get<std::string>()
       << "`: the probability that a run here scores a higher Q at evaluation seed 0 than a run there (ties one "
          "half), its 95% bootstrap interval and the verdict, as above.\n\n"
          "| Activity | Method here | Mean Q here | Method there | Mean Q there | P(here > there) | Verdict |\n"
          "|---|---|---|---|---|---|---|\n";
    for (const nlohmann::json& c : r["comparisons"]) {
      md << "| " << activity_title(c["activity"]) << " | " << method_title(c["method"]) << " | "
         << fixed(c["mean"].get<double>()) << " | " << method_title(c["other_method"]) << " | "
         << fixed(c["other_mean"].get<double>()) << " | " << bracket(c["probability_of_improvement"]) << " | "
         << c["verdict"].get<std::string>() << " |\n";
    }
  }
  if (!r["profiles"].empty()) {
    md << "\nPerformance profiles (the fraction of runs whose Q at evaluation seed 0 lies above each Q):\n\n";
    for (const auto& [a, file] : r["profiles"].items()) {
      md << "![" << activity_title(a) << "](" << fs::relative(file.get<std::string>(), o.out).string() << ")\n";
    }
  }
  md << "\n";

  md << "## How episodes ended and which primitives failed (all evaluation episodes, summed over runs)\n\n"
     << "Failures as counts and, in brackets, per 100 primitives chosen; the scripted expert's on the "
        "episodes of evaluation seed 0 (the same instances) where `scripts/reproduce` ran it.\n\n"
     << "| Activity | Method | success | policy failure (" << policy_failure_words(r["protocol"]["policy_failure"])
     << ") | time limit | primitives | motion planning | grasp | place | precondition |\n"
        "|---|---|---|---|---|---|---|---|---|---|\n";
  const auto failure_row = [&](const std::string& activity, const std::string& who, const nlohmann::json& e,
                               const nlohmann::json& f, int64_t primitives) {
    const auto cell = [&](const char* kind) {
      const int64_t n = f.value(kind, int64_t{0});
      return std::to_string(n) + (primitives > 0 ? " (" + fixed(100.0 * n / primitives) + ")" : "");
    };
    md << "| " << activity_title(activity) << " | " << who << " | " << e.value("success", 0) << " | "
       << e.value("policy_failure", 0) << " | " << e.value("time_limit", 0) << " | " << primitives << " | "
       << cell("motion_planning_failure") << " | " << cell("grasp_failure") << " | " << cell("place_failure")
       << " | " << cell("precondition_failure") << " |\n";
  };
  for (const std::string& a : o.activities) {
    for (const nlohmann::json& row : r["rows"]) {
      if (row["activity"] != a || row["runs"].get<int>() == 0) continue;
      failure_row(a, method_title(row["method"]), row["episodes_ended_by"], row["failed_primitives"],
                  row.value("primitives", int64_t{0}));
    }
    if (r.contains("expert") && r["expert"].contains(a)) {
      const nlohmann::json& x = r["expert"][a];
      failure_row(a, "scripted expert", x["episodes_ended_by"], x["failed_primitives"], x["primitives"].get<int64_t>());
    }
  }
  md << "\nRL-VMC acts in the low-level action space: it has no primitives to fail.\n\n";

  md << "## Runs\n\n| Activity | Method | Seed | Train wall-clock | Eval wall-clock | Q seed 0 | Q fresh |\n"
        "|---|---|---|---|---|---|---|\n";
  for (const nlohmann::json& run : r["runs"]) {
    md << "| " << activity_title(run["activity"]) << " | " << method_title(run["method"]) << " | " << run["seed"]
       << " | " << format_hours(run["train_wall_s"].get<double>()) << " | "
       << format_hours(run["eval_wall_s"].get<double>()) << " | " << fixed(run["q_seed0"].get<double>()) << " | "
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
      md << "- " << activity_title(a) << ": [" << fs::relative(v["file"].get<std::string>(), o.out).string() << "]("
         << fs::relative(v["file"].get<std::string>(), o.out).string() << ") (" << method_title(v["method"])
         << ", seed " << v["seed"] << ")\n";
    }
  }
  return md.str();
}

}  // namespace chore
