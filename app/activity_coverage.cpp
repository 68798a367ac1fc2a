#include "app/activity_coverage.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <thread>
#include <vector>

#include "base/error.hpp"
#include "env/env.hpp"
#include "tasks/goal.hpp"
#include "tasks/vocabulary.hpp"

namespace fs = std::filesystem;

namespace chore {

std::string failure_cause(const std::string& error) {
  std::string cause = error;
  // A leading location ("path/file.bddl:12:3: ", "path/file.json: ") and the
  // activity and scene an Activity error starts with.
  cause = std::regex_replace(cause, std::regex(R"(^\S+\.(bddl|json):(\d+:\d+:)?\s*)"), "");
  cause = std::regex_replace(cause, std::regex(R"(^activity '[^']*' in scene '[^']*': )"), "");
  cause = std::regex_replace(cause, std::regex(R"(activity '[^']*')"), "activity '_'");
  // Synsets and instances, quoted names and paths, numbers.
  cause = std::regex_replace(cause, std::regex(R"([A-Za-z_]+\.n\.\d+(_\d+)?)"), "_");
  cause = std::regex_replace(cause, std::regex(R"('[^'\s]*[./][^'\s]*')"), "'_'");
  cause = std::regex_replace(cause, std::regex(R"(\b\d+(\.\d+)?\b)"), "N");
  return cause;
}

namespace {

struct Result {
  std::string name, file, stage = "instantiated", error;
  double seconds = 0;        // parse, ground, instantiate
  std::string out_of_reach;  // of an instantiated one: what lies out of the robot's reach ("": none)
};

// Parse and ground (as `activity check`), then reset an Env at the seed;
// then whether the primitives' targets are within the robot's reach (not
// timed: EnvConfig::reachable_instances resamples until they are).
Result run_one(const std::string& file, const Vocabulary& vocabulary, uint64_t seed) {
  Result r;
  r.file = file;
  r.name = fs::path(file).stem() == "problem0" ? fs::path(file).parent_path().filename().string()
                                               : fs::path(file).stem().string();
  const auto start = std::chrono::steady_clock::now();
  try {
    r.stage = "parse";
    const Problem p = load_bddl(file, {.vocabulary = &vocabulary});
    ground_goal(p, synset_type_test(dialect_knowledge_base(p.domain)));
    r.stage = "instantiate";
    EnvConfig config;
    config.activity = file;
    config.observations = {"proprio"};  // no rendering: instantiation alone
    config.reachable_instances = false;
    Env env(config);
    env.reset(seed);
    r.stage = "instantiated";
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.out_of_reach = env.out_of_reach();
  } catch (const Error& e) {
    r.error = e.what();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return r;
}

// A domain definition (predicates), not an activity: BEHAVIOR's folders hold one.
bool is_domain_file(const fs::path& path) {
  std::ifstream in(path);
  std::string head(1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return std::regex_search(head, std::regex(R"(^\s*\(\s*define\s*\(\s*domain\b)"));
}

}  // namespace

nlohmann::json activity_coverage(const CoverageOptions& options, std::ostream& log) {
  if (!fs::is_directory(options.dir)) throw Error("activity coverage: '" + options.dir + "' is not a folder");
  std::vector<std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(options.dir)) {
    if (entry.is_regular_file() && entry.path().extension() == ".bddl" && !is_domain_file(entry.path())) {
      files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) throw Error("activity coverage: no .bddl file under '" + options.dir + "'");

  const Vocabulary vocabulary = load_vocabulary();
  std::vector<Result> results(files.size());
  std::atomic<size_t> next = 0, done = 0;
  auto work = [&] {
    for (size_t i; (i = next++) < files.size();) {
      results[i] = run_one(files[i], vocabulary, options.seed);
      if (const size_t n = ++done; n % 50 == 0 || n == files.size())
        log << "coverage: " << n << "/" << files.size() << std::endl;
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < options.threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();

  nlohmann::json activities = nlohmann::json::array();
  std::map<std::string, std::pair<int, std::string>> causes;  // "stage: cause" -> count, example
  std::map<std::string, std::pair<int, std::string>> reach_causes;
  int parsed = 0, instantiated = 0, within_20s = 0, reachable = 0;
  std::vector<double> seconds;
  for (const Result& r : results) {
    parsed += r.stage != "parse";
    instantiated += r.stage == "instantiated";
    if (r.stage == "instantiated") {
      seconds.push_back(r.seconds);
      within_20s += r.seconds <= 20;
      reachable += r.out_of_reach.empty();
    }
    nlohmann::json a = {{"name", r.name}, {"file", r.file}, {"stage", r.stage}, {"seconds", r.seconds}};
    if (r.stage == "instantiated") a["out_of_reach"] = r.out_of_reach;
    if (!r.out_of_reach.empty()) {
      auto& [count, example] = reach_causes[failure_cause(r.out_of_reach)];
      if (count++ == 0) example = r.name;
    }
    if (!r.error.empty()) {
      const std::string cause = r.stage + ": " + failure_cause(r.error);
      a["error"] = r.error;
      a["cause"] = cause;
      auto& [count, example] = causes[cause];
      if (count++ == 0) example = r.name;
    }
    activities.push_back(std::move(a));
  }
  std::sort(seconds.begin(), seconds.end());
  const auto grouped = [](const std::map<std::string, std::pair<int, std::string>>& causes) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& [cause, entry] : causes)
      out.push_back({{"cause", cause}, {"count", entry.first}, {"example", entry.second}});
    std::stable_sort(out.begin(), out.end(),
                     [](const nlohmann::json& a, const nlohmann::json& b) { return a["count"] > b["count"]; });
    return out;
  };
  return {{"dir", options.dir},
          {"seed", options.seed},
          {"activities", activities},
          {"total", files.size()},
          {"parsed", parsed},
          {"instantiated", instantiated},
          {"instantiated_within_20s", within_20s},
          {"reachable", reachable},
          {"median_seconds", seconds.empty() ? 0.0 : seconds[seconds.size() / 2]},
          {"max_seconds", seconds.empty() ? 0.0 : seconds.back()},
          {"causes", grouped(causes)},
          {"out_of_reach_causes", grouped(reach_causes)}};
}

std::string format_coverage(const nlohmann::json& c) {
  std::ostringstream out;
  const double total = c["total"].get<double>();
  out.precision(1);
  out << std::fixed << "coverage of " << c["dir"].get<std::string>() << ": " << c["total"]
      << " activities; parsed and grounded " << c["parsed"] << " (" << 100 * c["parsed"].get<double>() / total
      << "%), instantiated " << c["instantiated"] << " (" << 100 * c["instantiated"].get<double>() / total
      << "%) at seed " << c["seed"] << ", median " << c["median_seconds"].get<double>() << " s, slowest "
      << c["max_seconds"].get<double>() << " s; " << c["instantiated_within_20s"] << " within 20 s; " << c["reachable"]
      << " with everything the primitives act on within the robot's reach\n";
  const auto list = [&](const char* title, const nlohmann::json& causes) {
    if (!causes.empty()) out << title << ":\n";
    for (const auto& cause : causes) {
      out << "  " << cause["count"] << "  " << cause["cause"].get<std::string>() << "  (e.g. "
          << cause["example"].get<std::string>() << ")\n";
    }
  };
  list("failures by cause", c["causes"]);
  list("instantiated, out of reach", c["out_of_reach_causes"]);
  return out.str();
}

}  // namespace chore
