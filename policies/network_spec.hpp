// What the baselines' networks are built for (policies/networks.hpp builds
// them): saved in checkpoints to rebuild them. Torch-free, so checkpoint
// metadata is read and checked without LibTorch (and fuzzed by clang).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>

#include "env/spaces.hpp"

namespace chore {

struct NetworkSpec {
  int height = 0, width = 0;  // image size; 0: no image observed
  int state_size = 0;         // is_grasping (1) then proprio (30), as observed
  int feature_size = 128;     // the MLP's output (Figure A.11)
  int frames = 1;             // observations the encoder takes: this step's and frames - 1 before it
  int history = 0;            // past primitives and their outcomes the policy sees (rl-prim-action-hist)
  int64_t num_actions = 0;    // PPO: Discrete size
  int action_size = 0;        // SAC: Box size
  int hidden = 256;           // SAC actor/critic MLP width
  // Whether the state is normalised by running statistics as the image is.
  // PPO's is not: appendix F.1 normalises "the image input" of RL-Prim.'s
  // encoder alone. SAC's is (proprio's joint positions and velocities differ
  // in scale), as are PPO checkpoints of before issue 53's correction.
  bool normalize_state = true;
  bool has_rgb() const { return height > 0; }
  // Bytes of one (stacked) observation as the networks' buffers hold it: uint8 RGB, float32 state.
  double observation_bytes() const { return frames * (3.0 * height * width + 4.0 * state_size); }
};
nlohmann::json to_json(const NetworkSpec& spec);
NetworkSpec network_spec_from_json(const nlohmann::json& j);  // throws chore::Error
// From an env's spaces: rgb and the state fields it observes (depth is unused).
NetworkSpec network_spec(const Space& observation, const Space& action, int frames, int history);

}  // namespace chore
