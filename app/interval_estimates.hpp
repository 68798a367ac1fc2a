// Interval estimates over training runs, as Agarwal et al. recommend ("Deep
// Reinforcement Learning at the Edge of the Statistical Precipice", NeurIPS
// 2021; their rliable library): the interquartile mean and the mean with 95%
// stratified bootstrap confidence intervals, the probability of improvement
// with its interval, and performance profiles. Each function takes the scores
// of one task's runs (one cell of Table A.13: a stratum of one task, so the
// stratified bootstrap resamples runs); draws come from `seed`, so a report is
// the same every time it is written.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace chore {

struct Interval {
  double point = 0, lo = 0, hi = 0;  // the statistic on the runs; the bootstrap's 2.5th and 97.5th percentiles
};

inline constexpr int kBootstrapReps = 50000;  // rliable's default

double mean(const std::vector<double>& scores);
// scipy.stats.trim_mean(scores, 0.25), as rliable computes the IQM: the mean
// after dropping floor(n / 4) scores at each end (n < 4 drops none).
double interquartile_mean(const std::vector<double>& scores);
// Percentile bootstrap over runs (resampled with replacement); chore::Error
// for no runs.
Interval bootstrap_interval(const std::vector<double>& scores, double (*statistic)(const std::vector<double>&),
                            uint64_t seed, int reps = kBootstrapReps);
// P(X > Y) for a run X of `x` and a run Y of `y`, ties counting one half (the
// Mann-Whitney U statistic over |x||y|), with x's and y's runs resampled
// independently for the interval.
Interval probability_of_improvement(const std::vector<double>& x, const std::vector<double>& y, uint64_t seed,
                                    int reps = kBootstrapReps);
// The verdict on "X is better than Y" that P(X > Y)'s interval allows: "holds"
// (above 0.5), "does not hold" (below), "cannot tell at 95%" (0.5 inside it),
// or "too few runs to tell" where a method has fewer than kMinVerdictRuns runs
// (a bootstrap over one or two runs cannot see their spread: one run against
// one gives the interval [P, P]).
inline constexpr size_t kMinVerdictRuns = 3;
std::string improvement_verdict(const Interval& p, size_t fewest_runs);
// The fraction of runs scoring above each threshold.
std::vector<double> performance_profile(const std::vector<double>& scores, const std::vector<double>& thresholds);

}  // namespace chore
