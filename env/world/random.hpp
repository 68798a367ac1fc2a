// Seeded random numbers that are the same on every platform: std::mt19937_64
// is fully specified, its distributions are not, so chore draws from the raw
// bits itself.
#pragma once

#include <cstdint>
#include <random>

namespace chore {

using Rng = std::mt19937_64;

// Uniform in [lo, hi) from 53 random bits.
inline double uniform(Rng& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
}

// Uniform integer in [0, n).
inline int uniform_index(Rng& rng, int n) {
  return static_cast<int>(uniform(rng, 0, n));
}

}  // namespace chore
