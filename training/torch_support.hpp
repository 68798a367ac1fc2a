// Torch helpers shared by the torch translation units of training/ (ppo.cpp,
// sac.cpp, checkpoint_tensors.cpp): archives as checkpoint bytes, generators. Includes
// <torch/torch.h>: never include it from torch-free code.
#pragma once

#include <torch/torch.h>

#include <functional>
#include <string>

#include "policies/networks.hpp"

namespace chore {

struct CheckpointFile;

std::string archive_bytes(torch::serialize::OutputArchive& archive);
// Throws chore::Error naming `what` when the bytes are not a torch archive.
void read_archive(torch::serialize::InputArchive& archive, const std::string& bytes, const std::string& what);

// Pins torch's intra-op threads, seeds the global generator (the networks'
// initial weights are drawn from it next) and returns the trainer's own.
at::Generator seed_torch(uint64_t seed, int threads);

// A trainer's own generator (action sampling, minibatch order, replay
// sampling): two trainers in one process do not disturb each other.
void save_rng(torch::serialize::OutputArchive& archive, const at::Generator& generator);
void load_rng(torch::serialize::InputArchive& archive, at::Generator& generator);

// Loads the sub-archive `key` into `module`, checking every tensor's shape
// (libtorch would silently take another shape); throws chore::Error naming `what`.
void load_module(torch::nn::Module& module, torch::serialize::InputArchive& archive, const std::string& key,
                 const std::string& what);

// Where an algorithm's load_policy starts: the checkpoint's network spec, and
// its tensors read into `archive`; throws chore::Error naming the file.
NetworkSpec read_network(const CheckpointFile& file, torch::serialize::InputArchive& archive);

// Runs `load`, turning a torch exception (a missing name, a shape mismatch)
// into a chore::Error naming `what`.
void load_or_throw(const std::string& what, const std::function<void()>& load);

}  // namespace chore
