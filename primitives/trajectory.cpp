#include "primitives/trajectory.hpp"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "base/error.hpp"

namespace chore {

double Trajectory::duration() const {
  return samples.empty() ? 0.0 : double(samples.size() - 1) * dt;
}

namespace {

using Points = Eigen::MatrixXd;  // one point per row
using Validity = std::function<bool(const Eigen::VectorXd&)>;

constexpr int kSmoothingAttempts = 4;  // weight, weight/2, weight/4, weight/8; then the unsmoothed path
constexpr double kTurnShare = 0.5;     // of max_acceleration that turning may use; the rest changes the speed

void check_input(const std::vector<Eigen::VectorXd>& path, const TrajectoryLimits& limits, double dt, double resolution,
                 double smoothing) {
  const auto fail = [](const std::string& what) { throw Error("make_trajectory: " + what); };
  const auto require = [&](bool ok, const std::string& name, double value, const std::string& rule) {
    if (!ok || !std::isfinite(value)) fail(name + " = " + (std::ostringstream() << value).str() + ", must be " + rule);
  };
  if (path.empty()) fail("empty path");
  const Eigen::Index dims = limits.max_velocity.size();
  if (dims == 0) fail("the limits have no dimensions");
  if (limits.max_acceleration.size() != dims)
    fail("max_acceleration has " + std::to_string(limits.max_acceleration.size()) + " dimensions, max_velocity " +
         std::to_string(dims));
  for (Eigen::Index j = 0; j < dims; ++j) {
    const std::string index = "[" + std::to_string(j) + "]";
    require(limits.max_velocity[j] > 0, "max_velocity" + index, limits.max_velocity[j], "positive and finite");
    require(limits.max_acceleration[j] > 0, "max_acceleration" + index, limits.max_acceleration[j],
            "positive and finite");
  }
  for (size_t i = 0; i < path.size(); ++i) {
    if (path[i].size() != dims)
      fail("path point " + std::to_string(i) + " has " + std::to_string(path[i].size()) + " dimensions, the limits " +
           std::to_string(dims));
    if (!path[i].allFinite()) fail("path point " + std::to_string(i) + " is not finite");
  }
  require(dt > 0, "dt", dt, "positive and finite");
  require(resolution > 0, "resolution", resolution, "positive and finite");
  require(smoothing >= 0, "smoothing", smoothing, ">= 0 and finite");
}

// A point equal to its predecessor makes a segment with no direction.
Points without_repeats(const Points& points) {
  Points kept(points.rows(), points.cols());
  Eigen::Index n = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i)
    if (n == 0 || points.row(i) != kept.row(n - 1)) kept.row(n++) = points.row(i);
  return kept.topRows(n);
}

Points densify(const Points& path, double resolution) {
  std::vector<Eigen::Index> steps(path.rows() - 1);
  Eigen::Index n = 1;
  for (Eigen::Index k = 0; k + 1 < path.rows(); ++k) {
    const double widest = (path.row(k + 1) - path.row(k)).cwiseAbs().maxCoeff();
    steps[k] = Eigen::Index(std::ceil(widest / resolution));
    n += steps[k];
  }
  Points dense(n, path.cols());
  dense.row(0) = path.row(0);
  Eigen::Index i = 1;
  for (Eigen::Index k = 0; k + 1 < path.rows(); ++k) {
    for (Eigen::Index s = 1; s < steps[k]; ++s)
      dense.row(i++) = path.row(k) + (path.row(k + 1) - path.row(k)) * (double(s) / double(steps[k]));
    dense.row(i++) = path.row(k + 1);  // exactly, not by interpolation: the end point must be preserved bit for bit
  }
  return dense;
}

// Minimises |x - p|^2 + w |D x|^2 (D: second differences) over the interior points, the two ends fixed.
// Splitting D's columns into interior (Di) and ends (De) gives (I + w Di'Di) x = p_interior - w Di'De p_ends.
Points smooth(const Points& dense, double weight, const Validity& valid) {
  const Eigen::Index n = dense.rows();
  if (n < 3 || weight == 0) return dense;
  const Eigen::Index unknowns = n - 2;  // point i + 1 is unknown i
  constexpr double kDifference[3] = {1, -2, 1};
  std::vector<Eigen::Triplet<double>> entries;
  Points ends = Points::Zero(unknowns, dense.cols());  // Di'De p_ends
  for (Eigen::Index r = 0; r < n - 2; ++r) {           // the difference centred on point r + 1
    for (int a = 0; a < 3; ++a) {
      const Eigen::Index row = r + a - 1;
      if (row < 0 || row >= unknowns) continue;
      for (int b = 0; b < 3; ++b) {
        const Eigen::Index col = r + b - 1;
        const double value = kDifference[a] * kDifference[b];
        if (col < 0 || col >= unknowns)
          ends.row(row) += value * dense.row(r + b);
        else
          entries.emplace_back(row, col, value);
      }
    }
  }
  Eigen::SparseMatrix<double> curvature(unknowns, unknowns);  // Di'Di: banded, its diagonal all nonzero
  curvature.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseMatrix<double> identity(unknowns, unknowns);
  identity.setIdentity();

  // Simplicial: CHOLMOD 3.0 (SuiteSparse 5.12) has no thread setting, and its OpenMP (and BLAS) calls are all in the
  // supernodal factorisation, which a band this narrow does not need. In natural order a band has no fill-in.
  Eigen::CholmodSimplicialLLT<Eigen::SparseMatrix<double>> solver;
  solver.cholmod().nmethods = 1;
  solver.cholmod().method[0].ordering = CHOLMOD_NATURAL;
  solver.analyzePattern(curvature);  // I + w Di'Di has the same pattern whatever w: one symbolic factorisation
  const Points interior = dense.middleRows(1, unknowns);
  for (int attempt = 0; attempt < kSmoothingAttempts; ++attempt, weight /= 2) {
    solver.factorize(identity + weight * curvature);  // SPD: I plus a positive semi-definite matrix
    Points smoothed = dense;
    smoothed.middleRows(1, unknowns) = solver.solve(interior - weight * ends);
    bool accepted = true;
    for (Eigen::Index i = 1; accepted && i + 1 < n; ++i) accepted = !valid || valid(smoothed.row(i).transpose());
    if (accepted) return smoothed;
  }
  return dense;
}

// One segment's motion along the path: speed up at `accel` from v0 to the peak, cruise, slow down to v1.
struct SegmentMotion {
  double accel, v0, peak, v1;
  double t_up, t_cruise, t_down;
  double d_up, d_cruise;

