// Interval estimates against answers known by hand and by their statistics.
#include <gtest/gtest.h>

#include <cmath>

#include "app/interval_estimates.hpp"
#include "base/error.hpp"
#include "base/random.hpp"

namespace chore {
namespace {

TEST(IntervalEstimates, InterquartileMeanDropsAQuarterAtEachEndAsScipyTrimMean) {
  EXPECT_DOUBLE_EQ(interquartile_mean({8, 1, 7, 2, 6, 3, 5, 4}), 4.5);            // 3, 4, 5, 6
  EXPECT_DOUBLE_EQ(interquartile_mean({0, 0, 1, 1, 1, 1, 1, 1, 100, 100}), 1.0);  // drops 2 at each end
  EXPECT_DOUBLE_EQ(interquartile_mean({0.0, 0.3, 0.9}), 0.4);                     // n < 4: the mean
  EXPECT_DOUBLE_EQ(interquartile_mean({2, 9, 4, 1, 100}), 5.0);                   // n = 5: drops 1 each end
}

TEST(IntervalEstimates, BootstrapIntervalsHaveTheirStatisticsWidth) {
  const Interval constant = bootstrap_interval({0.4, 0.4, 0.4}, mean, 1, 2000);
  EXPECT_DOUBLE_EQ(constant.lo, 0.4);
  EXPECT_DOUBLE_EQ(constant.hi, 0.4);
  // The mean of 400 standard normals: its interval is about +-1.96 / sqrt(400) around the sample mean.
  Rng rng(7);
  Normals normal(rng);
  std::vector<double> scores(400);
  for (double& s : scores) s = normal();
  const Interval m = bootstrap_interval(scores, mean, 3, 4000);
  EXPECT_DOUBLE_EQ(m.point, mean(scores));
  EXPECT_NEAR(m.hi - m.lo, 2 * 1.96 / 20, 0.02);
  EXPECT_LT(m.lo, m.point);
  EXPECT_GT(m.hi, m.point);
  EXPECT_LT(m.lo, 0.0);
  EXPECT_GT(m.hi, 0.0);
  // Seeded: the same draws every time.
  const Interval again = bootstrap_interval(scores, mean, 3, 4000);
  EXPECT_EQ(again.lo, m.lo);
  EXPECT_EQ(again.hi, m.hi);
  EXPECT_THROW(bootstrap_interval({}, mean, 0, 10), Error);
}

TEST(IntervalEstimates, ProbabilityOfImprovementCountsTiesAsHalf) {
  EXPECT_DOUBLE_EQ(probability_of_improvement({1, 2, 3}, {0, 0, 0}, 0, 100).point, 1.0);
  EXPECT_DOUBLE_EQ(probability_of_improvement({0, 0, 0}, {0, 0, 0}, 0, 100).point, 0.5);
  // Pairs: 0.2 beats 0.1; 0.5 beats 0.1 and ties 0.5: (1 + 1.5) / 4.
  const Interval p = probability_of_improvement({0.2, 0.5}, {0.1, 0.5}, 0, 4000);
  EXPECT_DOUBLE_EQ(p.point, 2.5 / 4);
  EXPECT_GE(p.lo, 0.0);
  EXPECT_LE(p.hi, 1.0);
  EXPECT_LT(p.lo, p.point);
  // Separated runs: every resample says X is better.
  const Interval sure = probability_of_improvement({0.8, 0.9, 0.7}, {0.1, 0.2, 0.0}, 0, 1000);
  EXPECT_DOUBLE_EQ(sure.lo, 1.0);
}

TEST(IntervalEstimates, AVerdictIsWhatTheIntervalAllows) {
  EXPECT_EQ(improvement_verdict({0.9, 0.6, 1.0}, 3), "holds");
  EXPECT_EQ(improvement_verdict({0.1, 0.0, 0.4}, 5), "does not hold");
  EXPECT_EQ(improvement_verdict({0.6, 0.3, 0.9}, 10), "cannot tell at 95%");
  EXPECT_EQ(improvement_verdict({0.5, 0.5, 0.5}, 10), "cannot tell at 95%");  // every run tied
  // One run against one: the bootstrap's interval is the point, whatever the runs.
  const Interval one = probability_of_improvement({0.2}, {0.1}, 0, 100);
  EXPECT_DOUBLE_EQ(one.lo, 1.0);
  EXPECT_EQ(improvement_verdict(one, 1), "too few runs to tell");
  EXPECT_EQ(improvement_verdict({1.0, 1.0, 1.0}, 2), "too few runs to tell");
}

TEST(IntervalEstimates, PerformanceProfilesCountRunsAboveEachThreshold) {
  const std::vector<double> f = performance_profile({0.0, 0.25, 0.5, 1.0}, {0.0, 0.25, 0.75, 1.0});
  ASSERT_EQ(f.size(), 4u);
  EXPECT_DOUBLE_EQ(f[0], 0.75);
  EXPECT_DOUBLE_EQ(f[1], 0.5);
  EXPECT_DOUBLE_EQ(f[2], 0.25);
  EXPECT_DOUBLE_EQ(f[3], 0.0);
}

}  // namespace
}  // namespace chore
