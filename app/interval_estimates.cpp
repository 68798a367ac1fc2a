#include "app/interval_estimates.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "base/error.hpp"
#include "base/random.hpp"

namespace chore {
namespace {

std::vector<double> resample(const std::vector<double>& scores, Rng& rng) {
  std::vector<double> drawn(scores.size());
  for (double& d : drawn) d = scores[uniform_index(rng, static_cast<int>(scores.size()))];
  return drawn;
}

// The 2.5th and 97.5th percentiles, interpolated linearly (numpy's default).
Interval percentiles(double point, std::vector<double> draws) {
  std::sort(draws.begin(), draws.end());
  const auto at = [&](double q) {
    const double pos = q * static_cast<double>(draws.size() - 1);
    const size_t i = static_cast<size_t>(pos);
    const double frac = pos - static_cast<double>(i);
    return i + 1 < draws.size() ? draws[i] + frac * (draws[i + 1] - draws[i]) : draws[i];
  };
  return {point, at(0.025), at(0.975)};
}

void check_runs(const std::vector<double>& scores, const char* what) {
  if (scores.empty()) throw Error(std::string("interval estimates: no runs for ") + what);
}

}  // namespace

double mean(const std::vector<double>& scores) {
  return scores.empty() ? 0 : std::accumulate(scores.begin(), scores.end(), 0.0) / static_cast<double>(scores.size());
}

double interquartile_mean(const std::vector<double>& runs) {
  std::vector<double> scores = runs;
  std::sort(scores.begin(), scores.end());
  const size_t cut = scores.size() / 4;
  return mean(std::vector<double>(scores.begin() + static_cast<std::ptrdiff_t>(cut),
                                  scores.end() - static_cast<std::ptrdiff_t>(cut)));
}

Interval bootstrap_interval(const std::vector<double>& scores, double (*statistic)(const std::vector<double>&),
                            uint64_t seed, int reps) {
  check_runs(scores, "a bootstrap interval");
  Rng rng(seed);
  std::vector<double> draws(reps);
  for (double& d : draws) d = statistic(resample(scores, rng));
  return percentiles(statistic(scores), std::move(draws));
}

Interval probability_of_improvement(const std::vector<double>& x, const std::vector<double>& y, uint64_t seed,
                                    int reps) {
  check_runs(x, "the probability of improvement (X)");
  check_runs(y, "the probability of improvement (Y)");
  const auto p = [](const std::vector<double>& a, const std::vector<double>& b) {
    double wins = 0;
    for (double u : a)
      for (double v : b) wins += u > v ? 1.0 : u == v ? 0.5 : 0.0;
    return wins / static_cast<double>(a.size() * b.size());
  };
  Rng rng(seed);
  std::vector<double> draws(reps);
  for (double& d : draws) {
    const std::vector<double> a = resample(x, rng);
    d = p(a, resample(y, rng));
  }
  return percentiles(p(x, y), std::move(draws));
}

std::string improvement_verdict(const Interval& p, size_t fewest_runs) {
  if (fewest_runs < kMinVerdictRuns) return "too few runs to tell";
  return p.lo > 0.5 ? "holds" : p.hi < 0.5 ? "does not hold" : "cannot tell at 95%";
}

std::vector<double> performance_profile(const std::vector<double>& scores, const std::vector<double>& thresholds) {
  std::vector<double> fractions;
  for (double t : thresholds) {
    const auto above = std::count_if(scores.begin(), scores.end(), [&](double s) { return s > t; });
    fractions.push_back(scores.empty() ? 0 : static_cast<double>(above) / static_cast<double>(scores.size()));
  }
  return fractions;
}

}  // namespace chore
