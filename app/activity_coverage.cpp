#include "app/activity_coverage.hpp"

#include <sys/wait.h>
#include <unistd.h>
#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "app/activity_commands.hpp"
#include "app/activity_solve.hpp"
#include "app/png.hpp"
#include "base/error.hpp"
#include "base/json_file.hpp"
#include "base/random.hpp"
#include "base/temp_file.hpp"
#include "env/env.hpp"
#include "env/vector_env.hpp"
#include "planner/reachability.hpp"
#include "tasks/activity_check.hpp"
#include "tasks/goal.hpp"
#include "tasks/vocabulary.hpp"

namespace fs = std::filesystem;

namespace chore {

std::string failure_cause(const std::string& error) {
  // std::regex recurses along a match: a bound first (an error may quote a
  // 40,000-character token), well past what a cause needs to be told apart.
  std::string cause = error.substr(0, kMaxCauseReadChars);
  // A leading location ("path/file.bddl:12:3: ", "path/file.json: ") and the
  // activity and scene an Activity error starts with.
  cause = std::regex_replace(cause, std::regex(R"(^\S+\.(bddl|json):(\d+:\d+:)?\s*)"), "");
  cause = std::regex_replace(cause, std::regex(R"(^activity '[^']*' in scene '[^']*': )"), "");
  cause = std::regex_replace(cause, std::regex(R"(activity '[^']*')"), "activity '_'");
  // Synsets and instances, quoted names and paths, numbers.
  cause = std::regex_replace(cause, std::regex(R"([A-Za-z_]+\.n\.\d+(_\d+)?)"), "_");
  cause = std::regex_replace(cause, std::regex(R"('[^'\s]*[./][^'\s]*')"), "'_'");
  cause = std::regex_replace(cause, std::regex(R"('[a-z][a-z_]*_\d+')"), "'_'");  // scene objects: 'sink_1'
  cause = std::regex_replace(cause, std::regex(R"(\b\d+(\.\d+)?\b)"), "N");
  return cause.substr(0, kMaxCauseChars);
}

namespace {

// BEHAVIOR-1K's NAME/problem0.bddl is NAME; any other file its stem.
std::string activity_name(const std::string& file) {
  return fs::path(file).stem() == "problem0" ? fs::path(file).parent_path().filename().string()
                                             : fs::path(file).stem().string();
}

struct Result {
  std::string name, file, stage = "instantiated", error;
  double seconds = 0;           // parse, ground, instantiate
  std::string out_of_reach;     // of an instantiated one: what lies out of the robot's reach ("": none)
  bool ran = false;             // and it ran in a VectorEnv, from the same instance
  bool ran_primitives = false;  // and random primitives ran on it
  cv::Mat picture;              // for the contact sheet
  // Of a parsed one: its goal literals some primitives and rules could make
  // hold (planner/reachability.hpp), those none can by predicate, and its
  // future objects no rule makes or none can make here.
  nlohmann::json goal_reach;
  nlohmann::json solve;  // of an instantiated one, with CoverageOptions::solve (activity_solve.hpp)
};

// Instantiated, whether or not a later stage ("run", "primitives", "solve") failed.
bool was_instantiated(const Result& r) {
  return r.stage == "instantiated" || r.stage == "run" || r.stage == "primitives" || r.stage == "solve";
}

// An instance's head camera and view from above; a solved activity's final
// state larger, its head camera showing what the last primitive acted on.
constexpr int kSheetHead = 64, kSheetTop = 128, kSheetSolved = 160, kSheetLabel = 12, kSheetColumns = 16;

// The pictures (all one size) in a grid, each under its activity's name.
// None (nothing instantiated, or solved): no sheet, said in the log, the
// report kept.
void write_contact_sheet(const std::string& path, const std::vector<Result>& results, bool solved, std::ostream& log) {
  std::vector<const Result*> shown;
  for (const Result& r : results) {
    if (!r.picture.empty()) shown.push_back(&r);
  }
  if (shown.empty()) {
    log << "activity " << (solved ? "solve" : "coverage") << ": no activity " << (solved ? "solved" : "instantiated")
        << ", no contact sheet written to " << path << std::endl;
    return;
  }
  const int width = shown[0]->picture.cols, picture_height = shown[0]->picture.rows,
            height = picture_height + kSheetLabel;
  const int columns = std::min<int>(kSheetColumns, static_cast<int>(shown.size()));
  const int rows = (static_cast<int>(shown.size()) + columns - 1) / columns;
  cv::Mat sheet(rows * height, columns * width, CV_8UC3, cv::Scalar(255, 255, 255));
  for (size_t i = 0; i < shown.size(); ++i) {
    const int x = static_cast<int>(i % columns) * width, y = static_cast<int>(i / columns) * height;
    shown[i]->picture.copyTo(sheet(cv::Rect(x, y + kSheetLabel, width, picture_height)));
    cv::putText(sheet, shown[i]->name.substr(0, 34), {x + 2, y + kSheetLabel - 3}, cv::FONT_HERSHEY_PLAIN, 0.7,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  write_png(path, sheet, "contact sheet");
}

// A VectorEnv (of one env: the next would take the next seed, another
// instance), reset at `seed`: it must start bit for bit as `env` did (the
// same seed, the same instance, from a second build of the scene), then take
// `steps` seeded random low-level actions with finite rewards and Q in [0, 1].
void run_in_vector_env(const EnvConfig& config, const Env& env, uint64_t seed, int steps) {
  VectorEnvConfig vector;
  vector.env = config;
  vector.num_envs = 1;
  VectorEnv envs(vector);
  envs.reset(seed);
  const mjModel* m = env.world().model();
  const mjData *a = env.world().data(), *b = envs.state(0).world().data();
  const auto same = [](double x, double y) { return std::memcmp(&x, &y, sizeof x) == 0; };
  if (envs.state(0).world().model()->nq != m->nq || !std::equal(a->qpos, a->qpos + m->nq, b->qpos, same))
    throw Error("the same seed gave another instance in a VectorEnv");
  const Space& space = envs.single_action_space();
  const size_t size = space.element_count();
  Rng rng(seed);
  std::vector<float> actions(size);
  for (int step = 0; step < steps; ++step) {
    for (float& x : actions) x = static_cast<float>(uniform(rng, space.low, space.high));
    const Batch batch = envs.step(actions);
    for (int i = 0; i < batch.size(); ++i) {
      const Info& info = batch.infos[i];
      if (!std::isfinite(batch.rewards[i]) || info.q < 0 || info.q > 1)
        throw Error("step " + std::to_string(step) + ": reward " + std::to_string(batch.rewards[i]) + ", Q " +
                    std::to_string(info.q));
    }
  }
}

// `steps` seeded random actions of the primitive action space, executed
// physically (motion planning, grasps, placements in MuJoCo) from the
// instance at `seed`: failed primitives are outcomes, an exception is not.
void run_primitives(EnvConfig config, uint64_t seed, int steps) {
  config.action_space = "primitives";
  config.primitive_mode = ExecutionMode::physical;
  Env env(config);
  env.reset(seed);
  const int64_t n = env.action_space().n;
  if (n <= 0) return;  // nothing in the activity for a primitive to act on
  Rng rng(seed);
  for (int step = 0; step < steps; ++step) {
    const float action = static_cast<float>(uniform_index(rng, static_cast<int>(n)));
    const auto result = env.step({&action, 1});
    if (!std::isfinite(result.reward) || result.info.q < 0 || result.info.q > 1)
      throw Error("primitive step " + std::to_string(step) + ": reward " + std::to_string(result.reward) + ", Q " +
                  std::to_string(result.info.q));
    if (result.terminated || result.truncated) env.reset(seed + step + 1);
  }
}

// What the primitives and the knowledge base's transition rules can make of
// the goal, by the planner's relaxed reachability.
nlohmann::json goal_reach_json(const CheckedActivity& checked) {
  const TransitionRules& rules = behavior_transition_rules();
  const auto kb = dialect_knowledge_base(checked.problem.domain);
  const SymbolicProblem problem = symbolic_problem(checked.problem, *kb, rules);
  const GoalReach g = goal_reach(problem, reachability(problem), checked.goal, *kb, rules);
  return {{"literals", g.literals},
          {"achievable", g.achievable},
          {"future", g.future},
          {"unachievable", g.unachievable},
          {"future_without_rule", g.future_without_rule},
          {"future_unreachable", g.future_unreachable}};
}

// Parse and ground (as `activity check`), then reset an Env at the seed;
// then whether the primitives' targets are within the robot's reach (not
// timed: EnvConfig::reachable_instances resamples until they are); then the
// options' low-level and primitive steps.
Result run_one(const std::string& file, const Vocabulary& vocabulary, const CoverageOptions& options) {
  Result r;
  r.file = file;
  r.name = activity_name(file);
  const bool picture = !options.sheet.empty();
  const auto start = std::chrono::steady_clock::now();
  try {
    r.stage = "parse";
    const CheckedActivity checked = check_activity(file, vocabulary);
    r.goal_reach = goal_reach_json(checked);
    if (options.goals_only) {
      r.stage = "grounded";
      return r;
    }
    r.stage = "instantiate";
    EnvConfig config;
    config.activity = file;
    // Rendering only for the sheet (of the instance; a solve's draws its final state).
    config.observations = {picture && !options.solve ? "rgb" : "proprio"};
    config.width = config.height = kSheetHead;
    config.reachable_instances = false;
    Env env(config);
    const auto reset = env.reset(options.seed);
    r.stage = "instantiated";
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.out_of_reach = env.out_of_reach();
    if (picture && !options.solve) r.picture = instance_picture(env, reset.obs, kSheetHead, kSheetTop);
    if (options.steps > 0) {
      r.stage = "run";
      run_in_vector_env(config, env, options.seed, options.steps);
      r.stage = "instantiated";
      r.ran = true;
    }
    if (options.primitive_steps > 0) {
      r.stage = "primitives";
      config.observations = {"proprio"};
      run_primitives(config, options.seed, options.primitive_steps);
      r.stage = "instantiated";
      r.ran_primitives = true;
    }
    if (options.solve) {
      r.stage = "solve";
      // The first seed's result, with its plan; over a range, solved where
      // every seed's was, and why not the first seed's that was not.
      nlohmann::json seeds = nlohmann::json::array();
      for (uint64_t seed = options.seed; seed <= std::max(options.seed, options.last_seed); ++seed) {
        const bool first = r.solve.is_null();
        const nlohmann::json one =
            solve_activity(config, seed, *options.solve, picture && first ? &r.picture : nullptr, kSheetSolved);
        if (first) r.solve = one;
        if (!one["solved"].get<bool>() && r.solve["solved"].get<bool>()) {
          r.solve["solved"] = false;
          r.solve["reason"] = "seed " + std::to_string(seed) + ": " + one.value("reason", std::string());
        }
        seeds.push_back({{"seed", seed},
                         {"solved", one["solved"]},
                         {"q", one.value("q", 0.0)},
                         {"reason", one.value("reason", std::string())}});
      }
      if (seeds.size() > 1) r.solve["seeds"] = seeds;
      r.stage = "instantiated";
    }
  } catch (const Error& e) {
    r.error = e.what();
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return r;
}

// A Result as the child that made it writes it for the parent: JSON, then
// the picture's bytes.
void write_result(const fs::path& path, const Result& r) {
  const nlohmann::json j = {{"name", r.name},
                            {"file", r.file},
                            {"stage", r.stage},
                            {"error", r.error},
                            {"seconds", r.seconds},
                            {"out_of_reach", r.out_of_reach},
                            {"ran", r.ran},
                            {"ran_primitives", r.ran_primitives},
                            {"goal_reach", r.goal_reach},
                            {"solve", r.solve},
                            {"rows", r.picture.rows},
                            {"cols", r.picture.cols}};
  std::ofstream out(path, std::ios::binary);
  out << json_text(j) << "\n";
  if (!r.picture.empty()) {
    const cv::Mat picture = r.picture.isContinuous() ? r.picture : r.picture.clone();
    out.write(reinterpret_cast<const char*>(picture.data), static_cast<std::streamsize>(picture.total() * 3));
  }
}

Result read_result(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::getline(in, line);
  const nlohmann::json j = nlohmann::json::parse(line);
  Result r;
  r.name = j["name"];
  r.file = j["file"];
  r.stage = j["stage"];
  r.error = j["error"];
  r.seconds = j["seconds"];
  r.out_of_reach = j["out_of_reach"];
  r.ran = j["ran"];
  r.ran_primitives = j["ran_primitives"];
  r.goal_reach = j["goal_reach"];
  r.solve = j["solve"];
  if (const int rows = j["rows"], cols = j["cols"]; rows > 0) {
    r.picture = cv::Mat(rows, cols, CV_8UC3);
    in.read(reinterpret_cast<char*>(r.picture.data), static_cast<std::streamsize>(r.picture.total() * 3));
  }
  return r;
}

constexpr const char* kScratchName = "chore-coverage";  // the children's results, in a temporary folder

// Each activity in a child process, `threads` at a time: an activity that
// crashes the simulator (a signal inside MuJoCo) is reported as crashed, with
// its signal, and the others go on. The parent forks before it starts any
// thread of its own, and a child renders in an EGL context of its own.
std::vector<Result> run_each_in_a_child(const std::vector<std::string>& files, const Vocabulary& vocabulary,
                                        const CoverageOptions& options, std::ostream& log) {
  // Named as a temporary of this process's (base/temp_file.hpp): those of
  // runs that were killed go now.
  remove_dead_writers_temps(fs::temp_directory_path(), [](const std::string& name) { return name == kScratchName; });
  const fs::path scratch = temp_path_for(fs::temp_directory_path() / kScratchName);
  fs::create_directories(scratch);
  std::vector<Result> results(files.size());
  std::map<pid_t, size_t> running;
  size_t next = 0, done = 0;
  const auto result_file = [&](size_t i) { return scratch / std::to_string(i); };
  while (next < files.size() || !running.empty()) {
    while (next < files.size() && running.size() < static_cast<size_t>(std::max(options.threads, 1))) {
      const pid_t pid = ::fork();
      if (pid < 0) throw Error(std::string("activity coverage: fork failed: ") + std::strerror(errno));
      if (pid == 0) {
        int status = 0;
        try {
          write_result(result_file(next), run_one(files[next], vocabulary, options));
        } catch (...) {
          status = 1;
        }
        ::_exit(status);  // no destructors: the parent's objects are the parent's to free
      }
      running[pid] = next++;
    }
    int status = 0;
    const pid_t pid = ::waitpid(-1, &status, 0);
    if (pid < 0) throw Error(std::string("activity coverage: waitpid failed: ") + std::strerror(errno));
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    const size_t i = it->second;
    running.erase(it);
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {
      results[i] = read_result(result_file(i));
    } else {
      Result& r = results[i];
      r.file = files[i];
      r.name = activity_name(files[i]);
      r.stage = "crashed";
      r.error = WIFSIGNALED(status) ? std::string("the process died of signal ") + std::to_string(WTERMSIG(status)) +
                                          " (" + strsignal(WTERMSIG(status)) + ")"
                                    : "the process exited with status " + std::to_string(WEXITSTATUS(status));
    }
    std::error_code ignored;
    fs::remove(result_file(i), ignored);
    if (++done % 50 == 0 || done == files.size()) log << "coverage: " << done << "/" << files.size() << std::endl;
  }
  std::error_code ignored;
  fs::remove_all(scratch, ignored);
  return results;
}

// A domain definition (predicates), not an activity: BEHAVIOR's folders hold one.
bool is_domain_file(const fs::path& path) {
  std::ifstream in(path);
  std::string head(1024, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return std::regex_search(head, std::regex(R"(^\s*\(\s*define\s*\(\s*domain\b)"));
}

// The activities under `dir`, sorted, through symbolic links to folders too
// (a corpus gathered as links to its activities' folders): each file once,
// by the first of its paths in order, and a link back to a folder above it
// not followed again.
std::vector<std::string> activity_files(const fs::path& dir) {
  std::set<fs::path> seen;  // canonical paths of the files kept
  std::set<fs::path> folders = {fs::canonical(dir)};
  std::vector<fs::path> paths;
  for (auto it = fs::recursive_directory_iterator(
           dir, fs::directory_options::follow_directory_symlink | fs::directory_options::skip_permission_denied);
       it != fs::recursive_directory_iterator(); ++it) {
    std::error_code error;
    if (it->is_symlink(error) && it->is_directory(error) && !folders.insert(fs::canonical(it->path(), error)).second) {
      it.disable_recursion_pending();
    } else if (it->is_regular_file(error) && it->path().extension() == ".bddl") {
      paths.push_back(it->path());
    }
  }
  std::sort(paths.begin(), paths.end());
  std::vector<std::string> files;
  for (const fs::path& path : paths) {
    std::error_code error;
    const fs::path target = fs::canonical(path, error);
    if (!error && seen.insert(target).second && !is_domain_file(path)) {
      files.push_back(path.string());
    }
  }
  return files;
}

}  // namespace

nlohmann::json activity_coverage(const CoverageOptions& options, std::ostream& log) {
  std::vector<std::string> files;
  if (fs::is_regular_file(options.dir) && fs::path(options.dir).extension() == ".bddl") {
    files.push_back(options.dir);
  } else if (!fs::is_directory(options.dir)) {
    throw Error("activity coverage: '" + options.dir + "' is neither a folder nor a .bddl file");
  } else {
    files = activity_files(options.dir);
  }
  if (files.empty()) throw Error("activity coverage: no .bddl file under '" + options.dir + "'");
  if (options.goals_only && (options.steps > 0 || options.primitive_steps > 0 || !options.sheet.empty())) {
    throw Error("activity coverage: --goals-only builds no world: drop --steps, --primitive-steps and --sheet");
  }

  const Vocabulary vocabulary = load_vocabulary();
  const std::vector<Result> results = run_each_in_a_child(files, vocabulary, options, log);

  if (!options.sheet.empty()) write_contact_sheet(options.sheet, results, options.solve.has_value(), log);

  nlohmann::json activities = nlohmann::json::array();
  std::map<std::string, std::pair<int, std::string>> causes;  // "stage: cause" -> count, example
  std::map<std::string, std::pair<int, std::string>> reach_causes;
  int parsed = 0, instantiated = 0, within_20s = 0, reachable = 0, ran = 0, ran_primitives = 0;
  // Goal literals over the parsed activities, those some primitives and rules
  // could make hold, and those none can by predicate; activities with future
  // objects, and their future objects without a rule or out of the search's reach.
  size_t literals = 0, achievable = 0, with_future = 0, future = 0;
  std::map<std::string, int> unachievable;
  std::map<std::string, std::string> unachievable_example;
  std::vector<std::string> future_without_rule, future_unreachable;
  std::vector<double> seconds;
  // With solve: plans found, activities solved, planning seconds, why not.
  int built = 0, planned = 0, solved = 0;
  std::vector<double> planning;
  std::map<std::string, std::pair<int, std::string>> unsolved_causes;
  for (const Result& r : results) {
    parsed += r.stage != "parse" && r.stage != "crashed";
    instantiated += was_instantiated(r);
    ran += r.ran;
    ran_primitives += r.ran_primitives;
    if (was_instantiated(r)) {
      seconds.push_back(r.seconds);
      within_20s += r.seconds <= 20;
      reachable += r.out_of_reach.empty();
    }
    nlohmann::json a = {{"name", r.name}, {"file", r.file}, {"stage", r.stage}, {"seconds", r.seconds}};
    if (!r.goal_reach.is_null()) {
      const nlohmann::json& g = r.goal_reach;
      a["goal_reach"] = g;
      literals += g["literals"].get<size_t>();
      achievable += g["achievable"].get<size_t>();
      for (const auto& [predicate, list] : g["unachievable"].items()) {
        unachievable[predicate] += static_cast<int>(list.size());
        unachievable_example.emplace(predicate, r.name + ": " + list[0].get<std::string>());
      }
      with_future += g["future"].get<size_t>() > 0;
      future += g["future"].get<size_t>();
      for (const auto& name : g["future_without_rule"])
        future_without_rule.push_back(r.name + ": " + name.get<std::string>());
      for (const auto& name : g["future_unreachable"])
        future_unreachable.push_back(r.name + ": " + name.get<std::string>());
    }
    if (was_instantiated(r)) a["out_of_reach"] = r.out_of_reach;
    if (!r.solve.is_null()) {
      a["solve"] = r.solve;
      built += r.solve["built"].get<bool>();
      planned += r.solve["found"].get<bool>();
      solved += r.solve["solved"].get<bool>();
      planning.push_back(r.solve["planning_seconds"].get<double>());
      if (!r.solve["solved"].get<bool>()) {
        auto& [count, example] = unsolved_causes[failure_cause(r.solve["reason"].get<std::string>())];
        if (count++ == 0) example = r.name;
      }
    }
    if (options.steps > 0) a["ran"] = r.ran;
    if (options.primitive_steps > 0) a["ran_primitives"] = r.ran_primitives;
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
  std::sort(planning.begin(), planning.end());
  nlohmann::json by_predicate = nlohmann::json::array();
  for (const auto& [predicate, count] : unachievable) {
    by_predicate.push_back({{"predicate", predicate}, {"count", count}, {"example", unachievable_example[predicate]}});
  }
  std::stable_sort(by_predicate.begin(), by_predicate.end(),
                   [](const nlohmann::json& a, const nlohmann::json& b) { return a["count"] > b["count"]; });
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
          {"last_seed", std::max(options.seed, options.last_seed)},
          {"goals_only", options.goals_only},
          {"activities", activities},
          {"total", files.size()},
          {"parsed", parsed},
          {"instantiated", instantiated},
          {"instantiated_within_20s", within_20s},
          {"reachable", reachable},
          {"steps", options.steps},
          {"ran", ran},
          {"primitive_steps", options.primitive_steps},
          {"ran_primitives", ran_primitives},
          {"median_seconds", seconds.empty() ? 0.0 : seconds[seconds.size() / 2]},
          {"max_seconds", seconds.empty() ? 0.0 : seconds.back()},
          {"goal_literals", literals},
          {"goal_literals_achievable", achievable},
          {"unachievable_by_predicate", by_predicate},
          {"activities_with_future", with_future},
          {"future_objects", future},
          {"future_without_rule", future_without_rule},
          {"future_unreachable", future_unreachable},
          {"causes", grouped(causes)},
          {"out_of_reach_causes", grouped(reach_causes)},
          {"solve_mode", options.solve ? to_string(*options.solve) : ""},
          {"built", built},
          {"planned", planned},
          {"solved", solved},
          {"median_planning_seconds", planning.empty() ? 0.0 : planning[planning.size() / 2]},
          {"max_planning_seconds", planning.empty() ? 0.0 : planning.back()},
          {"unsolved_causes", grouped(unsolved_causes)}};
}

std::string format_coverage(const nlohmann::json& c) {
  std::ostringstream out;
  const double total = c["total"].get<double>();
  out.precision(1);
  if (c["goals_only"].get<bool>()) {
    out << std::fixed << "coverage of " << c["dir"].get<std::string>() << ": " << c["total"]
        << " activities; parsed and grounded " << c["parsed"] << " (" << 100 * c["parsed"].get<double>() / total
        << "%)\n";
  } else {
    out << std::fixed << "coverage of " << c["dir"].get<std::string>() << ": " << c["total"]
        << " activities; parsed and grounded " << c["parsed"] << " (" << 100 * c["parsed"].get<double>() / total
        << "%), instantiated " << c["instantiated"] << " (" << 100 * c["instantiated"].get<double>() / total
        << "%) at seed " << c["seed"] << ", median " << c["median_seconds"].get<double>() << " s, slowest "
        << c["max_seconds"].get<double>() << " s; " << c["instantiated_within_20s"] << " within 20 s; "
        << c["reachable"] << " with everything the primitives act on within the robot's reach";
    if (c["steps"].get<int>() > 0)
      out << "; " << c["ran"] << " ran " << c["steps"]
          << " random low-level steps in a VectorEnv from the same instance";
    if (c["primitive_steps"].get<int>() > 0)
      out << "; " << c["ran_primitives"] << " ran " << c["primitive_steps"] << " random physical primitives";
    out << "\n";
  }
  const auto list = [&](const char* title, const nlohmann::json& causes) {
    if (!causes.empty()) out << title << ":\n";
    for (const auto& cause : causes) {
      out << "  " << cause["count"] << "  " << cause["cause"].get<std::string>() << "  (e.g. "
          << cause["example"].get<std::string>() << ")\n";
    }
  };
  if (c["goal_literals"].get<double>() > 0) {
    out << "goal literals some primitives and transition rules could make hold (relaxed reachability): "
        << c["goal_literals_achievable"] << " of " << c["goal_literals"] << " ("
        << 100 * c["goal_literals_achievable"].get<double>() / c["goal_literals"].get<double>() << "%); "
        << c["activities_with_future"] << " activities with " << c["future_objects"] << " future objects, "
        << c["future_without_rule"].size() << " of them made by no rule, " << c["future_unreachable"].size()
        << " out of reach of the search\n";
  }
  if (!c["unachievable_by_predicate"].empty()) out << "goal literals no primitive or rule makes hold, by predicate:\n";
  for (const auto& p : c["unachievable_by_predicate"]) {
    out << "  " << p["count"] << "  " << p["predicate"].get<std::string>() << "  (e.g. "
        << p["example"].get<std::string>() << ")\n";
  }
  list("failures by cause", c["causes"]);
  list("instantiated, out of reach", c["out_of_reach_causes"]);
  return out.str();
}

std::string format_solve(const nlohmann::json& c) {
  std::ostringstream out;
  out.precision(1);
  const double instantiated = std::max(1.0, c["instantiated"].get<double>());
  out << std::fixed << "solve of " << c["dir"].get<std::string>() << " (" << c["solve_mode"].get<std::string>()
      << ", seeds " << c["seed"] << "-" << c["last_seed"] << "): " << c["total"] << " activities, " << c["instantiated"]
      << " instantiated, " << c["built"] << " (" << 100 * c["built"].get<double>() / instantiated
      << "%) with an instance that has what a plan acts on in reach; a plan found for " << c["planned"] << " ("
      << 100 * c["planned"].get<double>() / instantiated << "%), solved (executed to Q = 1) " << c["solved"] << " ("
      << 100 * c["solved"].get<double>() / instantiated << "%); planning median "
      << c["median_planning_seconds"].get<double>() << " s, slowest " << c["max_planning_seconds"].get<double>()
      << " s\n";
  for (const auto& a : c["activities"]) {
    if (!a.contains("solve")) continue;
    const nlohmann::json& s = a["solve"];
    std::string seeds;  // "k of n seeds; " over a range
    if (s.contains("seeds")) {
      const auto& all = s["seeds"];
      const auto k =
          std::count_if(all.begin(), all.end(), [](const auto& x) { return x["solved"].template get<bool>(); });
      seeds = std::to_string(k) + " of " + std::to_string(all.size()) + " seeds; ";
    }
    out << "  " << a["name"].get<std::string>() << ": " << seeds
        << (s["solved"].get<bool>() ? "solved, " + std::to_string(s["primitives"].get<size_t>()) + " primitives"
                                    : "not solved: " + s["reason"].get<std::string>())
        << "\n";
  }
  if (!c["unsolved_causes"].empty()) out << "not solved, by cause:\n";
  for (const auto& cause : c["unsolved_causes"]) {
    out << "  " << cause["count"] << "  " << cause["cause"].get<std::string>() << "  (e.g. "
        << cause["example"].get<std::string>() << ")\n";
  }
  return out.str();
}

}  // namespace chore
