// Env's implementation: its state, and the stages of reset and step that
// VectorEnv's workers run one by one to batch the rendering of many envs.
// Internal to env/ (tests reach the mutable world through it).
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "base/random.hpp"
#include "env/env.hpp"
#include "world/renderer.hpp"
#include "world/sampling.hpp"
#include "world/sensors.hpp"

namespace chore {

struct ObservationSource;
struct RewardKind;

struct Env::Impl {
  Impl(const EnvConfig& config, const EnvAssets& assets);
  ~Impl();

  // The pieces of reset/step: the state moves, then the cameras are rendered
  // (by the caller, batched across envs), then the observation is finished.
  Info reset_state(std::optional<uint64_t> seed);
  struct Outcome {
    double reward = 0;
    bool terminated = false, truncated = false;
    Info info;
  };
  Outcome advance(std::span<const float> action);
  // The camera views writing into element `index` of `obs` (empty when no
  // image is observed). Once they are rendered, finish_observation() writes
  // the rest: the modalities derived from the images, the LiDAR, sensor
  // noise, and the state observations (those alone: write_state()).
  std::vector<CameraView> camera_views(ArrayDict& obs, int index);
  void finish_observation(ArrayDict& obs, int index);
  void write_state(ArrayDict& obs, int index) const;
  void observe();  // renders and writes into obs_ with this env's own renderer
  void close();
  World& world() { return *world_; }

  void check_open() const;
  Info make_info(const Score* score = nullptr) const;
  // Applies one action to the world; returns physics steps run.
  int64_t act_low_level(std::span<const float> action, World::StepReport& report);
  int64_t act_primitive(std::span<const float> action, World::StepReport& report);
  std::string first_out_of_reach(uint64_t seed);  // a reach check failing in the sampled instance, or ""
  SensorFrame sensor_frame(ArrayDict& obs, int index) const;
  ObservationSource observation_source() const;

  EnvConfig config_;
  std::shared_ptr<const Scene> scene_;
  std::shared_ptr<const Activity> activity_;
  double potential_ = 0;  // BEHAVIOR's potential after the last step
  const RewardKind* reward_ = nullptr;
  std::unique_ptr<World> world_;
  std::unique_ptr<Renderer> renderer_;  // made on first use, on the calling thread
  std::unique_ptr<Sensors> sensors_;
  Space observation_space_, action_space_;
  ArrayDict obs_;
  Rng rng_;
  std::vector<PrimitiveAction> primitive_actions_;
  std::vector<PrimitiveAction> reach_checks_;  // what must be within reach (reset checks it when asked)
  // Where the instance samplers put objects first (arm_reach_preference()),
  // from the scene as reset leaves it: made at the first reset, the same at every one.
  SampleOptions sample_options_;
  PrimitiveResult last_primitive_;
  std::array<int, kPrimitiveStatuses> primitive_counts_{};
  int last_primitive_status_ = -1, last_invalid_action_ = -1, invalid_repeats_ = 0;
  int64_t elapsed_ = 0;
  uint64_t episode_seed_ = 0;
  bool episode_over_ = true, closed_ = false, diverged_ = false;
};

}  // namespace chore
