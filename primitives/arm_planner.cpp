#include "primitives/arm_planner.hpp"

#include <mujoco/mujoco.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/SimpleSetup.h>

#include <algorithm>
#include <memory>

#include "primitives/base_planner.hpp"
#include "primitives/rrt_connect.hpp"
#include "world/object_geometry.hpp"

namespace chore {
namespace {

constexpr double kPlanningClearance = 0.015;  // m kept from everything along a planned arm path
constexpr double kEndpointSpan = 0.15;        // rad from its start or goal where it may be less

}  // namespace

ArmCollisionChecker::ArmCollisionChecker(const World& world)
    : world_(world), kinematics_(world), data_(world.scratch()) {
  const mjModel* m = world.model();
  const Robot& r = *world.robot();
  // Which geoms move with the robot: its own, and for the clearance those
  // below the torso joint, and the load's (its root body's).
  std::vector<unsigned char> mine(m->ngeom, 0);
  moved_by_arm_.assign(m->ngeom, 0);
  const int torso = m->jnt_bodyid[r.torso.joint];
  for (int g : kinematics_.robot_geoms()) {
    robot_and_load_.push_back(g);
    mine[g] = 1;
    int b = m->geom_bodyid[g];
    if (b == r.gripper_body || b == r.left_finger_body || b == r.right_finger_body) hand_and_load_.push_back(g);
    while (b != torso && m->body_rootid[b] != b) b = m->body_parentid[b];
    moved_by_arm_[g] = b == torso;
  }
  for (int g : kinematics_.load_geoms()) {
    // Of a load of several bodies (a cloth) only the part in the hand: the
    // rest hangs, drapes over what it meets and gives way.
    const int b = m->geom_bodyid[g];
    mine[g] = 1;
    if (m->body_rootid[b] != b) continue;
    robot_and_load_.push_back(g);
    hand_and_load_.push_back(g);
    moved_by_arm_[g] = 1;
  }
  whole_load_ = kinematics_.load_geoms();
  mju_copy(data_->geom_xpos, world.data()->geom_xpos, 3 * m->ngeom);
  mju_copy(data_->geom_xmat, world.data()->geom_xmat, 9 * m->ngeom);
  for (int g = 0; g < m->ngeom; ++g) {
    if (mine[g] || (!m->geom_contype[g] && !m->geom_conaffinity[g])) continue;
    const Aabb box = geom_aabb(world, g);
    others_.push_back({g, box.lo, box.hi, driven_over(world, g, box)});
  }
}

bool ArmCollisionChecker::collides(const double* q, const Pose2* base, double clearance) {
  ArmConfiguration joints;
  std::copy(q, q + joints.size(), joints.begin());
  kinematics_.set(base ? *base : world_.base_pose(), joints);
  return touches(robot_and_load_, -1, clearance);
}

bool ArmCollisionChecker::hand_touches(const ArmConfiguration& q, const Pose2* base, int ignored_object) {
  kinematics_.set(base ? *base : world_.base_pose(), q);
  return touches(hand_and_load_, ignored_object, 0.0);
}

// Broad phase by bounding spheres against world boxes, then MuJoCo's pair functions.
template <typename Visit>
bool ArmCollisionChecker::for_each_contact(const std::vector<int>& mine, int ignored_object, double clearance,
                                           Visit visit) {
  const mjModel* m = world_.model();
  mjData* d = data_;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
  for (int g : mine) {
    kinematics_.geom_pose(g, d->geom_xpos + 3 * g, d->geom_xmat + 9 * g);
    const Eigen::Vector3d c(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
    const Eigen::Vector3d r = Eigen::Vector3d::Constant(m->geom_rbound[g] + clearance);
    lo = lo.cwiseMin(c - r);
    hi = hi.cwiseMax(c + r);
  }
  mjPreContact found[mjMAXCONPAIR];
  mjContact contacts[mjMAXCONPAIR];  // only what the readers read is set (geoms, dist, pos, frame)
  for (const Box& other : others_) {
    if ((other.lo.array() > hi.array()).any() || (other.hi.array() < lo.array()).any()) continue;
    const int o = other.geom;
    if (ignored_object >= 0 && world_.scene().object_of_geom(o) == ignored_object) continue;
    for (int g : mine) {
      if (!((m->geom_contype[g] & m->geom_conaffinity[o]) || (m->geom_contype[o] & m->geom_conaffinity[g]))) continue;
      if (other.driven_over && !moved_by_arm_[g]) continue;
      const double extra = moved_by_arm_[g] ? clearance : 0.0;
      const double r = m->geom_rbound[g] + extra;
      const Eigen::Vector3d c(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
      if ((other.lo.array() > c.array() + r).any() || (other.hi.array() < c.array() - r).any()) continue;
      // MuJoCo's table takes the lower geom type first.
      const bool ordered = m->geom_type[g] <= m->geom_type[o];
      const int g1 = ordered ? g : o, g2 = ordered ? o : g;
      const mjfCollision collide = mjCOLLISIONFUNC[m->geom_type[g1]][m->geom_type[g2]];
      const double margin = std::max(m->geom_margin[g1], m->geom_margin[g2]) + extra;
      const int n = collide ? collide(m, d, found, g1, g2, margin) : 0;
      if (n <= 0) continue;
      for (int k = 0; k < n; ++k) {
        contacts[k].dist = found[k].dist;
        mju_copy3(contacts[k].pos, found[k].pos);
        mju_copy3(contacts[k].frame, found[k].normal);
        mju_copy3(contacts[k].frame + 3, found[k].tangent);
        contacts[k].geom[0] = g1;
        contacts[k].geom[1] = g2;
        contacts[k].efc_address = -1;
      }
      if (visit(contacts, n)) return true;
    }
  }
  return false;
}

Aabb ArmCollisionChecker::load_contacts(const ArmConfiguration& q, std::vector<mjContact>& contacts) {
  kinematics_.set(world_.base_pose(), q);
  contacts.clear();
  for_each_contact(whole_load_, -1, 0.0, [&](const mjContact* found, int n) {
    contacts.insert(contacts.end(), found, found + n);
    return false;
  });
  Aabb box;
  for (int g : whole_load_) box.grow(geom_aabb(world_.model(), g, data_->geom_xpos + 3 * g, data_->geom_xmat + 9 * g));
  return box;
}

bool ArmCollisionChecker::touches(const std::vector<int>& mine, int ignored_object, double clearance) {
  return for_each_contact(mine, ignored_object, clearance, [](const mjContact*, int) { return true; });
}

bool arm_in_collision(const World& world, const ArmConfiguration& q) {
  return ArmCollisionChecker(world).collides(q.data());
}

ArmPath plan_arm_path(const World& world, const ArmConfiguration& goal, uint64_t seed, unsigned iterations) {
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
  // Away from its ends a path keeps kPlanningClearance from everything: the
  // tracked arm lags its trajectory by a few millimetres and cuts corners.
  setup.setStateValidityChecker([probe, start, goal](const ob::State* s) {
    const double* q = s->as<ob::RealVectorStateSpace::StateType>()->values;
    double to_start = 0, to_goal = 0;
    for (size_t k = 0; k < start.size(); ++k) {
      to_start = std::max(to_start, std::abs(q[k] - start[k]));
      to_goal = std::max(to_goal, std::abs(q[k] - goal[k]));
    }
    return !probe->collides(q, nullptr, std::min(to_start, to_goal) < kEndpointSpan ? 0.0 : kPlanningClearance);
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
