// Axis-aligned boxes in the world frame (objects', geoms', regions').
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace chore {

struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);

  Eigen::Vector3d center() const { return (lo + hi) / 2; }
  Eigen::Vector3d extent() const { return hi - lo; }
  // Half the box's width along a horizontal direction `d` (unit): how far its
  // edge lies from its centre that way.
  double half_across(const Eigen::Vector3d& d) const {
    return (std::abs(d.x()) * (hi.x() - lo.x()) + std::abs(d.y()) * (hi.y() - lo.y())) / 2;
  }
  bool contains(const Eigen::Vector3d& p) const {
    return (p.array() >= lo.array()).all() && (p.array() <= hi.array()).all();
  }
  void grow(const Aabb& other) {
    lo = lo.cwiseMin(other.lo);
    hi = hi.cwiseMax(other.hi);
  }
  Aabb grown(double margin) const {
    Aabb b = *this;
    b.lo.array() -= margin;
    b.hi.array() += margin;
    return b;
  }
  bool overlaps(const Aabb& other) const {
    return (lo.array() <= other.hi.array()).all() && (other.lo.array() <= hi.array()).all();
  }
  // Euclidean distance between the closest points of two boxes (0 if they overlap).
  static double gap(const Aabb& a, const Aabb& b) {
    return (a.lo - b.hi).cwiseMax(b.lo - a.hi).cwiseMax(Eigen::Vector3d::Zero()).norm();
  }
};

}  // namespace chore
