#include "app/bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <memory>
#include <span>
#include <thread>

#include <mujoco/mujoco.h>

#include "base/error.hpp"
#include "env/env.hpp"
#include "env/vector_env.hpp"
#include "policies/expert.hpp"

namespace chore {
namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Row {
  const char* name;
  bool robot, cloth, object_states;
  const char* note;
};

// Table A.10's rows, each removing one more feature. Each scene runs its
// activity (tasks/activities/scenes.json): extended states and goal checks
// every step. Without cloth, rags are rigid boxes (water is a container level,
// never particles); without the robot there is no activity (its agent is the
// robot) and a fixed camera looks on.
const Row kRows[] = {
    {"Full Feature Set", true, true, true, ""},
    {"- Fluid and Cloth", true, false, true, "rigid rags"},
    {"- Object State Update", true, false, false, "extended states frozen too"},
    {"- Robot", false, false, false, "no robot, no activity: a fixed camera"},
};

double env_steps_per_second(const EnvConfig& config, const BenchOptions& o) {
  Env env(config);
  env.reset(0);
  std::vector<float> zero(env.action_space().element_count(), 0.f);
  for (int i = 0; i < 30; ++i) env.step(zero);  // warm-up: caches, lazy GL state
  std::vector<double> rates;
  for (int r = 0; r < o.repeats; ++r) {
    const auto start = Clock::now();
    for (int i = 0; i < o.steps; ++i) env.step(zero);
    rates.push_back(o.steps / std::chrono::duration<double>(Clock::now() - start).count());
  }
  return median(rates);
}

// Steps per second of a vector env: synchronous steps at 1 and 2 threads, and
// EnvPool-style asynchronous stepping at 2 threads (batch_size = envs / 2: the
// caller sends the batch it received back at once, so no worker waits for the
// slowest env of a round). The machines are shared and noisy: the three are
// measured in alternating blocks and the speed-ups are medians of per-block ratios.
struct VectorRates {
  double one, two, two_async, speedup, speedup_async;
};

VectorRates vector_rates(const EnvConfig& env, int envs, const BenchOptions& o) {
  auto make = [&](int threads, int batch) {
    VectorEnvConfig config;
    config.env = env;
    config.num_envs = envs;
    config.num_threads = threads;
    config.batch_size = batch;
    auto v = std::make_unique<VectorEnv>(config);
    v->reset(0);
    return v;
  };
  auto sync1 = make(1, 0), sync2 = make(2, 0), async2 = make(2, envs / 2);
  const size_t action_size = sync1->single_action_space().element_count();
  const std::vector<float> zero(envs * action_size, 0.f);
  const int rounds = std::max(1, o.steps / envs);
  auto rate = [&](const Clock::time_point& start) {
    return double(rounds) * envs / std::chrono::duration<double>(Clock::now() - start).count();
  };
  auto measure_sync = [&](VectorEnv& v) {
    const auto start = Clock::now();
    for (int i = 0; i < rounds; ++i) v.step(zero);
    return rate(start);
  };
  std::vector<int> all(envs);
  for (int i = 0; i < envs; ++i) all[i] = i;
  async2->send(zero, all);  // from here on, every env is in flight or just received
  auto measure_async = [&]() {
    const auto start = Clock::now();
    for (int i = 0; i < 2 * rounds; ++i) {
      const Batch b = async2->recv();
      const std::vector<int> ids(b.env_ids.begin(), b.env_ids.end());
      async2->send(std::span<const float>(zero).first(ids.size() * action_size), ids);
    }
    return rate(start);
  };
  measure_sync(*sync1);  // warm-up
  measure_sync(*sync2);
  measure_async();
  std::vector<double> ones, twos, asyncs, ratios, async_ratios;
  for (int r = 0; r < std::max(3, o.repeats); ++r) {
    ones.push_back(measure_sync(*sync1));
    twos.push_back(measure_sync(*sync2));
    asyncs.push_back(measure_async());
    ratios.push_back(twos.back() / ones.back());
    async_ratios.push_back(asyncs.back() / ones.back());
  }
  return {median(ones), median(twos), median(asyncs), median(ratios), median(async_ratios)};
}

// This process's resident memory (VmRSS), in bytes.
double resident_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);) {
    if (line.starts_with("VmRSS:")) return std::stod(line.substr(6)) * 1024;  // "VmRSS:   123456 kB"
  }
  throw Error("bench: no VmRSS in /proc/self/status");
}

