#include "world/sensor_noise.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "base/error.hpp"

namespace chore {

bool SensorNoise::rgb() const {
  return rgb_exposure != 1.0 || rgb_black_level > 0 || rgb_shot_noise > 0 || rgb_read_noise > 0;
}
bool SensorNoise::depth() const {
  return depth_noise > 0 || depth_noise_quadratic > 0 || depth_edge > 0 || depth_max > 0;
}
bool SensorNoise::lidar() const {
  return lidar_noise > 0 || lidar_dropout > 0;
}

void validate(const SensorNoise& n) {
  auto fail = [](const char* name, double value, const char* expected) {
    throw Error(std::string("noise.") + name + " = " + std::to_string(value) + ": expected " + expected);
  };
  if (!(n.rgb_exposure > 0 && std::isfinite(n.rgb_exposure))) fail("rgb_exposure", n.rgb_exposure, "a positive gain");
  if (!(n.rgb_black_level >= 0 && n.rgb_black_level < 1))
    fail("rgb_black_level", n.rgb_black_level, "a fraction in [0, 1)");
  if (!(n.lidar_dropout >= 0 && n.lidar_dropout < 1)) fail("lidar_dropout", n.lidar_dropout, "a probability in [0, 1)");
  const std::pair<const char*, double> nonnegative[] = {
      {"rgb_shot_noise", n.rgb_shot_noise}, {"rgb_read_noise", n.rgb_read_noise},
      {"depth_noise", n.depth_noise},       {"depth_noise_quadratic", n.depth_noise_quadratic},
      {"depth_edge", n.depth_edge},         {"depth_max", n.depth_max},
      {"lidar_noise", n.lidar_noise}};
  for (const auto& [name, value] : nonnegative) {
    if (!(value >= 0 && std::isfinite(value))) fail(name, value, "a finite value >= 0");
  }
}

void add_rgb_noise(const SensorNoise& n, Rng& rng, std::uint8_t* rgb, size_t values) {
  const double black = 255 * n.rgb_black_level, stretch = 1 / (1 - n.rgb_black_level);
  const bool noisy = n.rgb_shot_noise > 0 || n.rgb_read_noise > 0;
  const double shot = n.rgb_shot_noise * n.rgb_shot_noise, read = n.rgb_read_noise * n.rgb_read_noise;
  Normals normal(rng);
  for (size_t i = 0; i < values; ++i) {
    double v = std::min(255.0, rgb[i] * n.rgb_exposure);
    v = std::max(0.0, v - black) * stretch;
    if (noisy) v += normal() * std::sqrt(shot * v + read);
    rgb[i] = static_cast<std::uint8_t>(std::clamp(std::round(v), 0.0, 255.0));
  }
}

void add_depth_noise(const SensorNoise& n, Rng& rng, float* depth, int width, int height) {
  std::vector<char> shadow;
  if (n.depth_edge > 0) {
    // From the clean image: the far side of each occluding edge.
    shadow.assign(size_t(width) * height, 0);
    for (int row = 0; row < height; ++row) {
      for (int col = 0; col < width; ++col) {
        const float z = depth[row * width + col];
        auto nearer = [&](int c, int r) {
          return c >= 0 && c < width && r >= 0 && r < height && z - depth[r * width + c] > n.depth_edge;
        };
        shadow[row * width + col] =
            nearer(col - 1, row) || nearer(col + 1, row) || nearer(col, row - 1) || nearer(col, row + 1);
      }
    }
  }
  const bool noisy = n.depth_noise > 0 || n.depth_noise_quadratic > 0;
  Normals normal(rng);
  for (size_t i = 0; i < size_t(width) * height; ++i) {
    const double z = depth[i];
    if ((!shadow.empty() && shadow[i]) || (n.depth_max > 0 && z > n.depth_max)) {
      depth[i] = 0;
      continue;
    }
    if (noisy)
      depth[i] = static_cast<float>(std::max(0.0, z + normal() * (n.depth_noise + n.depth_noise_quadratic * z * z)));
  }
}

void add_lidar_noise(const SensorNoise& n, Rng& rng, float* ranges, int beams, double max_range) {
  Normals normal(rng);
  for (int i = 0; i < beams; ++i) {
    // Both draws for every beam, so that one beam's dropout does not shift the others' noise.
    const bool lost = uniform(rng, 0, 1) < n.lidar_dropout;
    const double noise = n.lidar_noise > 0 ? normal() * n.lidar_noise : 0.0;
    if (lost || ranges[i] >= max_range) {  // no return has no range to perturb
      ranges[i] = static_cast<float>(max_range);
    } else {
      ranges[i] = static_cast<float>(std::clamp(ranges[i] + noise, 0.0, max_range));
    }
  }
}

}  // namespace chore
