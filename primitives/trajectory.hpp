// Trajectories: a motion planner's piecewise-linear path (joint space, or base x, y, yaw with yaw
// unwrapped) made smooth and timed, as samples that position controllers track.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace chore {

struct TrajectoryLimits {
  Eigen::VectorXd max_velocity;      // per dimension, > 0
  Eigen::VectorXd max_acceleration;  // per dimension, > 0
};

// Positions sampled every dt seconds: samples.front() is the path's start, samples.back() its end.
struct Trajectory {
  double dt = 0;
  std::vector<Eigen::VectorXd> samples;
  double duration() const;  // (samples.size() - 1) * dt, 0 if empty
};

// 1) densify the path so no dimension moves more than `resolution` between points;
// 2) smooth: minimise sum |x_i - p_i|^2 + weight * sum |x_{i-1} - 2x_i + x_{i+1}|^2 with the two end points fixed
//    (a banded SPD system, one solve for all dimensions: CHOLMOD); a smoothed path is accepted only if every point
//    passes `valid` (when given); otherwise the weight is halved (a few times) and finally the dense unsmoothed path
//    is used (the planner checked that one); smoothing = 0 keeps the dense path;
// 3) time-parameterise: speed bound along the path from max_velocity, forward/backward passes for max_acceleration
//    (starts and ends at rest; at most half of it goes to turning), resampled at dt by linear interpolation.
// Throws chore::Error on bad input: empty path, dimension mismatch, non-finite points, non-positive limits/dt/
// resolution, negative smoothing.
Trajectory make_trajectory(const std::vector<Eigen::VectorXd>& path, const TrajectoryLimits& limits, double dt,
                           double resolution, const std::function<bool(const Eigen::VectorXd&)>& valid = {},
                           double smoothing = 20.0);

}  // namespace chore
