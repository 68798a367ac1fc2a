// chore::Env: one environment with a Gym-like reset/step interface.
//
//   chore::Env env({.scene = "apartment"});
//   auto [obs, info] = env.reset(42);
//   auto step = env.step(action);   // obs, reward, terminated, truncated, info
//
// Observations are a Dict of arrays with a batch dimension of 1, owned by the
// env and overwritten by the next reset/step (as EnvPool's are).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "env/primitive_actions.hpp"
#include "env/spaces.hpp"
#include "env/state.hpp"
#include "env/types.hpp"
#include "tasks/activity.hpp"
#include "world/appearance.hpp"
#include "world/lidar.hpp"
#include "world/sensor_noise.hpp"
#include "world/world.hpp"

namespace chore {

class Segmentation;

struct EnvConfig {
  // A BDDL activity (tasks/activities/<name>.bddl or a path); empty: no
  // activity, reward 0, episodes end by the time limit.
  std::string activity;
  // A scene file (assets/scenes/<name>.json or a path), or a scene of
  // BEHAVIOR-1K's inventories (chore scene list), built as its analog with the
  // objects the activity needs. Empty: the activity's scene
  // (tasks/activities/scenes.json), else for a BEHAVIOR-1K activity the analog
  // of a scene that has its rooms (analogs/activity_scenes.hpp), else the apartment.
  std::string scene;
  int width = 128, height = 128;
  // Any of "rgb", "depth", "seg_semantic", "seg_instance", "normal", "flow",
  // "lidar", "proprio", "is_grasping", and for the primitive action space
  // "action_mask": (n,) uint8, 1 where action i's precondition holds now
  // (unmet_precondition in primitives/primitive.hpp is empty). Shapes and
  // conventions: docs/observations.md.
  std::vector<std::string> observations = {"rgb", "depth", "proprio", "is_grasping"};
  Lighting lighting = Lighting::full;
  // Domain randomisation of lights and colours, drawn afresh at every reset
  // from the episode seed (off by default).
  AppearanceRandomization randomization;
  LidarConfig lidar;            // the "lidar" observation's beams, field of view and range
  SensorNoise noise;            // off by default; drawn from the episode seed's sensor stream
  int max_episode_steps = 500;  // then the episode is truncated
  bool robot = true;            // false: a fixed camera, no robot (benchmarks)
  bool object_states = true;    // false: extended states are not updated (benchmarks)
  bool cloth = true;            // false: cloths are rigid (faster; benchmarks)
  // Reset places the robot at the scene's start pose plus a seeded offset up to
  // this far (m) in x and y and 10x this (rad) in heading.
  double start_jitter = 0.1;
  // "low_level": the 14-d RL-VMC action below. "primitives": one action
  // primitive per step, Discrete over the activity's (primitive, object) pairs
  // (env/primitive_actions.hpp), executed in `primitive_mode`.
  std::string action_space = "low_level";
  ExecutionMode primitive_mode = ExecutionMode::physical;
  // Reset samples the activity's instance again (up to kInstanceAttempts
  // times, then chore::Error) while something the robot must act on lies out
  // of its reach from every base pose it can drive to: first_out_of_reach
  // (primitives/primitive.hpp) over each pick, push, dip and wipe of the
  // primitive action space that a plan for the goal takes
  // (EnvAssets::needed_actions: an object nothing needs may lie out of reach,
  // as in a real home). Whatever the action space, so that both see the same
  // instances.
  bool reachable_instances = true;
  // The policy failure of the seed's real-robot setup (appendix G: "we
  // consider policy failures when the policy selects the same invalid action
  // three times in a row ... we decide to terminate early"): this many
  // identical invalid actions in a row end the episode (terminated,
  // info.policy_failure). What is invalid:
  //   "none"          nothing: no episode ends this way (the default: the
  //                   simulated baselines of appendix F end episodes only
  //                   by success or the time limit)
  //   "precondition"  a primitive whose precondition fails (a navigate to
  //                   what is already within reach is one: the appendix's
  //                   example, "requesting to navigate to the bin when it
  //                   is already in front of the bin")
  //   "paper"         as the appendix's words read too: any primitive that
  //                   fails (planning, grasp, place failures as well)
  int policy_failure_repeats = 3;
  std::string policy_failure_rule = "none";
  // Which instance of the activity a reset puts the world in:
  //   "resample"  drawn afresh from the episode's seed at every reset
  //   "fixed"     instance number `instance`, the same at every reset
  //               whatever the episode's seed (OmniGibson's BehaviorTask
  //               loads one pre-sampled instance, instance 0, by default);
  //               the robot's start pose is the instance's too. What
  //               happens after reset (primitives' samples, sensor noise,
  //               appearance randomisation) still follows the episode's seed.
  std::string instances = "resample";
  uint64_t instance = 0;
  // "activity": BEHAVIOR's potential reward (0 without an activity). "reach": a
  // dense task for testing continuous-control learners, minus the distance (m)
  // from the gripper to `reach_target`, a point fixed in the robot's base frame
  // (x forward, y left, z up from the floor); success stays the activity's.
  std::string reward = "activity";
  std::array<double, 3> reach_target = {0.35, 0.1, 0.7};  // ~0.3 m from the tucked gripper
};

// What envs of one config share, read-only: the compiled scene and the bound activity.
struct EnvAssets {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const Activity> activity;  // null without an activity
  // With an activity and the robot: the primitive actions a plan for its goal
  // takes (actions_a_plan_needs, env/task_plan.hpp), what reachable_instances
  // checks; nullopt: every one.
  std::optional<std::set<std::string>> needed_actions;
};
EnvAssets load_assets(const EnvConfig& config);

class Env : public EnvState {
 public:
  // Physics steps of 1/120 s per env step of 1/30 s (the seed's time steps).
  static constexpr int kPhysicsSubsteps = 4;
  static constexpr int kInstanceAttempts = 20;