// Resident memory of a vector env of `envs` envs, after a reset and a few
// steps (every buffer touched): what one env adds is the difference to a
// vector env of one, per extra env; the one env's own is what the first costs
// with the assets its vector env shares.
// `keep` holds every vector env measured so far: memory freed and reused would
// hide what the next one takes.
nlohmann::json memory_per_env(const EnvConfig& env, int envs, std::vector<std::unique_ptr<VectorEnv>>& keep) {
  const auto grow = [&](int n) {
    const double before = resident_bytes();
    VectorEnvConfig config;
    config.env = env;
    config.num_envs = n;
    config.num_threads = 1;
    auto v = std::make_unique<VectorEnv>(config);
    v->reset(0);
    const std::vector<float> zero(n * v->single_action_space().element_count(), 0.f);
    for (int i = 0; i < 5; ++i) v->step(zero);
    keep.push_back(std::move(v));
    return resident_bytes() - before;
  };
  const double one = grow(1), many = grow(envs);
  return {{"envs", envs},
          {"first_env_mb", one / 1e6},
          {"vector_env_mb", many / 1e6},
          {"per_extra_env_mb", (many - one) / (envs - 1) / 1e6}};
}

// The observations whose cost per frame the modality rows measure, each on its
// own over a step that observes nothing (physics, states, the activity).
struct ModalityRow {
  const char* name;
  std::vector<std::string> observations;
  bool noise = false;
};

const std::vector<ModalityRow> kModalityRows = {
    {"rgb", {"rgb"}},
    {"depth", {"depth"}},
    {"seg_semantic", {"seg_semantic"}},
    {"seg_instance", {"seg_instance"}},
    {"normal", {"normal"}},
    {"flow", {"flow"}},
    {"lidar", {"lidar"}},
    {"rgb + noise", {"rgb"}, true},
    {"depth + noise", {"depth"}, true},
    {"lidar + noise", {"lidar"}, true},
    {"all of them", {"rgb", "depth", "seg_semantic", "seg_instance", "normal", "flow", "lidar"}},
};

// Milliseconds per step of each modality row over the bare step, medians of
// per-repetition differences (repetitions alternate over the rows).
nlohmann::json modality_costs(const std::string& scene, const BenchOptions& o) {
  EnvConfig config;
  config.scene = scene;
  config.activity = scene_activity(scene);
  config.width = o.width;
  config.height = o.height;
  config.max_episode_steps = 1 << 30;
  const EnvAssets assets = load_assets(config);
  auto make = [&](const std::vector<std::string>& observations, bool noise) {
    EnvConfig c = config;
    c.observations = observations;
    if (noise) {
      c.noise.rgb_shot_noise = c.noise.rgb_read_noise = 1;
      c.noise.depth_noise = c.noise.depth_noise_quadratic = c.noise.depth_edge = 0.01;
      c.noise.lidar_noise = c.noise.lidar_dropout = 0.01;
    }
    auto env = std::make_unique<Env>(c, assets);
    env->reset(0);
    return env;
  };
  auto bare = make({}, false);
  std::vector<std::unique_ptr<Env>> envs;
  for (const ModalityRow& row : kModalityRows) envs.push_back(make(row.observations, row.noise));
  std::vector<float> zero(bare->action_space().element_count(), 0.f);
  auto ms_per_step = [&](Env& env) {
    const auto start = Clock::now();
    for (int i = 0; i < o.steps; ++i) env.step(zero);
    return 1e3 * std::chrono::duration<double>(Clock::now() - start).count() / o.steps;
  };
  ms_per_step(*bare);  // warm-up
  for (auto& env : envs) ms_per_step(*env);
  std::vector<double> bases;
  std::vector<std::vector<double>> extra(envs.size());
  for (int r = 0; r < o.repeats; ++r) {
    const double base = ms_per_step(*bare);
    bases.push_back(base);
    for (size_t k = 0; k < envs.size(); ++k) extra[k].push_back(ms_per_step(*envs[k]) - base);
  }
  nlohmann::json out;
  out["scene"] = scene;
  out["activity"] = config.activity;
  out["bare_step_ms"] = median(bases);
  for (size_t k = 0; k < envs.size(); ++k) out["ms_per_frame"][kModalityRows[k].name] = median(extra[k]);
  return out;
}

}  // namespace

