#include "world/normals.hpp"

#include <cmath>

namespace chore {

void surface_normals(const Pinhole& camera, const float* depth, double far, float* normal) {
  const int w = camera.width, h = camera.height;
  auto seen = [&](int col, int row) { return depth[row * w + col] < far; };
  // The tangent along one axis: to the neighbour (before or after) nearer in depth.
  auto tangent = [&](int col, int row, int dc, int dr, double out[3]) {
    const double z = depth[row * w + col];
    const bool has_before = col - dc >= 0 && row - dr >= 0 && seen(col - dc, row - dr);
    const bool has_after = col + dc < w && row + dr < h && seen(col + dc, row + dr);
    if (!has_before && !has_after) return false;
    bool after = has_after;
    if (has_before && has_after) {
      after = std::abs(depth[(row + dr) * w + col + dc] - z) <= std::abs(depth[(row - dr) * w + col - dc] - z);
    }
    double p[3], q[3];
    camera.unproject(col, row, z, p);
    if (after) {
      camera.unproject(col + dc, row + dr, depth[(row + dr) * w + col + dc], q);
      for (int k = 0; k < 3; ++k) out[k] = q[k] - p[k];
    } else {
      camera.unproject(col - dc, row - dr, depth[(row - dr) * w + col - dc], q);
      for (int k = 0; k < 3; ++k) out[k] = p[k] - q[k];
    }
    return true;
  };
  for (int row = 0; row < h; ++row) {
    for (int col = 0; col < w; ++col) {
      float* n = normal + 3 * (size_t(row) * w + col);
      double du[3], dv[3];
      if (!seen(col, row) || !tangent(col, row, 1, 0, du) || !tangent(col, row, 0, 1, dv)) {
        n[0] = n[1] = n[2] = 0;
        continue;
      }
      double c[3] = {du[1] * dv[2] - du[2] * dv[1], du[2] * dv[0] - du[0] * dv[2], du[0] * dv[1] - du[1] * dv[0]};
      const double length = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
      double p[3];
      camera.unproject(col, row, depth[row * w + col], p);
      // Facing the camera: against the line of sight.
      const double sign = c[0] * p[0] + c[1] * p[1] + c[2] * p[2] > 0 ? -1.0 : 1.0;
      for (int k = 0; k < 3; ++k) n[k] = length > 0 ? static_cast<float>(sign * c[k] / length) : 0.f;
    }
  }
}

}  // namespace chore