  SegmentMotion(double length, double max_speed, double accel, double v0_squared, double v1_squared)
      : accel(accel), v0(std::sqrt(v0_squared)), v1(std::sqrt(v1_squared)) {
    const double peak_squared = std::min(max_speed * max_speed, (v0_squared + v1_squared) / 2 + accel * length);
    peak = std::sqrt(peak_squared);
    t_up = std::max(0.0, (peak - v0) / accel);
    t_down = std::max(0.0, (peak - v1) / accel);
    d_up = (peak_squared - v0_squared) / (2 * accel);
    d_cruise = std::max(0.0, length - d_up - (peak_squared - v1_squared) / (2 * accel));
    t_cruise = d_cruise / peak;
  }
  double duration() const { return t_up + t_cruise + t_down; }
  double distance(double t) const {
    if (t < t_up) return v0 * t + accel * t * t / 2;
    t -= t_up;
    if (t < t_cruise) return d_up + peak * t;
    t = std::min(t - t_cruise, t_down);
    return d_up + d_cruise + peak * t - accel * t * t / 2;
  }
};

std::vector<Eigen::VectorXd> time_parameterise(const Points& q, const TrajectoryLimits& limits, double dt) {
  const Eigen::Index m = q.rows();  // >= 2, no repeats
  const Eigen::ArrayXd max_v = limits.max_velocity.array(), max_a = limits.max_acceleration.array();
  Eigen::VectorXd length(m - 1), max_speed(m - 1);
  Eigen::ArrayXXd direction(m - 1, q.cols());  // unit, per segment
  for (Eigen::Index k = 0; k + 1 < m; ++k) {
    length[k] = (q.row(k + 1) - q.row(k)).norm();
    direction.row(k) = (q.row(k + 1) - q.row(k)).array() / length[k];
    max_speed[k] = 1 / (direction.row(k).abs() / max_v.transpose()).maxCoeff();
  }
  // Turning by du at a point at speed v is an acceleration v^2 |du| / h over the shorter neighbouring segment h,
  // and samples dt apart see at least v |du| / dt of it: cap v so that both stay within kTurnShare.
  Eigen::ArrayXd speed_cap = Eigen::ArrayXd::Zero(m);  // at rest at both ends
  Eigen::ArrayXXd turn_accel = Eigen::ArrayXXd::Zero(m, q.cols());
  for (Eigen::Index k = 1; k + 1 < m; ++k) {
    const Eigen::ArrayXd du = (direction.row(k) - direction.row(k - 1)).abs().transpose();
    const double h = std::min(length[k - 1], length[k]);
    const Eigen::ArrayXd budget = kTurnShare * max_a;
    const double turn_speed =
        std::min(std::sqrt(1 / (du / (budget * h)).maxCoeff()), 1 / (du / (budget * dt)).maxCoeff());
    const double v = std::min({max_speed[k - 1], max_speed[k], turn_speed});
    speed_cap[k] = v;
    turn_accel.row(k) = du.transpose() * std::max(v * v / h, v / dt);
  }
  // Along segment k the rest of the acceleration budget, after turning at either end.
  Eigen::VectorXd accel(m - 1);
  for (Eigen::Index k = 0; k + 1 < m; ++k) {
    const Eigen::ArrayXd left = max_a - turn_accel.row(k).max(turn_accel.row(k + 1)).transpose();
    accel[k] = 1 / (direction.row(k).abs().transpose() / left).maxCoeff();
  }
  // Speed squared at the points: forward pass bounds speeding up, backward pass slowing down.
  Eigen::ArrayXd v2 = speed_cap.square();
  for (Eigen::Index k = 0; k + 1 < m; ++k) v2[k + 1] = std::min(v2[k + 1], v2[k] + 2 * accel[k] * length[k]);
  for (Eigen::Index k = m - 2; k >= 0; --k) v2[k] = std::min(v2[k], v2[k + 1] + 2 * accel[k] * length[k]);

  std::vector<SegmentMotion> motion;
  double total = 0;
  for (Eigen::Index k = 0; k + 1 < m; ++k) {
    motion.emplace_back(length[k], max_speed[k], accel[k], v2[k], v2[k + 1]);
    total += motion.back().duration();
  }
  // A whole number of dt: stretch time a little (slower is within the limits).
  const Eigen::Index intervals = std::max<Eigen::Index>(1, Eigen::Index(std::ceil(total / dt)));
  std::vector<Eigen::VectorXd> samples;
  samples.reserve(intervals + 1);
  samples.push_back(q.row(0).transpose());
  Eigen::Index k = 0;
  double segment_start = 0;
  for (Eigen::Index i = 1; i < intervals; ++i) {
    const double t = total * double(i) / double(intervals);
    while (k + 2 < m && t > segment_start + motion[k].duration()) segment_start += motion[k++].duration();
    const double s = std::min(motion[k].distance(t - segment_start), length[k]);
    samples.push_back((q.row(k) + (q.row(k + 1) - q.row(k)) * (s / length[k])).transpose());
  }
  samples.push_back(q.row(m - 1).transpose());
  return samples;
}

}  // namespace

Trajectory make_trajectory(const std::vector<Eigen::VectorXd>& path, const TrajectoryLimits& limits, double dt,
                           double resolution, const Validity& valid, double smoothing) {
  check_input(path, limits, dt, resolution, smoothing);
  Points points(path.size(), path.front().size());
  for (size_t i = 0; i < path.size(); ++i) points.row(i) = path[i].transpose();
  points = without_repeats(points);

  Trajectory trajectory;
  trajectory.dt = dt;
  if (points.rows() == 1) {
    trajectory.samples = {path.front()};
    return trajectory;
  }
  const Points smoothed = without_repeats(smooth(densify(points, resolution), smoothing, valid));
  trajectory.samples = time_parameterise(smoothed, limits, dt);
  return trajectory;
}

}  // namespace chore