// The scripted expert's primitive steps, timed one by one: wall time of the
// env step (no rendering: the state observation only), and the primitive's own
// planning and execution time, and the seconds it simulated, per primitive
// type and overall.
nlohmann::json primitive_rates(const std::string& activity, ExecutionMode mode, int episodes) {
  EnvConfig config;
  config.activity = activity;
  config.observations = {"is_grasping"};
  config.action_space = "primitives";
  config.primitive_mode = mode;
  config.max_episode_steps = 30;
  Env env(config);
  const ScriptedExpert expert(env);
  struct Sum {
    int n = 0;
    double wall = 0, planning = 0, execution = 0, simulated = 0;
  };
  std::vector<Sum> sums(kPrimitiveTypes + 1);  // the last: all primitives
  for (int e = 0; e < episodes; ++e) {
    env.reset(static_cast<uint64_t>(e));
    for (bool done = false; !done;) {
      const std::optional<int> a = expert.act(env);
      if (!a) break;
      const float value = static_cast<float>(*a);
      const auto start = Clock::now();
      const Env::StepResult r = env.step({&value, 1});
      const double wall = std::chrono::duration<double>(Clock::now() - start).count();
      for (Sum* sum : {&sums[static_cast<int>(env.primitive_actions()[*a].type)], &sums.back()}) {
        ++sum->n;
        sum->wall += wall;
        sum->planning += env.last_primitive().planning_seconds;
        sum->execution += env.last_primitive().execution_seconds;
        sum->simulated += static_cast<double>(env.last_primitive().physics_steps) * env.world().model()->opt.timestep;
      }
      done = r.terminated || r.truncated;
    }
  }
  nlohmann::json out;
  for (int t = 0; t <= kPrimitiveTypes; ++t) {
    const Sum& s = sums[t];
    if (!s.n) continue;
    out[t == kPrimitiveTypes ? "all" : to_string(static_cast<PrimitiveType>(t))] = {
        {"n", s.n},
        {"steps_per_second", s.n / s.wall},
        {"planning_ms", 1e3 * s.planning / s.n},
        {"execution_ms", 1e3 * s.execution / s.n},
        {"simulated_s", s.simulated / s.n}};
  }
  return out;
}

