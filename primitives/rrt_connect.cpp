#include "primitives/rrt_connect.hpp"

#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

namespace chore {

bool solve_and_simplify(ompl::geometric::SimpleSetup& setup, double time_limit) {
  ompl::msg::setLogLevel(ompl::msg::LOG_NONE);
  setup.setPlanner(std::make_shared<ompl::geometric::RRTConnect>(setup.getSpaceInformation()));
  if (setup.solve(time_limit) != ompl::base::PlannerStatus::EXACT_SOLUTION) return false;
  setup.simplifySolution();
  return true;
}

}  // namespace chore
