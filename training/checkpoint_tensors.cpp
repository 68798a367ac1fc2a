// The torch side of checkpoints (checkpoint.hpp, torch_support.hpp): tensors
// as records and back with their types and shapes checked, modules, Adam's
// state, the trainers' RNG state, and the policy a checkpoint holds.
#include <cstring>

#include "base/error.hpp"
#include "policies/networks.hpp"
#include "training/checkpoint.hpp"
#include "training/torch_support.hpp"
#include "training/trainer.hpp"

namespace chore {

namespace {

ElementType element_type(const torch::Tensor& t) {
  switch (t.scalar_type()) {
    case torch::kUInt8:
      return ElementType::uint8;
    case torch::kInt64:
      return ElementType::int64;
    case torch::kFloat32:
      return ElementType::float32;
    case torch::kFloat64:
      return ElementType::float64;
    default:
      throw Error(std::string("checkpoint: no element type for torch's ") + c10::toString(t.scalar_type()));
  }
}

const char* element_type_name(ElementType type) {
  static const char* const names[] = {"uint8", "int64", "float32", "float64"};
  return names[static_cast<int>(type)];
}

// Adam's state key for a parameter (torch/optim/serialize.h keys it so).
std::string adam_key(const torch::Tensor& parameter) {
  return c10::guts::to_string(parameter.unsafeGetTensorImpl());
}

}  // namespace

void put_tensor(TensorRecords& records, const std::string& name, const torch::Tensor& tensor) {
  const torch::Tensor t = tensor.detach().cpu().contiguous();
  TensorRecord& r = records[name];
  r.type = element_type(t);
  r.shape = t.sizes().vec();
  r.bytes.assign(static_cast<const char*>(t.data_ptr()), t.nbytes());
}

torch::Tensor get_tensor(const CheckpointFile& file, const std::string& name, const torch::Tensor& like) {
  const TensorRecord& r = file.tensor(name);
  const std::string where = "checkpoint " + file.path + ": tensor '" + name + "'";
  if (r.type != element_type(like)) {
    throw Error(where + " is " + element_type_name(r.type) + ", the network expects " +
                element_type_name(element_type(like)));
  }
  if (r.shape != like.sizes().vec()) {
    throw Error(where + " has shape " + c10::str(c10::IntArrayRef(r.shape)) + ", the network expects " +
                c10::str(like.sizes()));
  }
  torch::Tensor t = torch::empty(like.sizes(), like.options().requires_grad(false));
  std::memcpy(t.data_ptr(), r.bytes.data(), r.bytes.size());
  return t;
}

void save_module(TensorRecords& records, const std::string& prefix, const torch::nn::Module& module) {
  for (const auto& p : module.named_parameters()) put_tensor(records, prefix + "." + p.key(), p.value());
  for (const auto& b : module.named_buffers()) put_tensor(records, prefix + "." + b.key(), b.value());
}

void load_module(torch::nn::Module& module, const CheckpointFile& file, const std::string& prefix) {
  torch::NoGradGuard no_grad;
  for (auto& p : module.named_parameters()) p.value().copy_(get_tensor(file, prefix + "." + p.key(), p.value()));
  for (auto& b : module.named_buffers()) b.value().copy_(get_tensor(file, prefix + "." + b.key(), b.value()));
}

void save_adam(TensorRecords& records, const std::string& prefix, const torch::optim::Adam& adam) {
  for (size_t g = 0; g < adam.param_groups().size(); ++g) {
    const std::vector<torch::Tensor>& params = adam.param_groups()[g].params();
    for (size_t i = 0; i < params.size(); ++i) {
      const auto it = adam.state().find(adam_key(params[i]));
      if (it == adam.state().end()) continue;  // no step taken yet
      const auto& state = static_cast<const torch::optim::AdamParamState&>(*it->second);
      const std::string name = prefix + "." + std::to_string(g) + "." + std::to_string(i);
      put_tensor(records, name + ".step", torch::tensor(state.step(), torch::kInt64));
      put_tensor(records, name + ".exp_avg", state.exp_avg());
      put_tensor(records, name + ".exp_avg_sq", state.exp_avg_sq());  // amsgrad is off: no max_exp_avg_sq
    }
  }
}

void load_adam(torch::optim::Adam& adam, const CheckpointFile& file, const std::string& prefix) {
  adam.state().clear();
  for (size_t g = 0; g < adam.param_groups().size(); ++g) {
    const std::vector<torch::Tensor>& params = adam.param_groups()[g].params();
    for (size_t i = 0; i < params.size(); ++i) {
      const std::string name = prefix + "." + std::to_string(g) + "." + std::to_string(i);
      if (!file.tensors.contains(name + ".step")) continue;
      auto state = std::make_unique<torch::optim::AdamParamState>();
      const int64_t step = get_tensor(file, name + ".step", torch::tensor(int64_t{0})).item<int64_t>();
      state->step(within<int64_t>("checkpoint " + file.path + ": " + name + ".step", step, 0, 1000000000000));
      state->exp_avg(get_tensor(file, name + ".exp_avg", params[i]));
      state->exp_avg_sq(get_tensor(file, name + ".exp_avg_sq", params[i]));
      adam.state()[adam_key(params[i])] = std::move(state);
    }
  }
}

at::Generator seed_torch(uint64_t seed, int threads) {
  torch::set_num_threads(threads);
  torch::manual_seed(seed);
  return at::detail::createCPUGenerator(seed);
}

void save_rng(TensorRecords& records, const at::Generator& generator) {
  put_tensor(records, "rng", generator.get_state());
}

void load_rng(at::Generator& generator, const CheckpointFile& file) {
  const torch::Tensor state = get_tensor(file, "rng", generator.get_state());
  try {
    generator.set_state(state);
  } catch (const c10::Error& e) {
    throw Error("checkpoint " + file.path + ": tensor 'rng': " + e.what_without_backtrace());
  }
}

void set_policy_threads(int threads) {
  if (threads < 1) throw Error("policy threads must be at least 1, got " + std::to_string(threads));
  torch::set_num_threads(threads);
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
