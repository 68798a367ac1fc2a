#include "env/rewards.hpp"

#include <mujoco/mujoco.h>

#include <cmath>

#include "base/error.hpp"
#include "base/registry.hpp"

namespace chore {
namespace {

// Minus the distance (m) from the gripper to reach_target, a point fixed in
// the robot's base frame.
double reach(const RewardInputs& in) {
  const World& w = in.world;
  const Pose2 base = w.base_pose();
  const double c = std::cos(base.yaw), s = std::sin(base.yaw);
  const auto& t = in.config.reach_target;
  const double target[3] = {base.x + c * t[0] - s * t[1], base.y + s * t[0] + c * t[1], t[2]};
  const double* gripper = w.data()->site_xpos + 3 * w.robot()->gripper_site;
  return -mju_dist3(gripper, target);
}

}  // namespace

const std::vector<RewardKind>& reward_kinds() {
  static const std::vector<RewardKind> list = {
      // BEHAVIOR's potential reward: positive when a literal of the goal's
      // first option becomes true, negative when one is undone.
      {"activity", false, [](const RewardInputs& in) { return in.potential_after - in.potential_before; }},
      // A dense task for testing continuous-control learners.
      {"reach", true, reach},
  };
  return list;
}

const RewardKind& find_reward(const std::string& name) {
  return find_by_name(reward_kinds(), name, "reward");
}

}  // namespace chore
