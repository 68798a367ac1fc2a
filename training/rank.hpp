// Which rank of a data-parallel run this process is, as the launcher says
// (torchrun's variables, or Slurm's srun): torch-free, for configs and the
// command line. training/distributed.hpp meets the other ranks.
#pragma once

#include <map>
#include <string>

namespace chore {

struct RankInfo {
  int rank = 0, world_size = 1;
  std::string master_addr = "127.0.0.1";  // the TCPStore's host: rank 0's
  int master_port = 29500;
  std::string source = "none";  // where it was read: "torchrun", "slurm" or "none"
};

// WORLD_SIZE, RANK, MASTER_ADDR and MASTER_PORT (torchrun's and
// torch.distributed's names), else Slurm's SLURM_NTASKS and SLURM_PROCID
// with MASTER_ADDR, or else SLURM_LAUNCH_NODE_IPADDR (the node srun ran on:
// the allocation's first in a batch job), and MASTER_PORT or else 29500 plus
// the job id modulo 1000 (two jobs on one node meet apart); else one rank.
// `environment` maps variable names to values (the process's own by
// default). A malformed or inconsistent value is a chore::Error naming it.
RankInfo rank_from_environment(const std::map<std::string, std::string>& environment);
RankInfo rank_from_environment();

}  // namespace chore
