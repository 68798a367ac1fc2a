// Torch helpers shared by the torch translation units of training/ (ppo.cpp,
// sac.cpp, checkpoint_tensors.cpp): tensors as checkpoint records, generators.
// Includes <torch/torch.h>: never include it from torch-free code.
#pragma once

#include <torch/torch.h>

#include <string>

#include "policies/networks.hpp"
#include "training/checkpoint.hpp"

namespace chore {

// Tensors as checkpoint records (checkpoint.hpp) and back. Every tensor read
// is checked against the one it replaces (type and shape), so a checkpoint
// of another network is an error naming the tensor, never a silent reshape.
void put_tensor(TensorRecords& records, const std::string& name, const torch::Tensor& tensor);
// `name`'s record as a tensor of `like`'s element type and shape.
torch::Tensor get_tensor(const CheckpointFile& file, const std::string& name, const torch::Tensor& like);
// Parameters and buffers as "PREFIX.KEY" (KEY as named_parameters names it).
void save_module(TensorRecords& records, const std::string& prefix, const torch::nn::Module& module);
void load_module(torch::nn::Module& module, const CheckpointFile& file, const std::string& prefix);
// Adam's per-parameter state (step, exp_avg, exp_avg_sq) as "PREFIX.G.I.*" for
// parameter I of group G; its options come from the run's config.
void save_adam(TensorRecords& records, const std::string& prefix, const torch::optim::Adam& adam);
void load_adam(torch::optim::Adam& adam, const CheckpointFile& file, const std::string& prefix);

// Pins torch's intra-op threads, seeds the global generator (the networks'
// initial weights are drawn from it next) and returns the trainer's own.
at::Generator seed_torch(uint64_t seed, int threads);

// A trainer's own generator (action sampling, minibatch order, replay
// sampling) as "rng": two trainers in one process do not disturb each other.
void save_rng(TensorRecords& records, const at::Generator& generator);
void load_rng(at::Generator& generator, const CheckpointFile& file);

}  // namespace chore
