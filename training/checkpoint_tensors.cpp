// The torch side of checkpoints (checkpoint.hpp, torch_support.hpp): archives
// as bytes, the trainers' RNG state, modules loaded with their shapes checked,
// and the policy a checkpoint holds.
#include <sstream>

#include "base/error.hpp"
#include "policies/networks.hpp"
#include "training/checkpoint.hpp"
#include "training/torch_support.hpp"
#include "training/trainer.hpp"

namespace chore {

std::string archive_bytes(torch::serialize::OutputArchive& archive) {
  std::ostringstream out;
  archive.save_to(out);
  return out.str();
}

void read_archive(torch::serialize::InputArchive& archive, const std::string& bytes, const std::string& what) {
  load_or_throw(what, [&] {
    std::istringstream in(bytes);
    archive.load_from(in);
  });
}

at::Generator seed_torch(uint64_t seed, int threads) {
  torch::set_num_threads(threads);
  torch::manual_seed(seed);
  return at::detail::createCPUGenerator(seed);
}

void save_rng(torch::serialize::OutputArchive& archive, const at::Generator& generator) {
  archive.write("rng", generator.get_state(), /*is_buffer=*/true);
}

void load_rng(torch::serialize::InputArchive& archive, at::Generator& generator) {
  torch::Tensor state;
  archive.read("rng", state, /*is_buffer=*/true);
  generator.set_state(state);
}

void load_or_throw(const std::string& what, const std::function<void()>& load) {
  try {
    load();
  } catch (const c10::Error& e) {
    throw Error(what + ": " + e.what_without_backtrace());
  }
}

void load_module(torch::nn::Module& module, torch::serialize::InputArchive& archive, const std::string& key,
                 const std::string& what) {
  std::vector<std::pair<std::string, std::vector<int64_t>>> expected;
  for (const auto& p : module.named_parameters()) expected.push_back({p.key(), p.value().sizes().vec()});
  for (const auto& b : module.named_buffers()) expected.push_back({b.key(), b.value().sizes().vec()});
  load_or_throw(what, [&] {
    torch::serialize::InputArchive sub;
    archive.read(key, sub);
    module.load(sub);
  });
  std::vector<torch::Tensor> loaded = module.parameters();
  for (const torch::Tensor& b : module.buffers()) loaded.push_back(b);
  for (size_t i = 0; i < expected.size(); ++i) {
    if (loaded[i].sizes().vec() != expected[i].second) {
      throw Error(what + ": tensor '" + key + "." + expected[i].first + "' has shape " + c10::str(loaded[i].sizes()) +
                  ", the network expects " + c10::str(c10::IntArrayRef(expected[i].second)));
    }
  }
}

void set_policy_threads(int threads) {
  if (threads < 1) throw Error("policy threads must be at least 1, got " + std::to_string(threads));
  torch::set_num_threads(threads);
}

NetworkSpec read_network(const CheckpointFile& file, torch::serialize::InputArchive& archive) {
  const NetworkSpec spec = read_checkpoint_meta(file).network;
  read_archive(archive, file.tensors, "checkpoint " + file.path);
  return spec;
}

LoadedPolicy load_policy(const std::string& checkpoint_path, bool sample) {
  return load_policy(read_checkpoint(checkpoint_path), sample);
}

LoadedPolicy load_policy(const CheckpointFile& file, bool sample) {
  const CheckpointMeta meta = read_checkpoint_meta(file);  // the baseline is one of baselines()
  return {.policy = algorithm_of(meta.config.baseline).load_policy(file, sample),
          .env = meta.config.env,
          .baseline = meta.config.baseline,
          .steps = meta.progress.steps};
}

}  // namespace chore
