// What a step returns beside the observations, and the batched view of a
// VectorEnv's results: the public types a policy needs (policies/policy.hpp),
// without the env's internals. The low-level (RL-VMC) action's layout.
#pragma once

#include <array>
#include <cstdint>
#include <span>

#include "env/spaces.hpp"
#include "primitives/primitive_types.hpp"

namespace chore {

struct Info {
  int env_id = 0;
  int64_t elapsed_steps = 0;
  // The seed of this episode's reset; an unseeded reset counts on from the
  // last (+1). A policy that draws random numbers can seed them from it, so
  // that an episode's draws do not depend on which env or thread plays it.
  uint64_t episode_seed = 0;
  bool diverged = false;       // MuJoCo became unstable; the episode was truncated
  bool grasp_refused = false;  // the gripper closed on an object over the mass limit
  bool is_grasping = false;
  // Activity scores (all 0 without an activity).
  bool success = false;
  double q = 0.0;     // success score Q: best fraction of satisfied goal literals
  int satisfied = 0;  // literals of the best option that hold ...
  int total = 0;      // ... out of its literals
  // Primitive action space only.
  int primitive_status = -1;                               // PrimitiveStatus of this step's primitive (-1: none ran)
  std::array<int, kPrimitiveStatuses> primitive_counts{};  // this episode's primitives by status
  bool policy_failure = false;                             // ended by repeated invalid actions
  int64_t physics_steps = 0;                               // physics steps this env step ran (a primitive runs many)
};

// The low-level (RL-VMC) action: 14 numbers in [-1, 1] (values outside are
// clipped; NaN is an error).
//   0-2  base velocity: forward, left (x 0.5 m/s), turn (x 1 rad/s), robot frame
//   3    torso lift velocity (x 0.1 m/s), integrated into a position target
//   4-10 arm joint velocities (x 1 rad/s), integrated into position targets
//   11   gripper: -1 closed .. +1 open (absolute finger position)
//   12-13 head pan, tilt velocities (x 1 rad/s), integrated into position targets
constexpr int kLowLevelActionSize = 14;

// Views into the vector env's buffers, valid until the next reset/step/recv.
struct Batch {
  const ArrayDict* obs;  // (size, ...) per field
  std::span<const float> rewards;
  std::span<const std::uint8_t> terminated, truncated;
  std::span<const int> env_ids;  // env id of each row
  std::span<const Info> infos;
  // same_step only: for rows whose episode ended, its last observation and info.
  const ArrayDict* final_obs;
  std::span<const Info> final_infos;
  int size() const { return static_cast<int>(env_ids.size()); }
};

}  // namespace chore
