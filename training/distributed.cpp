#include "training/distributed.hpp"

#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "base/error.hpp"
#include "base/hash.hpp"

extern char** environ;

namespace chore {
namespace {

std::map<std::string, std::string> process_environment() {
  std::map<std::string, std::string> out;
  for (char** e = environ; e && *e; ++e) {
    const char* eq = std::strchr(*e, '=');
    if (eq) out[std::string(*e, static_cast<size_t>(eq - *e))] = eq + 1;
  }
  return out;
}

// A whole number in [low, high] from variable `name`, or a chore::Error naming it.
int integer(const std::map<std::string, std::string>& env, const std::string& name, long low, long high) {
  const std::string& text = env.at(name);
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || v < low || v > high) {
    throw Error("distributed: " + name + "='" + text + "' is not a whole number in [" + std::to_string(low) + ", " +
                std::to_string(high) + "]");
  }
  return static_cast<int>(v);
}

}  // namespace

RankInfo rank_from_environment(const std::map<std::string, std::string>& env) {
  const auto has = [&](const char* name) { return env.count(name) > 0 && !env.at(name).empty(); };
  RankInfo info;
  constexpr long kMostRanks = 65536;
  if (has("WORLD_SIZE")) {
    info.source = "torchrun";
    info.world_size = integer(env, "WORLD_SIZE", 1, kMostRanks);
    if (!has("RANK")) throw Error("distributed: WORLD_SIZE is set but RANK is not");
    info.rank = integer(env, "RANK", 0, info.world_size - 1);
    if (info.world_size > 1 && !has("MASTER_ADDR"))
      throw Error("distributed: WORLD_SIZE=" + std::to_string(info.world_size) + " but MASTER_ADDR is not set");
  } else if (has("SLURM_NTASKS") && has("SLURM_PROCID")) {
    info.source = "slurm";
    info.world_size = integer(env, "SLURM_NTASKS", 1, kMostRanks);
    info.rank = integer(env, "SLURM_PROCID", 0, info.world_size - 1);
    if (!has("MASTER_ADDR") && !has("SLURM_LAUNCH_NODE_IPADDR") && info.world_size > 1)
      throw Error("distributed: Slurm runs " + std::to_string(info.world_size) +
                  " tasks but neither MASTER_ADDR nor SLURM_LAUNCH_NODE_IPADDR says where rank 0 is");
    if (!has("MASTER_ADDR") && has("SLURM_LAUNCH_NODE_IPADDR")) info.master_addr = env.at("SLURM_LAUNCH_NODE_IPADDR");
    if (!has("MASTER_PORT") && has("SLURM_JOB_ID"))
      info.master_port = 29500 + integer(env, "SLURM_JOB_ID", 0, std::numeric_limits<int>::max()) % 1000;
  } else {
    return info;
  }
  if (has("MASTER_ADDR")) info.master_addr = env.at("MASTER_ADDR");
  if (has("MASTER_PORT")) info.master_port = integer(env, "MASTER_PORT", 1, 65535);
  return info;
}

RankInfo rank_from_environment() {
  return rank_from_environment(process_environment());
}

struct Ranks::State {
  c10::intrusive_ptr<c10d::TCPStore> store;
  c10::intrusive_ptr<c10d::ProcessGroupGloo> group;
};

std::string Ranks::where() const {
  return "distributed: rank " + std::to_string(info_.rank) + " of " + std::to_string(info_.world_size) + " (" +
         info_.master_addr + ":" + std::to_string(info_.master_port) + ")";
}

