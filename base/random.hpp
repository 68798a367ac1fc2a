// Seeded random numbers that are the same on every platform: std::mt19937_64
// is fully specified, its distributions are not, so chore draws from the raw
// bits itself.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>

namespace chore {

using Rng = std::mt19937_64;

// The largest seed chore takes from a user: seeds derived from it (env i of a
// vector env: seed + i; eval's episode j of seed s: s * 10^6 + j) stay far
// from wrapping around 2^64.
inline constexpr uint64_t kMaxSeed = 1000000000000;

// Uniform in [lo, hi) from 53 random bits.
inline double uniform(Rng& rng, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(rng() >> 11) * 0x1.0p-53);
}

// Uniform integer in [0, n).
inline int uniform_index(Rng& rng, int n) {
  return static_cast<int>(uniform(rng, 0, n));
}

// Standard normals drawn in pairs (Box-Muller), handed out one at a time.
class Normals {
 public:
  explicit Normals(Rng& rng) : rng_(rng) {}
  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double r = std::sqrt(-2.0 * std::log(1.0 - uniform(rng_, 0, 1)));  // 1 - u in (0, 1]
    const double angle = 2.0 * M_PI * uniform(rng_, 0, 1);
    spare_ = r * std::sin(angle);
    has_spare_ = true;
    return r * std::cos(angle);
  }

 private:
  Rng& rng_;
  double spare_ = 0;
  bool has_spare_ = false;
};

// A seed for a stream of its own drawn from `seed` (SplitMix64's mixer): streams
// seeded with seed and seed + 1 share nothing.
inline uint64_t derive_seed(uint64_t seed, uint64_t stream) {
  uint64_t z = seed + 0x9e3779b97f4a7c15ull * (stream + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

}  // namespace chore