nlohmann::json run_bench(const BenchOptions& o, std::ostream& log) {
  nlohmann::json out;
  out["protocol"] = "idle: zero action, physics 4 x 1/120 s per step, one egocentric render";
  out["image"] = std::to_string(o.width) + "x" + std::to_string(o.height);
  out["steps"] = o.steps;
  out["repeats"] = o.repeats;
  out["hardware_threads"] = std::thread::hardware_concurrency();
  out["scenes"] = o.scenes;
  out["sections"] = o.sections;
  for (const std::string& section : o.sections) {
    if (section != "table" && section != "vector" && section != "primitives" && section != "modalities" &&
        section != "memory") {
      throw Error("bench: unknown section '" + section + "' (known: table, vector, primitives, modalities, memory)");
    }
  }
  auto runs = [&](const char* section) {
    return std::find(o.sections.begin(), o.sections.end(), section) != o.sections.end();
  };
  for (const std::string& scene : o.scenes) {
    EnvConfig config;
    config.scene = scene;
    config.width = o.width;
    config.height = o.height;
    config.max_episode_steps = 1 << 30;
    // The seed's protocol renders RGB only.
    config.observations = {"rgb"};
    for (const Row& row : kRows) {
      if (!runs("table")) break;
      config.robot = row.robot;
      config.cloth = row.cloth;
      config.object_states = row.object_states;
      config.activity = row.robot ? scene_activity(scene) : "";
      log << "bench: " << scene << " / " << row.name << " ..." << std::endl;
      const double sps = env_steps_per_second(config, o);
      out["table"][row.name][scene] = sps;
      if (*row.note) out["notes"][row.name] = row.note;
    }
    // Vector envs with RGB-D, the observation RL uses.
    config.robot = config.cloth = config.object_states = true;
    config.activity = scene_activity(scene);
    config.observations = {"rgb", "depth", "proprio", "is_grasping"};
    if (runs("memory") && scene == o.scenes.front()) {
      // The first scene only: the vector envs stay alive to the end of the section.
      std::vector<std::unique_ptr<VectorEnv>> keep;
      for (const std::string space : {"low_level", "primitives"}) {
        if (space == "primitives" && config.activity.empty()) continue;  // primitives act on an activity's objects
        log << "bench: " << scene << " / memory of " << o.vector_envs << " envs, " << space << " actions ..."
            << std::endl;
        EnvConfig spaced = config;
        spaced.action_space = space;
        out["memory"][scene + " " + space] = memory_per_env(spaced, o.vector_envs, keep);
      }
    }
    if (!runs("vector")) continue;
    log << "bench: " << scene << " / vector env, 1 and 2 threads ..." << std::endl;
    const VectorRates v = vector_rates(config, o.vector_envs, o);
    out["vector_env"][scene] = {{"1", v.one},
                                {"2", v.two},
                                {"2_async", v.two_async},
                                {"speedup", v.speedup},
                                {"speedup_async", v.speedup_async}};
  }
  out["primitive_episodes"] = o.primitive_episodes;
  for (const std::string& scene : o.scenes) {
    const std::string activity = scene_activity(scene);
    if (activity.empty() || o.primitive_episodes <= 0 || !runs("primitives")) continue;
    for (ExecutionMode mode : {ExecutionMode::symbolic, ExecutionMode::physical}) {
      log << "bench: " << activity << " / primitives, " << to_string(mode) << " ..." << std::endl;
      out["primitives"][activity][to_string(mode)] = primitive_rates(activity, mode, o.primitive_episodes);
    }
  }
  if (runs("modalities") && !o.scenes.empty()) {
    log << "bench: " << o.scenes.front() << " / observation modalities ..." << std::endl;
    out["modalities"] = modality_costs(o.scenes.front(), o);
  }
  return out;
}

namespace {

std::string format_modalities(const nlohmann::json& r) {
  const auto& m = r["modalities"];
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "\nObservation modalities, %s (%s), %s, one env: ms per frame over a step that observes\n"
                "nothing (%.2f ms), median of %d x %d steps\n",
                m["scene"].get<std::string>().c_str(),
                m["activity"].get<std::string>().empty() ? "no activity" : m["activity"].get<std::string>().c_str(),
                r["image"].get<std::string>().c_str(), m["bare_step_ms"].get<double>(), r["repeats"].get<int>(),
                r["steps"].get<int>());
  std::string text = buf;
  for (const ModalityRow& row : kModalityRows) {
    std::snprintf(buf, sizeof buf, "  %-16s%8.2f\n", row.name, m["ms_per_frame"][row.name].get<double>());
    text += buf;
  }
  return text;
}

std::string format_table(const nlohmann::json& r) {
  std::string text;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "Idle benchmark (seed Table A.10 protocol), %s RGB, env steps per second "
                "(median of %d x %d steps)\n\n",
                r["image"].get<std::string>().c_str(), r["repeats"].get<int>(), r["steps"].get<int>());
  text += buf;
  const std::vector<std::string> scenes = r["scenes"].get<std::vector<std::string>>();
  std::snprintf(buf, sizeof buf, "%-24s", "Eval. conditions");
  text += buf;
  for (const std::string& s : scenes) {
    std::snprintf(buf, sizeof buf, " %13s", s.c_str());  // a space apart, however long the name
    text += buf;
  }
  text += "\n";
  for (const Row& row : kRows) {
    std::snprintf(buf, sizeof buf, "%-24s", row.name);
    text += buf;
    for (const std::string& s : scenes) {
      std::snprintf(buf, sizeof buf, "%14.0f", r["table"][row.name][s].get<double>());
      text += buf;
    }
    if (r.contains("notes") && r["notes"].contains(row.name)) {
      text += "   (" + r["notes"][row.name].get<std::string>() + ")";
    }
    text += "\n";
  }
  return text;
}

