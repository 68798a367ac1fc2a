// Google Benchmark micro-benchmarks of the pieces of an env step:
//   build/tests/chore_micro_bench [--benchmark_filter=...]
// Not part of ctest: timings belong to benchmark programs, not tests.
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <chrono>
#include <fstream>
#include <string>

#include "env/env.hpp"
#include "env/env_impl.hpp"
#include "world/renderer.hpp"

namespace chore {
namespace {

EnvConfig rgbd() {
  EnvConfig c;
  c.scene = "apartment";
  return c;
}

const EnvAssets& apartment() {
  static const EnvAssets assets = load_assets(rgbd());
  return assets;
}

// One physics step of 1/120 s of the apartment with the robot standing still.
void BM_PhysicsStep(benchmark::State& state) {
  World world(apartment().scene);
  for (auto _ : state) world.step(1);
}
BENCHMARK(BM_PhysicsStep);

// One 128x128 RGB-D frame of the head camera, readback included.
void BM_RenderRgbd(benchmark::State& state) {
  Env env(rgbd(), apartment());
  env.reset(0);
  ArrayDict out(env.observation_space(), 1);
  Renderer renderer(env.world().model(), 128, 128, 1);
  std::vector<CameraView> views = env.impl().camera_views(out, 0);
  for (auto _ : state) renderer.render(views);
}
BENCHMARK(BM_RenderRgbd);

// N cameras in one pass (tiles, one readback); reported per frame.
void BM_RenderTiled(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::vector<std::unique_ptr<Env>> envs;
  ArrayDict out(Env(rgbd(), apartment()).observation_space(), n);
  std::vector<CameraView> views;
  for (int i = 0; i < n; ++i) {
    envs.push_back(std::make_unique<Env>(rgbd(), apartment()));
    envs.back()->reset(0);  // the same view in every tile: only the batching differs
    for (CameraView v : envs.back()->impl().camera_views(out, i)) {
      v.tile = i;
      views.push_back(v);
    }
  }
  Renderer renderer(envs[0]->world().model(), 128, 128, n);
  for (auto _ : state) renderer.render(views);
  state.SetItemsProcessed(state.iterations() * n);
}
BENCHMARK(BM_RenderTiled)->Arg(1)->Arg(4)->Arg(8)->Arg(16);

// Writing proprioception into a batch slot.
void BM_WriteState(benchmark::State& state) {
  Env env(rgbd(), apartment());
  env.reset(0);
  ArrayDict out(env.observation_space(), 8);
  int i = 0;
  for (auto _ : state) env.impl().write_state(out, i++ % 8);
}
BENCHMARK(BM_WriteState);

// The action_mask of store_decoration's 7 primitive actions at its first
// state (one IK reach test per navigate action, state checks for the rest).
void BM_ActionMask(benchmark::State& state) {
  EnvConfig c;
  c.activity = "store_decoration";
  c.action_space = "primitives";
  c.observations = {"action_mask"};
  Env env(c);
  env.reset(1);
  ArrayDict out(env.observation_space(), 1);
  for (auto _ : state) env.impl().write_state(out, 0);
}
BENCHMARK(BM_ActionMask);

// A seeded reset of each activity in the primitive action space (sampling
// :init, settling, the first observation is not rendered), with the check
// that every pick, push, dip and wipe is within reach of a drivable base pose
// (arg 1, the default) or without it (arg 0). Seeds cycle over 0..19.
void reset_activity(benchmark::State& state, const std::string& activity) {
  EnvConfig c;
  c.activity = activity;
  c.action_space = "primitives";
  c.primitive_mode = ExecutionMode::symbolic;
  c.observations = {"is_grasping"};
  c.reachable_instances = state.range(0) != 0;
  Env env(c);
  uint64_t seed = 0;
  for (auto _ : state) env.reset(seed++ % 20);
}
BENCHMARK_CAPTURE(reset_activity, store_decoration, std::string("store_decoration"))
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(reset_activity, collect_trash, std::string("collect_trash"))
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(reset_activity, clean_table, std::string("clean_table"))
    ->Arg(0)
    ->Arg(1)
    ->Unit(benchmark::kMillisecond);

// MuJoCo's timer clock (mjcb_time).
mjtNum microseconds() {
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
// Times World::step(1) with MuJoCo's timers on: the benchmark's counters are
// microseconds per step of kinematics, collision detection and the constraint solver,
// contacts per step, and the model's size.
void time_physics_steps(benchmark::State& state, World& w) {
  mjcb_time = microseconds;
  w.step(1);
  mjData* d = w.data();
  for (mjTimerStat& t : d->timer) t = {};
  double contacts = 0;
  for (auto _ : state) {
    w.step(1);
    contacts += d->ncon;
  }
  const double steps = d->timer[mjTIMER_STEP].number;
  state.counters["kinematics_us"] = d->timer[mjTIMER_POS_KINEMATICS].duration / steps;
  state.counters["collision_us"] = d->timer[mjTIMER_POS_COLLISION].duration / steps;
  state.counters["solver_us"] = d->timer[mjTIMER_CONSTRAINT].duration / steps;
  state.counters["contacts"] = contacts / static_cast<double>(state.iterations());
  state.counters["dofs"] = w.model()->nv;
  state.counters["bodies"] = w.model()->nbody;
  state.counters["asleep"] = w.sleepers();
  state.counters["objects"] = static_cast<double>(w.scene().objects().size());
  mjcb_time = nullptr;
}

// One physics step of an activity's scene at rest after reset 0 (World::step:
// mj_step with the robot's controllers, grasp and state rules), with objects
// asleep as every reset starts them (MuJoCo's sleeping) or not, with the
// scene's Newton solver or MuJoCo's conjugate-gradient one.
void physics_step_activity(benchmark::State& state, const std::string& activity, bool sleeping, mjtSolver solver) {
  EnvConfig c;
  c.activity = activity;
  c.action_space = "primitives";
  c.observations = {"is_grasping"};
  Env env(c);
  env.reset(0);
  World& w = env.impl().world();
  w.model()->opt.solver = solver;
  w.set_sleeping(sleeping);
  time_physics_steps(state, w);
}
BENCHMARK_CAPTURE(physics_step_activity, store_decoration, std::string("store_decoration"), false, mjSOL_NEWTON)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(physics_step_activity, collect_trash, std::string("collect_trash"), false, mjSOL_NEWTON)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(physics_step_activity, clean_table, std::string("clean_table"), false, mjSOL_NEWTON)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(physics_step_activity, store_decoration_sleeping, std::string("store_decoration"), true, mjSOL_NEWTON)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(physics_step_activity, collect_trash_sleeping, std::string("collect_trash"), true, mjSOL_NEWTON)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(physics_step_activity, clean_table_sleeping, std::string("clean_table"), true, mjSOL_NEWTON)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(physics_step_activity, store_decoration_cg, std::string("store_decoration"), false, mjSOL_CG)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(physics_step_activity, store_decoration_sleeping_cg, std::string("store_decoration"), true, mjSOL_CG)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(physics_step_activity, clean_table_sleeping_cg, std::string("clean_table"), true, mjSOL_CG)
    ->Unit(benchmark::kMillisecond);

// The floor under a physical primitive's step: the robot alone in the
// studio's rooms (walls and floors, no object), one physics step.
void physics_step_robot_alone(benchmark::State& state) {
  World w(Scene::load(std::string(CHORE_TEST_DATA) + "/scenes/robot_only.json"));
  time_physics_steps(state, w);
}
BENCHMARK(physics_step_robot_alone)->Unit(benchmark::kMicrosecond);

// A whole env step (physics x4 + render + state), as `chore bench` times it.
void BM_EnvStep(benchmark::State& state) {
  Env env(rgbd(), apartment());
  env.reset(0);
  std::vector<float> zero(kLowLevelActionSize, 0.f);
  for (auto _ : state) {
    if (env.step(zero).truncated) env.reset(0);
  }
}
BENCHMARK(BM_EnvStep);

// Instantiating an activity of N apples on one living room's floor (issue
// 54's scale case): sampling places each with settling steps of the whole
// scene, so its cost grows with N; the state rules run at none of them. One
// reset, the instance as sampled (no resampling for reach).
void BM_InstantiateApplesOnTheFloor(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  std::string objects, init;
  for (int i = 1; i <= n; ++i) {
    objects += " apple.n.01_" + std::to_string(i);
    init += " (onfloor apple.n.01_" + std::to_string(i) + " floor.n.01_1)";
  }
  const std::string file = "/tmp/chore_bench_apples_" + std::to_string(n) + ".bddl";
  std::ofstream(file) << "(define (problem apples-0) (:domain igibson) (:objects" << objects
                      << " - apple.n.01 floor.n.01_1 - floor.n.01 agent.n.01_1 - agent.n.01) (:init" << init
                      << " (inroom floor.n.01_1 living_room) (onfloor agent.n.01_1 floor.n.01_1)) (:goal (and "
                         "(onfloor ?agent.n.01_1 ?floor.n.01_1))))\n";
  EnvConfig config;
  config.activity = file;
  config.observations = {"proprio"};
  config.reachable_instances = false;
  Env env(config);
  uint64_t seed = 0;
  for (auto _ : state) env.reset(seed++);
}
BENCHMARK(BM_InstantiateApplesOnTheFloor)->Arg(50)->Arg(200)->Arg(500)->Unit(benchmark::kSecond)->Iterations(3);

}  // namespace
}  // namespace chore

BENCHMARK_MAIN();
