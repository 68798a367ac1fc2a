#include "primitives/rrt_connect.hpp"

#include <ompl/base/goals/GoalState.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO2StateSpace.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <random>

namespace chore {
namespace {

namespace ob = ompl::base;
namespace og = ompl::geometric;

// OMPL keeps its generators in protected members; these subclasses seed them.
template <typename Base>
struct Seeded : Base {
  template <typename... Args>
  explicit Seeded(std::uint_fast32_t seed, Args&&... args) : Base(std::forward<Args>(args)...) {
    this->rng_.setLocalSeed(seed);
  }
};

// Gives every sampler OMPL allocates in `space` (and its components) its own
// seed, drawn in allocation order from `seeds`.
void seed_samplers(ob::StateSpace* space, std::shared_ptr<std::mt19937> seeds) {
  if (space->isCompound()) {
    for (const ob::StateSpacePtr& sub : space->as<ob::CompoundStateSpace>()->getSubspaces()) {
      seed_samplers(sub.get(), seeds);
    }
  } else if (space->getType() == ob::STATE_SPACE_SO2) {
    space->setStateSamplerAllocator([seeds](const ob::StateSpace* s) -> ob::StateSamplerPtr {
      return std::make_shared<Seeded<ob::SO2StateSampler>>((*seeds)(), s);
    });
  } else {
    space->setStateSamplerAllocator([seeds](const ob::StateSpace* s) -> ob::StateSamplerPtr {
      return std::make_shared<Seeded<ob::RealVectorStateSampler>>((*seeds)(), s);
    });
  }
}

}  // namespace

bool solve_and_simplify(og::SimpleSetup& setup, uint64_t seed, unsigned iterations) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  // The straight line first: often free, and then no search is needed.
  setup.setup();
  const ob::SpaceInformationPtr& info = setup.getSpaceInformation();
  const ob::State* from = setup.getProblemDefinition()->getStartState(0);
  const ob::State* to = setup.getProblemDefinition()->getGoal()->as<ob::GoalState>()->getState();
  if (info->checkMotion(from, to)) {
    og::PathGeometric direct(info, from, to);
    setup.getProblemDefinition()->clearSolutionPaths();
    setup.getProblemDefinition()->addSolutionPath(std::make_shared<og::PathGeometric>(direct));
    return true;
  }
  std::seed_seq sequence{static_cast<uint32_t>(seed), static_cast<uint32_t>(seed >> 32)};
  auto seeds = std::make_shared<std::mt19937>(sequence);
  seed_samplers(setup.getStateSpace().get(), seeds);
  const ob::SpaceInformationPtr& si = setup.getSpaceInformation();
  setup.setPlanner(std::make_shared<Seeded<og::RRTConnect>>((*seeds)(), si));
  unsigned count = 0;
  const ob::PlannerTerminationCondition stop([&count, iterations] { return ++count > iterations; });
  if (setup.solve(stop) != ob::PlannerStatus::EXACT_SOLUTION) return false;
  Seeded<og::PathSimplifier> simplifier((*seeds)(), si);
  // One pass of each (simplifyMax's repeated passes cost more than they gain
  // before the trajectory smoother rounds the corners anyway).
  og::PathGeometric& path = setup.getSolutionPath();
  simplifier.reduceVertices(path);
  simplifier.shortcutPath(path);
  return true;
}

}  // namespace chore
