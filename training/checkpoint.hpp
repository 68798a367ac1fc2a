// Checkpoints: one file each, written atomically (a temporary file in the same
// folder, fsync, rename), so a run killed at any moment leaves the last one whole.
//
// Layout (little-endian):
//   "CHORECKP"              8 bytes, magic
//   version                 uint32 (kCheckpointVersion)
//   meta length, meta       uint64 + JSON: baseline, train config (env config
//                           included), network spec, step count, episode statistics
//   tensor count            uint64, then per tensor, in name order:
//     name                  uint32 length + bytes ("net.encoder.mlp.0.weight")
//     element type, rank    uint8 (ElementType), uint8 (at most kMaxTensorRank)
//     shape                 int64 x rank
//     data                  uint64 length + the elements, row-major
//   checksum                uint64 FNV-1a of all bytes before it
// The tensors: "net" (PPO) or "critic", "critic_target", "actor", "log_alpha"
// (SAC) with the normalisers' statistics as buffers; the optimizers' states;
// the trainer's RNG state; SAC's replay buffer (checkpoint_tensors.cpp).
// A corrupt, truncated or incompatible file is a chore::Error naming the file.
//
// All of it is read and checked by chore's own code without LibTorch
// (checkpoint.cpp, fuzzed by clang): no TorchScript archive is parsed, as
// torch's reader of those crashes on crafted input (tests/fuzz/corpus).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "env/env.hpp"
#include "policies/network_spec.hpp"
#include "policies/policy.hpp"
#include "training/trainer.hpp"

namespace chore {

constexpr uint32_t kCheckpointVersion = 2;  // 1: the tensors were a TorchScript archive
constexpr int kMaxTensorRank = 8;

// One array of a checkpoint: its element type, shape and little-endian bytes.
enum class ElementType : uint8_t { uint8, int64, float32, float64 };
size_t element_size(ElementType type);
struct TensorRecord {
  ElementType type = ElementType::float32;
  std::vector<int64_t> shape;
  std::string bytes;
};
using TensorRecords = std::map<std::string, TensorRecord>;

struct CheckpointFile {
  nlohmann::json meta;
  TensorRecords tensors;
  std::string path;  // where it was read from (for messages)
  // The tensor `name`, or chore::Error naming the file and the name.
  const TensorRecord& tensor(const std::string& name) const;
};

// The largest checkpoint read: a SAC run's replay buffer of the paper's 300
// transitions at 128x128 is ~36 MB; 16 GiB leaves room for far larger
// buffers (--set sac.buffer=...) while bounding what a wrong path can cost.
inline constexpr uint64_t kMaxCheckpointBytes = uint64_t{16} << 30;

void write_checkpoint(const std::string& path, const CheckpointFile& checkpoint);
// A regular file of at most kMaxCheckpointBytes; chore::Error otherwise.
CheckpointFile read_checkpoint(const std::string& path);
// Removes the temporary files write_checkpoint left in `dir` when its process
// was killed mid-write (base/temp_file.hpp: checkpoint*.pt.tmp.PID.N whose
// PID is no longer running).
void remove_stale_checkpoint_temps(const std::string& dir);
// The same for a file's bytes; `path` names it in messages.
CheckpointFile parse_checkpoint(const std::string& bytes, const std::string& path);
// The checksum a file ends with: FNV-1a of its bytes before it.
uint64_t checkpoint_checksum(std::string_view bytes);

// A checkpoint's metadata, every field read and checked (the episode
// statistics too): what resuming and loading a policy start from. Throws
// chore::Error naming the file and the field.
struct CheckpointMeta {
  TrainConfig config;
  NetworkSpec network;
  RunProgress progress;
};
CheckpointMeta read_checkpoint_meta(const CheckpointFile& checkpoint);

// A trained policy for chore eval/video: PPO acts by argmax, SAC by tanh(mean),
// or, with `sample`, both draw from their distributions as in training (seeded
// by each episode's seed: policies/networks.hpp's ActingMode); `env` rebuilds
// the env it was trained in.
struct LoadedPolicy {
  std::unique_ptr<chore::Policy> policy;
  chore::EnvConfig env;
  std::string baseline;
  int64_t steps = 0;
};
LoadedPolicy load_policy(const std::string& checkpoint_path, bool sample = false);  // throws chore::Error
LoadedPolicy load_policy(const CheckpointFile& checkpoint, bool sample = false);
// Pins torch's intra-op threads (process-wide) for loaded policies: its OpenMP
// pool competes with the VectorEnv's workers and the renderer for the cores.
void set_policy_threads(int threads);

}  // namespace chore
