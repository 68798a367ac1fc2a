#include "primitives/trajectory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "test_util.hpp"

namespace chore {
namespace {

using Eigen::VectorXd;

constexpr double kDt = 1.0 / 30;

VectorXd vec(std::initializer_list<double> values) {
  VectorXd v(values.size());
  Eigen::Index i = 0;
  for (double x : values) v[i++] = x;
  return v;
}

TrajectoryLimits uniform_limits(Eigen::Index dims, double velocity, double acceleration) {
  return {VectorXd::Constant(dims, velocity), VectorXd::Constant(dims, acceleration)};
}

const std::vector<VectorXd> kCorner = {vec({0, 0}), vec({1, 0}), vec({1, 1})};  // an L: along x, then along y

double closest_approach(const Trajectory& t, const VectorXd& point) {
  double closest = std::numeric_limits<double>::infinity();
  for (const VectorXd& s : t.samples) closest = std::min(closest, (s - point).norm());
  return closest;
}

// Finite differences between consecutive samples against the limits, per dimension.
void expect_within_limits(const Trajectory& t, const TrajectoryLimits& limits) {
  ASSERT_GE(t.samples.size(), 2u);
  for (size_t i = 1; i < t.samples.size(); ++i) {
    const VectorXd velocity = (t.samples[i] - t.samples[i - 1]) / t.dt;
    EXPECT_TRUE((velocity.cwiseAbs().array() <= limits.max_velocity.array() * (1 + 1e-6)).all())
        << "sample " << i << ": velocity " << velocity.transpose();
  }
  // Turning on a polyline is modelled, not exact, at sample level: allow 1%.
  for (size_t i = 1; i + 1 < t.samples.size(); ++i) {
    const VectorXd acceleration = (t.samples[i + 1] - 2 * t.samples[i] + t.samples[i - 1]) / (t.dt * t.dt);
    EXPECT_TRUE((acceleration.cwiseAbs().array() <= limits.max_acceleration.array() * 1.01).all())
        << "sample " << i << ": acceleration " << acceleration.transpose();
  }
}

TEST(Trajectory, EndpointsAreExactlyPreserved) {
  const std::vector<VectorXd> path = {vec({0.1, -0.3, 0.7}), vec({0.5, 0.2, -0.4}), vec({-0.2, 0.9, 0.3})};
  const Trajectory t = make_trajectory(path, uniform_limits(3, 1.0, 2.0), kDt, 0.05);
  EXPECT_EQ(t.dt, kDt);
  ASSERT_GE(t.samples.size(), 2u);
  EXPECT_TRUE(t.samples.front() == path.front());
  EXPECT_TRUE(t.samples.back() == path.back());
  EXPECT_DOUBLE_EQ(t.duration(), double(t.samples.size() - 1) * kDt);
}

TEST(Trajectory, AStraightLineStaysOnTheLine) {
  // Collinear points, unevenly spaced: smoothing may slide points along the line but never off it.
  const VectorXd a = vec({0.2, -1.0, 0.5}), b = vec({1.4, 0.6, -0.3});
  const std::vector<VectorXd> path = {a, a + 0.1 * (b - a), a + 0.75 * (b - a), b};
  const Trajectory t = make_trajectory(path, uniform_limits(3, 0.8, 1.5), kDt, 0.03);
  const VectorXd direction = (b - a).normalized();
  double progress = 0;
  for (const VectorXd& s : t.samples) {
    const double along = (s - a).dot(direction);
    EXPECT_LT((s - a - along * direction).norm(), 1e-9);
    EXPECT_GE(along, progress - 1e-12);  // never backwards
    progress = along;
  }
  EXPECT_NEAR(progress, (b - a).norm(), 1e-12);
}

TEST(Trajectory, StraightMovesFollowTheTrapezoidalProfile) {
  const TrajectoryLimits limits = uniform_limits(1, 1.0, 2.0);
  // Long enough to cruise: L / v + v / a.
  const Trajectory cruise = make_trajectory({vec({0}), vec({5})}, limits, kDt, 0.05);
  EXPECT_NEAR(cruise.duration(), 5.0 / 1.0 + 1.0 / 2.0, 2 * kDt);
  expect_within_limits(cruise, limits);
  // Too short to reach max_velocity: speed up for half the way, slow down for the other, 2 sqrt(L / a).
  const Trajectory hop = make_trajectory({vec({0}), vec({-0.2})}, limits, kDt, 0.05);
  EXPECT_NEAR(hop.duration(), 2 * std::sqrt(0.2 / 2.0), 2 * kDt);
  expect_within_limits(hop, limits);
  // Diagonal: y's velocity limit and x's acceleration limit bind, on a straight line through the plane:
  // cruise at (0.4, 0.1) for 2 / 0.4 s, plus 0.4 / 2 s of speeding up and slowing down.
  const TrajectoryLimits diagonal_limits{vec({1.0, 0.1}), vec({2.0, 2.0})};
  const Trajectory diagonal = make_trajectory({vec({0, 0}), vec({2, 0.5})}, diagonal_limits, kDt, 0.05);
  EXPECT_NEAR(diagonal.duration(), 2 / 0.4 + 0.4 / 2, 2 * kDt);
  expect_within_limits(diagonal, diagonal_limits);
}

TEST(Trajectory, VelocityAndAccelerationStayWithinPerDimensionLimits) {
  const TrajectoryLimits limits{vec({1.0, 0.5, 2.0, 0.3, 1.5, 0.8, 1.2, 0.6}),
                                vec({2.0, 1.0, 3.0, 0.5, 2.5, 1.5, 0.8, 1.0})};
  // A zigzag through 8-D joint space, with a sharp reversal in the middle.
  const std::vector<VectorXd> path = {vec({0, 0, 0, 0, 0, 0, 0, 0}), vec({0.8, -0.4, 1.2, 0.3, -0.6, 0.5, 0.2, -0.1}),
                                      vec({0.2, 0.6, 0.4, -0.3, 0.7, 0.9, -0.5, 0.4}),
                                      vec({0.8, -0.4, 1.2, 0.3, -0.6, 0.5, 0.2, -0.1}),
                                      vec({1.5, 0.1, -0.2, 0.1, 0.3, -0.4, 0.9, 0.7})};
  for (double smoothing : {20.0, 2.0, 0.0}) {
    SCOPED_TRACE(smoothing);
    const Trajectory t = make_trajectory(path, limits, kDt, 0.05, {}, smoothing);
    expect_within_limits(t, limits);
  }
  // The base: x, y (m) and unwrapped yaw (rad), turning past pi.
  const TrajectoryLimits base{vec({0.5, 0.5, 1.0}), vec({0.5, 0.5, 1.5})};
  const Trajectory t = make_trajectory({vec({0, 0, 3.0}), vec({1, 0.5, 3.6}), vec({1.2, 2, 4.2})}, base, kDt, 0.05);
  expect_within_limits(t, base);
}

TEST(Trajectory, SmoothingRoundsACorner) {
  const TrajectoryLimits limits = uniform_limits(2, 1.0, 2.0);
  // Unsmoothed, the path goes through the corner (slowly), so some sample is right at it.
  EXPECT_LT(closest_approach(make_trajectory(kCorner, limits, kDt, 0.05, {}, 0.0), vec({1, 0})), 0.005);
  // Smoothed, the corner is cut: every sample keeps away from it.
  const Trajectory t = make_trajectory(kCorner, limits, kDt, 0.05);
  EXPECT_GT(closest_approach(t, vec({1, 0})), 0.04);
  expect_within_limits(t, limits);
}

TEST(Trajectory, SmoothingNeverEntersWhatValidRejects) {
  const TrajectoryLimits limits = uniform_limits(2, 1.0, 2.0);
  // A disc inside the corner, clear of the L itself (0.05 away) but in the way of the fully smoothed cut.
  const VectorXd centre = vec({0.95, 0.05});
  const double radius = 0.03;
  int rejected = 0;
  const auto valid = [&](const VectorXd& x) {
    const bool ok = (x - centre).norm() > radius;
    rejected += !ok;
    return ok;
  };
  const Trajectory t = make_trajectory(kCorner, limits, kDt, 0.05, valid);
  EXPECT_GT(rejected, 0);  // the default weight was tried and refused
  EXPECT_GT(closest_approach(t, centre), radius);
  EXPECT_GT(closest_approach(t, vec({1, 0})), 0.01);  // a lighter smoothing still rounds the corner

  // When every smoothed path is refused, the dense path is used as it is.
  const Trajectory fallback = make_trajectory(kCorner, limits, kDt, 0.05, [](const VectorXd&) { return false; });
  const Trajectory unsmoothed = make_trajectory(kCorner, limits, kDt, 0.05, {}, 0.0);
  ASSERT_EQ(fallback.samples.size(), unsmoothed.samples.size());
  for (size_t i = 0; i < fallback.samples.size(); ++i) EXPECT_TRUE(fallback.samples[i] == unsmoothed.samples[i]);
}

TEST(Trajectory, APointOrRepeatedPointsGiveOneSample) {
  const TrajectoryLimits limits = uniform_limits(3, 1.0, 1.0);
  const VectorXd p = vec({0.3, -0.2, 1.0});
  for (const std::vector<VectorXd>& path : {std::vector<VectorXd>{p}, std::vector<VectorXd>{p, p, p}}) {
    const Trajectory t = make_trajectory(path, limits, kDt, 0.05);
    ASSERT_EQ(t.samples.size(), 1u);
    EXPECT_TRUE(t.samples[0] == p);
    EXPECT_EQ(t.duration(), 0.0);
  }
  // Repeats inside a path are ignored.
  const VectorXd q = vec({0.8, 0.1, 0.4});
  const Trajectory with = make_trajectory({p, p, q, q}, limits, kDt, 0.05);
  const Trajectory without = make_trajectory({p, q}, limits, kDt, 0.05);
  ASSERT_EQ(with.samples.size(), without.samples.size());
  for (size_t i = 0; i < with.samples.size(); ++i) EXPECT_TRUE(with.samples[i] == without.samples[i]);
}

TEST(Trajectory, IsDeterministic) {
  const TrajectoryLimits limits = uniform_limits(2, 1.0, 2.0);
  const Trajectory a = make_trajectory(kCorner, limits, kDt, 0.02);
  const Trajectory b = make_trajectory(kCorner, limits, kDt, 0.02);
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (size_t i = 0; i < a.samples.size(); ++i) EXPECT_TRUE(a.samples[i] == b.samples[i]);
}

TEST(Trajectory, BadInputIsAnError) {
  const TrajectoryLimits limits = uniform_limits(2, 1.0, 2.0);
  const auto error = [&](const std::vector<VectorXd>& path, const TrajectoryLimits& l, double dt, double resolution,
                         double smoothing = 20.0) {
    return test::error_of([&] { make_trajectory(path, l, dt, resolution, {}, smoothing); });
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error({}, limits, kDt, 0.05), "make_trajectory: empty path");
  EXPECT_EQ(error(kCorner, {vec({1, 1}), vec({1, 1, 1})}, kDt, 0.05),
            "make_trajectory: max_acceleration has 3 dimensions, max_velocity 2");
  EXPECT_EQ(error({vec({0, 0}), vec({1, 0, 0})}, limits, kDt, 0.05),
            "make_trajectory: path point 1 has 3 dimensions, the limits 2");
  EXPECT_EQ(error({vec({0, 0}), vec({1, nan})}, limits, kDt, 0.05), "make_trajectory: path point 1 is not finite");
  EXPECT_EQ(error(kCorner, {vec({1, 0}), vec({1, 1})}, kDt, 0.05),
            "make_trajectory: max_velocity[1] = 0, must be positive and finite");
  EXPECT_EQ(error(kCorner, {vec({1, 1}), vec({-2, 1})}, kDt, 0.05),
            "make_trajectory: max_acceleration[0] = -2, must be positive and finite");
  EXPECT_EQ(error(kCorner, {VectorXd(), VectorXd()}, kDt, 0.05), "make_trajectory: the limits have no dimensions");
  EXPECT_EQ(error(kCorner, limits, 0.0, 0.05), "make_trajectory: dt = 0, must be positive and finite");
  EXPECT_EQ(error(kCorner, limits, std::numeric_limits<double>::infinity(), 0.05),
            "make_trajectory: dt = inf, must be positive and finite");
  EXPECT_EQ(error(kCorner, limits, kDt, -0.1), "make_trajectory: resolution = -0.1, must be positive and finite");
  EXPECT_EQ(error(kCorner, limits, kDt, 0.05, -1.0), "make_trajectory: smoothing = -1, must be >= 0 and finite");
}

}  // namespace
}  // namespace chore
