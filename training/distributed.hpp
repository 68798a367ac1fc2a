// One rank of a data-parallel run, as DD-PPO (Wijmans et al., ICLR 2020)
// and habitat-lab run one: every rank steps envs of its own, computes its
// gradients, and the ranks average them before each optimizer step, so the
// parameters stay the same on all. The collectives are c10d's
// ProcessGroupGloo (LibTorch's, over TCP), met through a TCPStore on the
// first rank's host; which rank this process is comes from the environment
// a launcher sets (torchrun's variables, or Slurm's srun).
//
//   const RankInfo me = rank_from_environment();   // one rank when nothing says otherwise
//   Ranks ranks(me);                               // meets the others, or chore::Error
//   ranks.broadcast(params);                       // rank 0's parameters everywhere
//   ranks.mean(grads);                             // in place, before the optimizer step
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "training/rank.hpp"
#include "training/torch_support.hpp"

namespace chore {

// The ranks met: every collective waits at most `timeout` for the others,
// then throws chore::Error (a rank that died fails the run on every other
// rank, never hangs it).
class Ranks {
 public:
  static constexpr std::chrono::milliseconds kDefaultTimeout{std::chrono::minutes(5)};
  explicit Ranks(const RankInfo& info, std::chrono::milliseconds timeout = kDefaultTimeout);
  ~Ranks();
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  int rank() const { return info_.rank; }
  int size() const { return info_.world_size; }

  // Each tensor replaced by its mean over the ranks (one all-reduce of them
  // all, flattened into one buffer).
  void mean(const std::vector<torch::Tensor>& tensors);
  // Each tensor replaced by rank `root`'s.
  void broadcast(const std::vector<torch::Tensor>& tensors, int root = 0);
  // Whether every rank holds the same bytes in `tensors` (a hash of them,
  // its greatest and least over the ranks compared).
  bool same(const std::vector<torch::Tensor>& tensors);
  // Adds `amount` to the counter `key` in the ranks' store and returns its
  // value after (0: reads it); DD-PPO's count of the ranks done collecting.
  int64_t add(const std::string& key, int64_t amount);
  // Bytes sent per all-reduce of `tensors` (what mean() moves per rank, before
  // the ring's factor 2 (n - 1) / n).
  static int64_t bytes(const std::vector<torch::Tensor>& tensors);

 private:
  std::string where() const;  // "rank 1 of 2 (MASTER_ADDR:PORT)", for errors
  RankInfo info_;
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace chore
