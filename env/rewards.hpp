// The reward kinds (EnvConfig::reward), one entry each of one list
// (rewards.cpp): a name, what it needs, and the step's reward. Internal to env/.
#pragma once

#include <string>
#include <vector>

#include "env/env.hpp"

namespace chore {

// What a step's reward may depend on: the world after the step, and the
// activity's potential (BEHAVIOR's: 0 without an activity) before and after it.
struct RewardInputs {
  const EnvConfig& config;
  const World& world;
  double potential_before = 0, potential_after = 0;
};

struct RewardKind {
  std::string name;
  bool needs_robot = false;
  double (*reward)(const RewardInputs& inputs) = nullptr;
};

const std::vector<RewardKind>& reward_kinds();
// The kind named `name`; chore::Error naming the known ones.
const RewardKind& find_reward(const std::string& name);

}  // namespace chore
