#include "training/distributed.hpp"

#include <torch/csrc/distributed/c10d/ProcessGroupGloo.hpp>
#include <torch/csrc/distributed/c10d/TCPStore.hpp>

#include <algorithm>

#include "base/error.hpp"
#include "base/hash.hpp"

namespace chore {

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

int64_t Ranks::add(const std::string& key, int64_t amount) {
  try {
    return state_->store->add(key, amount);
  } catch (const std::exception& e) {
    throw Error(where() + ": the store did not answer (rank 0 gone?): " + e.what());
  }
}

int64_t Ranks::bytes(const std::vector<torch::Tensor>& tensors) {
  const torch::Tensor flat = flattened(tensors);
  return flat.numel() * flat.element_size();
}

}  // namespace chore
