// The sensors of one environment and how one frame of them is made. The
// renderer draws what the frame's images need (a colour pass for RGB and
// depth, a segmentation pass for the geom seen at each pixel); segmentation
// ids, normals and optical flow are derived from those, before any noise; the
// LiDAR casts rays; sensor noise comes last, from the episode's sensor stream.
// A modality that is not observed costs nothing: no pass, no computation.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "base/random.hpp"
#include "world/lidar.hpp"
#include "world/optical_flow.hpp"
#include "world/renderer.hpp"
#include "world/segmentation.hpp"
#include "world/sensor_noise.hpp"

namespace chore {

class World;

// Where one frame's observations go; nullptr for those not observed.
struct SensorFrame {
  std::uint8_t* rgb = nullptr;       // height x width x 3
  float* depth = nullptr;            // height x width, metres along the optical axis
  std::int32_t* semantic = nullptr;  // height x width semantic class ids
  std::int32_t* instance = nullptr;  // height x width instance ids
  float* normal = nullptr;           // height x width x 3, camera frame
  float* flow = nullptr;             // height x width x 2, pixels
  float* lidar = nullptr;            // beams, metres
};

class Sensors {
 public:
  // The egocentric camera (Scene::camera) at width x height; the configs must
  // be valid (validate() in lidar.hpp and sensor_noise.hpp).
  Sensors(int width, int height, const LidarConfig& lidar, const SensorNoise& noise);
  ~Sensors();
  Sensors(const Sensors&) = delete;
  Sensors& operator=(const Sensors&) = delete;

  // A new episode: no previous frame (its first flow is zero); with a seed,
  // the sensor stream restarts from it (without, it continues).
  void reset(std::optional<uint64_t> seed);
  // The episode's sensor stream: noise, and the appearance randomisation.
  Rng& rng() { return rng_; }

  // What to render for `frame` (empty when it needs no image).
  std::vector<CameraView> views(World& world, const SensorFrame& frame);
  // After those views are rendered: the derived modalities, the LiDAR, noise.
  void finish(const World& world, const SensorFrame& frame);

  // The semantic class and instance tables of `world` (built on first use).
  const Segmentation& segmentation(const World& world) const;

 private:
  int width_, height_;
  LidarConfig lidar_;
  SensorNoise noise_;
  Rng rng_;
  std::vector<float> depth_;        // depth a derived modality needs when it is not observed
  std::vector<std::int32_t> geom_;  // the segmentation pass's geom ids
  mutable std::unique_ptr<Segmentation> segmentation_;
  FramePoses before_, now_;  // for flow
  bool has_before_ = false;
};

}  // namespace chore
