// The planning step both planners share: OMPL's RRTConnect, then its path
// simplifier, quietly (OMPL logs to stdout by default).
#pragma once

#include <ompl/geometric/SimpleSetup.h>

namespace chore {

// True when an exact path was found (then setup.getSolutionPath() holds it, shortened).
bool solve_and_simplify(ompl::geometric::SimpleSetup& setup, double time_limit);

}  // namespace chore