Ranks::Ranks(const RankInfo& info, std::chrono::milliseconds timeout) : info_(info), state_(std::make_unique<State>()) {
  if (info.world_size < 1 || info.rank < 0 || info.rank >= info.world_size)
    throw Error(where() + ": the rank must be in [0, world size)");
  try {
    c10d::TCPStoreOptions store;
    store.port = static_cast<std::uint16_t>(info.master_port);
    store.isServer = info.rank == 0;
    store.numWorkers = info.world_size;
    store.waitWorkers = true;
    store.timeout = timeout;
    state_->store = c10::make_intrusive<c10d::TCPStore>(info.master_addr, store);
    auto options = c10d::ProcessGroupGloo::Options::create(timeout);
    // On one host, loopback; across hosts, the interface the host's name
    // resolves to (Gloo's default device).
    const bool local = info.master_addr == "127.0.0.1" || info.master_addr == "localhost";
    options->devices.push_back(local ? c10d::ProcessGroupGloo::createDeviceForHostname("127.0.0.1")
                                     : c10d::ProcessGroupGloo::createDefaultDevice());
    state_->group = c10::make_intrusive<c10d::ProcessGroupGloo>(state_->store, info.rank, info.world_size, options);
  } catch (const std::exception& e) {
    throw Error(where() + ": the ranks did not meet within " + std::to_string(timeout.count()) + " ms: " + e.what());
  }
}

Ranks::~Ranks() = default;

namespace {

// One buffer of them all: float32 where they all are (gradients: half the
// bytes on the wire), else float64.
torch::Tensor flattened(const std::vector<torch::Tensor>& tensors) {
  const bool single = std::all_of(tensors.begin(), tensors.end(),
                                  [](const torch::Tensor& t) { return t.scalar_type() == torch::kFloat32; });
  std::vector<torch::Tensor> parts;
  for (const torch::Tensor& t : tensors)
    parts.push_back(t.detach().reshape({-1}).to(single ? torch::kFloat32 : torch::kFloat64));
  return torch::cat(parts);
}

void scatter_back(const torch::Tensor& flat, const std::vector<torch::Tensor>& tensors) {
  torch::NoGradGuard no_grad;
  int64_t at = 0;
  for (const torch::Tensor& t : tensors) {
    t.copy_(flat.narrow(0, at, t.numel()).reshape(t.sizes()).to(t.scalar_type()));
    at += t.numel();
  }
}

}  // namespace

void Ranks::mean(const std::vector<torch::Tensor>& tensors) {
  if (size() == 1 || tensors.empty()) return;
  std::vector<torch::Tensor> flat = {flattened(tensors)};
  try {
    state_->group->allreduce(flat)->wait();
  } catch (const std::exception& e) {
    throw Error(where() + ": all-reduce failed (a rank gone?): " + e.what());
  }
  scatter_back(flat[0] / static_cast<double>(size()), tensors);
}

void Ranks::broadcast(const std::vector<torch::Tensor>& tensors, int root) {
  if (size() == 1 || tensors.empty()) return;
  std::vector<torch::Tensor> flat = {flattened(tensors)};
  try {
    c10d::BroadcastOptions options;
    options.rootRank = root;
    state_->group->broadcast(flat, options)->wait();
  } catch (const std::exception& e) {
    throw Error(where() + ": broadcast failed (a rank gone?): " + e.what());
  }
  scatter_back(flat[0], tensors);
}

bool Ranks::same(const std::vector<torch::Tensor>& tensors) {
  std::vector<uint64_t> each;
  for (const torch::Tensor& t : tensors) {
    const torch::Tensor c = t.detach().contiguous();
    each.push_back(fnv1a({static_cast<const char*>(c.data_ptr()), static_cast<size_t>(c.numel() * c.element_size())}));
  }
  const uint64_t h = fnv1a({reinterpret_cast<const char*>(each.data()), each.size() * sizeof(uint64_t)});
  if (size() == 1) return true;
  // The hash's greatest and least over the ranks, as one all-reduce (max of
  // h and of -h), in two 32-bit halves: a double holds them exactly.
  const double hi = static_cast<double>(h >> 32), lo = static_cast<double>(h & 0xffffffffu);
  std::vector<torch::Tensor> both = {torch::tensor({hi, lo, -hi, -lo}, torch::kFloat64)};
  try {
    c10d::AllreduceOptions options;
    options.reduceOp = c10d::ReduceOp::MAX;
    state_->group->allreduce(both, options)->wait();
  } catch (const std::exception& e) {
    throw Error(where() + ": comparing parameters failed (a rank gone?): " + e.what());
  }
  const auto v = both[0].accessor<double, 1>();
  return v[0] == -v[2] && v[1] == -v[3];
}

int64_t Ranks::bytes(const std::vector<torch::Tensor>& tensors) {
  return flattened(tensors).numel() * flattened(tensors).element_size();
}

}  // namespace chore
