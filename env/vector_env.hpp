// chore::VectorEnv: N environments stepped by a pool of T worker threads, with
// EnvPool's synchronous and asynchronous interfaces.
//
//   step(actions)        all N envs, results in env order
//   send(actions, ids)   start those envs stepping ...
//   recv()               ... the first batch_size to finish, with their env ids
//
// Workers write observations straight into batched buffers ((B, H, W, 3) uint8
// RGB, (B, H, W) float32 depth, ...). The cameras are drawn either by each
// worker in a render context of its own, up to `render_tiles` envs in one
// pass (Rendering::per_thread), or by one render context for the whole
// VectorEnv, every env of a batch in one pass (Rendering::batch). Env i is
// seeded with seed + i, so results do not depend on the thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "env/env.hpp"

namespace chore {

// What happens after an episode ends (Gymnasium's names):
//   next_step: the env's next step() resets it and returns the first observation
//              with reward 0 (its action is ignored);
//   same_step: the step that ends the episode resets at once; the returned
//              observation is the new episode's first, and the last
//              observation and info of the old one are in final_obs/final_info.
enum class AutoReset { next_step, same_step };

// Who draws the cameras:
//   per_thread: each worker, in an EGL context of its own, after stepping its
//               envs (up to render_tiles of them per pass);
//   batch:      one context for the VectorEnv (the scene's meshes and
//               textures uploaded once), every env of a batch drawn in one
//               pass as tiles of one offscreen buffer (env i in tile i) and
//               read back once, on the thread that calls reset(), step() or
//               recv(), after the workers have stepped the physics (with
//               same_step, the ended episodes' last frames first, then their
//               resets, on that thread too).
enum class Rendering { per_thread, batch };

struct VectorEnvConfig {
  EnvConfig env;
  int num_envs = 1;
  int num_threads = 1;  // 1 <= num_threads <= num_envs
  int batch_size = 0;   // recv() returns this many envs; 0 means num_envs
  AutoReset autoreset = AutoReset::next_step;
  // Cameras drawn per render pass (tiles of one offscreen buffer, one readback).
  // 0 chooses: 1 on llvmpipe, where per-geom draw calls dominate and wider
  // passes measured slower (docs/benchmarks.md); 16 on a GPU, where each
  // readback is a synchronisation.
  int render_tiles = 0;  // per_thread only
  Rendering rendering = Rendering::per_thread;
};

class VectorEnv {
 public:
  explicit VectorEnv(const VectorEnvConfig& config);
  ~VectorEnv();
  VectorEnv(const VectorEnv&) = delete;
  VectorEnv& operator=(const VectorEnv&) = delete;

  int num_envs() const;
  int batch_size() const;
  const Space& single_observation_space() const;
  const Space& single_action_space() const;

  // Resets every env (env i with seed + i; without a seed, each env's random
  // stream continues). No env may be in flight. Rows are in env order.
  Batch reset(std::optional<uint64_t> seed = std::nullopt);
  // The same with a seed per env (Gymnasium's reset(seed=[...])): env i with
  // seeds[i], or its stream continuing where seeds[i] is empty; one per env.
  Batch reset(std::span<const std::optional<uint64_t>> seeds);
  // All envs, actions row-major (num_envs x action size); needs batch_size == num_envs.
  Batch step(std::span<const float> actions);
  // Starts the given envs stepping; actions row-major (ids.size() x action size).
  // An env is in flight from send() until recv() returns its result; it cannot
  // be sent again before.
  void send(std::span<const float> actions, std::span<const int> env_ids);
  // Waits for the first batch_size results.
  Batch recv();
  // Env i's state, read-only, for policies that read it (the scripted expert).
  // Not while it is in flight.
  const EnvState& state(int i) const;
  // Stops the workers; idempotent.
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace chore