  explicit Env(const EnvConfig& config);
  // Shares what load_assets(config) compiled (scene, activity) with other envs.
  Env(const EnvConfig& config, const EnvAssets& assets);
  ~Env() override;

  const Space& observation_space() const;
  const Space& action_space() const;
  // The primitive action space's actions, in action order (empty for low_level).
  const std::vector<PrimitiveAction>& primitive_actions() const override;
  const EnvConfig& config() const override;

  struct ResetResult {
    const ArrayDict& obs;
    Info info;
  };
  struct StepResult {
    const ArrayDict& obs;
    double reward;
    bool terminated, truncated;
    Info info;
  };
  // With a seed the episode is fixed by it; without one the env's random
  // stream continues (as Gymnasium's reset() without seed).
  ResetResult reset(std::optional<uint64_t> seed = std::nullopt);
  StepResult step(std::span<const float> action);
  // An Env serves one thread at a time, any thread in turn: called on the
  // thread that used it last, before another uses it (its renderer's EGL
  // context is current on one thread at a time). Python's Env does it after
  // each call; C++ callers that hand an Env between threads do the same.
  void release_thread();
  // Idempotent; any other call after it throws chore::Error.
  void close();
  bool closed() const;

  // The semantic classes and instances that "seg_semantic" and "seg_instance" number.
  const Segmentation& segmentation() const;
  // The first thing of the current instance the robot must act on that lies
  // out of its reach (as reachable_instances checks it, whatever that
  // setting), or "" when all is within reach. Plans without acting: the
  // world and the episode's random stream are as they were.
  std::string out_of_reach();
  // The last primitive's full result (reason, timings), primitive action space only.
  const PrimitiveResult& last_primitive() const;
  // The activity (nullptr without one).
  const Activity* activity() const override;
  const World& world() const override;

  // The implementation (env/env_impl.hpp: the stages of reset and step that
  // VectorEnv's workers run, the mutable world); opaque here.
  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace chore
