#include "training/rank.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "base/error.hpp"

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

}  // namespace chore
