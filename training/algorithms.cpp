// The algorithms' registry (the baselines' is training/baselines.cpp), and
// the trainers made from it. Apart from trainer.cpp, whose configs and
// statistics need no LibTorch: this file's list links the torch trainers.
#include "base/error.hpp"
#include "base/registry.hpp"
#include "training/checkpoint.hpp"
#include "training/trainer.hpp"

namespace chore {

// The algorithms (one file each; the baselines are in training/baselines.cpp):
// a new one is a line here.
Algorithm ppo_algorithm();  // training/ppo.cpp
Algorithm sac_algorithm();  // training/sac.cpp

const std::vector<Algorithm>& algorithms() {
  static const std::vector<Algorithm> list = {ppo_algorithm(), sac_algorithm()};
  return list;
}

const Algorithm& algorithm_of(const std::string& baseline) {
  const std::string& name = find_by_name(baselines(), baseline, "baseline").algorithm;
  for (const Algorithm& a : algorithms()) {
    if (a.name == name) return a;
  }
  throw Error("baseline '" + baseline + "': no algorithm '" + name + "'");
}

std::unique_ptr<Trainer> make_trainer(const TrainConfig& config) {
  if (config.num_envs < 1) throw Error("train: --envs must be at least 1");
  if (config.threads < 1) throw Error("train: --threads must be at least 1");
  return algorithm_of(config.baseline).make(config, nullptr);  // names an unknown baseline
}

std::unique_ptr<Trainer> resume_trainer(const std::string& checkpoint, const RankInfo& rank) {
  const CheckpointFile file = read_checkpoint(checkpoint);
  TrainConfig config = read_checkpoint_meta(file).config;
  config.rank = rank;
  try {
    return algorithm_of(config.baseline).make(config, &file);
  } catch (const nlohmann::json::exception& e) {
    throw Error("checkpoint " + checkpoint + ": bad metadata: " + e.what());
  }
}

}  // namespace chore
