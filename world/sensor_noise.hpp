// Sensor noise models, all off by default (the seed's G.1 sim-to-real gaps):
// an RGB camera of limited dynamic range with photon noise, a structured-light
// depth camera (noise growing with distance, no return at the far side of
// occluding edges or beyond its range), a LiDAR with range noise and dropouts.
// Draws come from the caller's Rng (a stream of the episode seed).
#pragma once

#include <cstddef>
#include <cstdint>

#include "base/random.hpp"

namespace chore {

struct SensorNoise {
  // RGB, per 8-bit channel value I: I x rgb_exposure (over 1 burns highlights
  // out at 255), less the black level (rgb_black_level x 255 and below read 0,
  // the rest stretched to 0..255), plus Gaussian noise of standard deviation
  // rgb_shot_noise x sqrt(I) (photon noise) and rgb_read_noise (levels).
  double rgb_exposure = 1.0;
  double rgb_black_level = 0.0;
  double rgb_shot_noise = 0.0;
  double rgb_read_noise = 0.0;
  // Depth z (m): Gaussian noise of standard deviation depth_noise +
  // depth_noise_quadratic x z^2 (a Kinect-like sensor: 0.0012 + 0.0019 z^2 roughly);
  // 0 (invalid) where a 4-neighbour is nearer by more than depth_edge m (the
  // projector's shadow behind an occluding edge; 0: off) and beyond depth_max m (0: no limit).
  double depth_noise = 0.0;
  double depth_noise_quadratic = 0.0;
  double depth_edge = 0.0;
  double depth_max = 0.0;
  // LiDAR: Gaussian range noise (m); each beam lost with probability lidar_dropout
  // (it reads the maximum range, as one that hit nothing).
  double lidar_noise = 0.0;
  double lidar_dropout = 0.0;

  bool rgb() const;
  bool depth() const;
  bool lidar() const;
};

// Throws chore::Error naming the first bad value (negative noise, exposure <= 0,
// black level or dropout outside [0, 1)).
void validate(const SensorNoise& n);

void add_rgb_noise(const SensorNoise& n, Rng& rng, std::uint8_t* rgb, size_t values);
void add_depth_noise(const SensorNoise& n, Rng& rng, float* depth, int width, int height);
void add_lidar_noise(const SensorNoise& n, Rng& rng, float* ranges, int beams, double max_range);

}  // namespace chore
