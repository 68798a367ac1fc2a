// Torch archives as bytes for checkpoints (training/checkpoint.hpp), shared by
// the torch translation units of training/. Includes <torch/torch.h>: never
// include it from torch-free code.
#pragma once

#include <torch/torch.h>

#include <functional>
#include <string>

namespace chore {

std::string archive_bytes(torch::serialize::OutputArchive& archive);
// Throws chore::Error naming `what` when the bytes are not a torch archive.
void read_archive(torch::serialize::InputArchive& archive, const std::string& bytes, const std::string& what);

// The global CPU generator's state (sampling, minibatch order, initialisation).
void save_rng(torch::serialize::OutputArchive& archive);
void load_rng(torch::serialize::InputArchive& archive);

// Runs `load`, turning a torch exception (a missing name, a shape mismatch)
// into a chore::Error naming `what`.
void load_or_throw(const std::string& what, const std::function<void()>& load);

}  // namespace chore
