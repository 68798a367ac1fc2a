// chore::Policy: what chore's CLI (eval, video) and trainers call to act in a
// VectorEnv. No torch here, and none of the env's internals: a custom policy
// compiles against this header, env/types.hpp, env/spaces.hpp and
// primitives/primitive_types.hpp alone.
//
//   class MyPolicy : public chore::Policy {
//     void act(const chore::Batch& batch, std::span<float> actions) override;
//   };
//   CHORE_POLICY_PLUGIN(MyPolicy)   // in a shared library: chore eval --policy-plugin lib.so
//
// act() sees one VectorEnv result: the batched observation arrays (views into
// the vector env's buffers: rgb (B,H,W,3) uint8, depth (B,H,W) float32,
// proprio, is_grasping, action_mask for the primitive action space when
// observed), the env id of each row and the infos; it writes one action per
// row, row-major (B x action size floats; a Discrete action is its index as a
// float, as VectorEnv::step takes it).
#pragma once

#include <cstdio>
#include <exception>
#include <span>

#include "env/spaces.hpp"
#include "env/types.hpp"

// The version of the plugin API: this header's, env/types.hpp's and
// env/spaces.hpp's types as a plugin sees them. A plugin built against another
// version is refused when it is loaded (policies/plugin.hpp). Raise it when
// any of those layouts or the Policy interface change.
#define CHORE_POLICY_API_VERSION 2

namespace chore {

class Policy {
 public:
  virtual ~Policy() = default;
  virtual void act(const Batch& batch, std::span<float> actions) = 0;
  // These envs start new episodes: forget their recurrent or history state.
  virtual void reset(std::span<const int> env_ids) {}
};

// What a plugin's factory is told: the spaces of one env, and the text given
// to --policy-options (empty when none).
struct PolicySpec {
  const Space* observation_space;
  const Space* action_space;
  const char* options;
};

}  // namespace chore

// The plugin entry points (C linkage, so dlsym finds them by name): the API
// version the plugin was built against; the factory, which returns a new
// policy, or nullptr and a message in `error` (at most error_size bytes,
// NUL-terminated) when it cannot serve `spec`; and its deleter.
extern "C" {
using chore_policy_api_version_fn = int (*)();
using chore_create_policy_fn = chore::Policy* (*)(const chore::PolicySpec* spec, char* error, int error_size);
using chore_destroy_policy_fn = void (*)(chore::Policy* policy);
}

// Defines the entry points for a Policy class constructible from a PolicySpec.
#define CHORE_POLICY_PLUGIN(PolicyClass)                                                                      \
  extern "C" int chore_policy_api_version() {                                                                 \
    return CHORE_POLICY_API_VERSION;                                                                          \
  }                                                                                                           \
  extern "C" chore::Policy* chore_create_policy(const chore::PolicySpec* spec, char* error, int error_size) { \
    try {                                                                                                     \
      return new PolicyClass(*spec);                                                                          \
    } catch (const std::exception& e) {                                                                       \
      if (error && error_size > 0) {                                                                          \
        std::snprintf(error, static_cast<size_t>(error_size), "%s", e.what());                                \
      }                                                                                                       \
      return nullptr;                                                                                         \
    }                                                                                                         \
  }                                                                                                           \
  extern "C" void chore_destroy_policy(chore::Policy* policy) {                                               \
    delete policy;                                                                                            \
  }
