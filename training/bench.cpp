#include "training/bench.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <thread>

#include "env/env.hpp"
#include "env/vector_env.hpp"

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
  bool robot;
  const char* note;
};

// Table A.10's rows. Fluids, cloth and object-state updates are features of
// activities; a scene without them runs the same work in the first three rows.
const Row kRows[] = {
    {"Full Feature Set", true, ""},
    {"- Fluid and Cloth", true, "no fluid or cloth in this scene"},
    {"- Object State Update", true, "no extended states without an activity"},
    {"- Robot", false, "a fixed camera stands in for the robot"},
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

double vector_steps_per_second(const EnvConfig& env, int envs, int threads, const BenchOptions& o) {
  VectorEnvConfig config;
  config.env = env;
  config.num_envs = envs;
  config.num_threads = threads;
  VectorEnv vec(config);
  vec.reset(0);
  std::vector<float> zero(envs * vec.single_action_space().element_count(), 0.f);
  for (int i = 0; i < 10; ++i) vec.step(zero);
  const int rounds = std::max(1, o.steps / envs);
  std::vector<double> rates;
  for (int r = 0; r < o.repeats; ++r) {
    const auto start = Clock::now();
    for (int i = 0; i < rounds; ++i) vec.step(zero);
    rates.push_back(double(rounds) * envs /
                    std::chrono::duration<double>(Clock::now() - start).count());
  }
  return median(rates);
}

}  // namespace

nlohmann::json run_bench(const BenchOptions& o, std::ostream& log) {
  nlohmann::json out;
  out["protocol"] = "idle: zero action, physics 4 x 1/120 s per step, one egocentric render";
  out["image"] = std::to_string(o.width) + "x" + std::to_string(o.height);
  out["steps"] = o.steps;
  out["repeats"] = o.repeats;
  out["hardware_threads"] = std::thread::hardware_concurrency();
  for (const std::string& scene : o.scenes) {
    EnvConfig config;
    config.scene = scene;
    config.width = o.width;
    config.height = o.height;
    config.max_episode_steps = 1 << 30;
    // The seed's protocol renders RGB only.
    config.observations = {"rgb"};
    for (const Row& row : kRows) {
      config.robot = row.robot;
      log << "bench: " << scene << " / " << row.name << " ..." << std::endl;
      const double sps = env_steps_per_second(config, o);
      out["table"][row.name][scene] = sps;
      if (*row.note) out["notes"][row.name] = row.note;
    }
    // Vector env throughput with RGB-D, the observation RL uses.
    config.robot = true;
    config.observations = {"rgb", "depth", "proprio", "is_grasping"};
    for (int threads : {1, 2}) {
      log << "bench: " << scene << " / vector env, " << threads << " thread(s) ..." << std::endl;
      const double sps = vector_steps_per_second(config, o.vector_envs, threads, o);
      out["vector_env"][scene][std::to_string(threads)] = sps;
    }
  }
  return out;
}

std::string format_bench(const nlohmann::json& r) {
  std::string text;
  char buf[256];
  std::snprintf(buf, sizeof buf,
                "Idle benchmark (seed Table A.10 protocol), %s RGB, env steps per second "
                "(median of %d x %d steps)\n\n",
                r["image"].get<std::string>().c_str(), r["repeats"].get<int>(),
                r["steps"].get<int>());
  text += buf;
  std::vector<std::string> scenes;
  for (const auto& [scene, _] : r["vector_env"].items()) scenes.push_back(scene);
  std::snprintf(buf, sizeof buf, "%-24s", "Eval. conditions");
  text += buf;
  for (const std::string& s : scenes) {
    std::snprintf(buf, sizeof buf, "%14s", s.c_str());
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
  text += "\nVectorEnv throughput, 128x128 RGB-D + proprioception, zero action, sync step\n";
  for (const std::string& s : scenes) {
    const auto& v = r["vector_env"][s];
    const double one = v["1"].get<double>(), two = v["2"].get<double>();
    std::snprintf(buf, sizeof buf, "%-24s 1 thread: %6.0f steps/s   2 threads: %6.0f steps/s (%.2fx)\n",
                  s.c_str(), one, two, two / one);
    text += buf;
  }
  return text;
}

}  // namespace chore
