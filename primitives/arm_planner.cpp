#include "primitives/arm_planner.hpp"

#include <mujoco/mujoco.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>

#include <memory>

#include "primitives/rrt_connect.hpp"

namespace chore {
namespace {

// A scratch mjData for collision queries, so the world is never touched.
class CollisionProbe {
 public:
  explicit CollisionProbe(const World& world)
      : model_(world.model()), data_(mj_makeData(model_), mj_deleteData),
        joints_(world.robot()->torso_and_arm()),
        robot_(model_->body_rootid[world.robot()->gripper_body]) {
    mj_copyData(data_.get(), model_, world.data());
  }

  bool collides(const double* q) {
    for (size_t k = 0; k < joints_.size(); ++k) data_->qpos[joints_[k]->qpos] = q[k];
    mj_kinematics(model_, data_.get());
    mj_collision(model_, data_.get());
    for (int c = 0; c < data_->ncon; ++c) {
      const mjContact& con = data_->contact[c];
      if (model_->body_rootid[model_->geom_bodyid[con.geom1]] == robot_ ||
          model_->body_rootid[model_->geom_bodyid[con.geom2]] == robot_) {
        return true;
      }
    }
    return false;
  }

 private:
  const mjModel* model_;
  std::unique_ptr<mjData, void (*)(mjData*)> data_;
  std::array<const RobotJoint*, 1 + Robot::kArmJoints> joints_;
  int robot_;
};

}  // namespace

bool arm_in_collision(const World& world, const ArmConfiguration& q) {
  CollisionProbe probe(world);
  return probe.collides(q.data());
}

ArmPath plan_arm_path(const World& world, const ArmConfiguration& goal, double time_limit) {
  namespace ob = ompl::base;
  namespace og = ompl::geometric;
  const auto joints = world.robot()->torso_and_arm();
  ArmPath out;
  ArmConfiguration start;
  for (size_t k = 0; k < joints.size(); ++k) start[k] = world.data()->qpos[joints[k]->qpos];
  auto probe = std::make_shared<CollisionProbe>(world);
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
  if (!solve_and_simplify(setup, time_limit)) {
    out.reason = "no collision-free arm path found in " + std::to_string(time_limit) + " s";
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
