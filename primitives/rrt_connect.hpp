// The planning step both planners share: OMPL's RRTConnect, then its path
// simplifier, quietly (OMPL logs to stdout by default) and reproducibly: OMPL
// seeds every sampler from one process-wide generator, so a path would depend
// on whatever planned before it, on any thread. Here every random number comes
// from `seed`, and planning stops after a number of iterations, not seconds.
#pragma once

#include <ompl/geometric/SimpleSetup.h>

#include <cstdint>

namespace chore {

// True when an exact path was found (then setup.getSolutionPath() holds it, shortened).
bool solve_and_simplify(ompl::geometric::SimpleSetup& setup, uint64_t seed, unsigned iterations);

}  // namespace chore
