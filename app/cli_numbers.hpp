// Numbers on the command line, checked as text before CLI11 converts them:
// a sign on a count, an exponent, a fraction or a value past the option's
// range is an error naming the option and the range, never a wrap-around or a
// silent clamp (--seed -5 is not 2^64 - 5). --help states each range.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>

namespace chore {

// An integer in [low, high], written in decimal digits (a leading '-' where
// low < 0).
CLI::Validator integer_in(int64_t low, int64_t high);
// A seed: an integer in [0, kMaxSeed] (base/random.hpp).
CLI::Validator seed_number();
// A real number in [low, high] (decimal or exponent notation, finite).
CLI::Validator real_in(double low, double high);

}  // namespace chore