std::string format_vector_env(const nlohmann::json& r) {
  std::string text;
  char buf[256];
  const std::vector<std::string> scenes = r["scenes"].get<std::vector<std::string>>();
  text += "\nVectorEnv, " + r["image"].get<std::string>() +
          " RGB-D + proprioception, zero action, env steps per second (speed-up: median of\n"
          "per-block ratios to 1 thread, blocks alternating)\n";
  std::snprintf(buf, sizeof buf, "%-14s%18s%26s%28s\n", "scene", "1 thread, sync", "2 threads, sync",
                "2 threads, async (B=N/2)");
  text += buf;
  for (const std::string& s : scenes) {
    const auto& v = r["vector_env"][s];
    std::snprintf(buf, sizeof buf, "%-14s%18.0f%18.0f (%.2fx)%20.0f (%.2fx)\n", s.c_str(), v["1"].get<double>(),
                  v["2"].get<double>(), v["speedup"].get<double>(), v["2_async"].get<double>(),
                  v["speedup_async"].get<double>());
    text += buf;
  }
  return text;
}

std::string format_memory(const nlohmann::json& r) {
  std::string text = "\nResident memory of a vector env (RGB-D + proprioception, after reset and 5 steps), MB\n";
  char buf[256];
  std::snprintf(buf, sizeof buf, "%-22s%12s%18s%22s\n", "scene, actions", "first env", "vector env of N",
                "per extra env");
  text += buf;
  for (const auto& [scene, m] : r["memory"].items()) {
    std::snprintf(buf, sizeof buf, "%-22s%12.0f%14.0f (%d)%22.1f\n", scene.c_str(), m["first_env_mb"].get<double>(),
                  m["vector_env_mb"].get<double>(), m["envs"].get<int>(), m["per_extra_env_mb"].get<double>());
    text += buf;
  }
  return text;
}

std::string format_primitives(const nlohmann::json& r) {
  std::string text;
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "\nPrimitive action space: the scripted expert, %d episodes per activity and mode, one thread;\n"
                "primitive steps per second (state observation, no rendering), planning / execution ms per primitive;\n"
                "physical rows: then the seconds of physics one primitive simulates\n",
                r["primitive_episodes"].get<int>());
  text += buf;
  std::snprintf(buf, sizeof buf, "%-18s%-10s", "activity", "mode");
  text += buf;
  const char* columns[] = {"all", "navigate", "pick", "place", "push", "dip", "wipe"};
  for (const char* c : columns) {
    std::snprintf(buf, sizeof buf, "%20s", c);
    text += buf;
  }
  text += "\n";
  for (const auto& [activity, modes] : r["primitives"].items()) {
    for (const auto& [mode, rows] : modes.items()) {
      std::snprintf(buf, sizeof buf, "%-18s%-10s", activity.c_str(), mode.c_str());
      text += buf;
      for (const char* c : columns) {
        if (!rows.contains(c)) {
          std::snprintf(buf, sizeof buf, "%20s", "-");
        } else {
          const auto& x = rows[c];
          std::snprintf(buf, sizeof buf, "%7.1f/s %5.0f/%-5.0f", x["steps_per_second"].get<double>(),
                        x["planning_ms"].get<double>(), x["execution_ms"].get<double>());
        }
        text += buf;
      }
      text += "\n";
      if (mode != to_string(ExecutionMode::physical)) continue;
      std::snprintf(buf, sizeof buf, "%-18s%-10s", "", "simulated");
      text += buf;
      for (const char* c : columns) {
        if (!rows.contains(c)) {
          std::snprintf(buf, sizeof buf, "%20s", "-");
        } else {
          std::snprintf(buf, sizeof buf, "%18.2fs ", rows[c]["simulated_s"].get<double>());
        }
        text += buf;
      }
      text += "\n";
    }
  }
  return text;
}

}  // namespace

std::string format_bench(const nlohmann::json& r) {
  std::string text;
  if (r.contains("table")) text += format_table(r);
  if (r.contains("vector_env")) text += format_vector_env(r);
  if (r.contains("primitives")) text += format_primitives(r);
  if (r.contains("modalities")) text += format_modalities(r);
  if (r.contains("memory")) text += format_memory(r);
  return text;
}

}  // namespace chore
