#include "primitives/arm_planner.hpp"

#include <mujoco/mujoco.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>

#include <algorithm>
#include <memory>

#include "primitives/rrt_connect.hpp"

namespace chore {

ArmCollisionChecker::ArmCollisionChecker(const World& world)
    : world_(world), model_(world.model()), data_(world.scratch(1)),
      robot_(model_->body_rootid[world.robot()->gripper_body]) {
  // Kinematics and collision read positions only.
  mju_copy(data_->qpos, world.data()->qpos, model_->nq);
  mju_copy(data_->mocap_pos, world.data()->mocap_pos, 3 * model_->nmocap);
  mju_copy(data_->mocap_quat, world.data()->mocap_quat, 4 * model_->nmocap);
  const int held = world.carried_object();
  if (held >= 0) held_ = world.scene().objects()[held].body;
}

bool ArmCollisionChecker::collides(const double* q, const Pose2* base) {
  mjData* d = data_;
  const Robot& r = *world_.robot();
  if (base) {
    d->qpos[r.base_x.qpos] = base->x;
    d->qpos[r.base_y.qpos] = base->y;
    d->qpos[r.base_yaw.qpos] = base->yaw;
  }
  const auto joints = r.torso_and_arm();
  for (size_t k = 0; k < joints.size(); ++k) d->qpos[joints[k]->qpos] = q[k];
  mj_kinematics(model_, d);
  if (held_ >= 0) {
    world_.carry_grasped(d);
    mj_kinematics(model_, d);
  }
  mj_collision(model_, d);
  for (int c = 0; c < d->ncon; ++c) {
    const int r1 = model_->body_rootid[model_->geom_bodyid[d->contact[c].geom1]];
    const int r2 = model_->body_rootid[model_->geom_bodyid[d->contact[c].geom2]];
    const bool mine1 = r1 == robot_ || r1 == held_, mine2 = r2 == robot_ || r2 == held_;
    if (mine1 != mine2) return true;  // the robot and its load against anything else
  }
  return false;
}


bool arm_in_collision(const World& world, const ArmConfiguration& q) {
  return ArmCollisionChecker(world).collides(q.data());
}

ArmPath plan_arm_path(const World& world, const ArmConfiguration& goal, uint64_t seed,
                      unsigned iterations) {
  namespace ob = ompl::base;
  namespace og = ompl::geometric;
  const auto joints = world.robot()->torso_and_arm();
  ArmPath out;
  // Tracked joints sit a hair outside their limits at times (the torso sags
  // below 0 under gravity): OMPL would refuse such a start.
  ArmConfiguration start = arm_configuration(world);
  for (size_t k = 0; k < joints.size(); ++k) start[k] = std::clamp(start[k], joints[k]->low, joints[k]->high);
  auto probe = std::make_shared<ArmCollisionChecker>(world);
  if (probe->collides(start.data())) {
    out.reason = "the arm's start configuration is in collision";
    return out;
  }
  if (probe->collides(goal.data())) {
    out.reason = "the arm's goal configuration is in collision";
    return out;
  }
  auto space = std::make_shared<ob::RealVectorStateSpace>(static_cast<unsigned>(joints.size()));
  ob::RealVectorBounds bounds(static_cast<unsigned>(joints.size()));
  for (size_t k = 0; k < joints.size(); ++k) {
    bounds.setLow(k, joints[k]->low);
    bounds.setHigh(k, joints[k]->high);
  }
  space->setBounds(bounds);
  og::SimpleSetup setup(space);
  setup.setStateValidityChecker([probe](const ob::State* s) {
    return !probe->collides(s->as<ob::RealVectorStateSpace::StateType>()->values);
  });
  setup.getSpaceInformation()->setStateValidityCheckingResolution(0.005);
  ob::ScopedState<> from(space), to(space);
  for (size_t k = 0; k < joints.size(); ++k) {
    from[k] = start[k];
    to[k] = goal[k];
  }
  setup.setStartAndGoalStates(from, to);
  if (!solve_and_simplify(setup, seed, iterations)) {
    out.reason = "no collision-free arm path found in " + std::to_string(iterations) + " iterations";
    return out;
  }
  for (const ob::State* s : setup.getSolutionPath().getStates()) {
    ArmConfiguration q;
    for (size_t k = 0; k < joints.size(); ++k) q[k] = s->as<ob::RealVectorStateSpace::StateType>()->values[k];
    out.waypoints.push_back(q);
  }
  out.success = true;
  return out;
}

}  // namespace chore
