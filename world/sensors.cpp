#include "world/sensors.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>

#include "world/normals.hpp"
#include "world/world.hpp"

namespace chore {
namespace {

// Streams drawn from an episode seed (random.hpp's derive_seed).
constexpr uint64_t kSensorStream = 1;

bool needs_ids(const SensorFrame& f) {
  return f.semantic || f.instance || f.flow;
}
bool needs_depth(const SensorFrame& f) {
  return f.depth || f.normal || needs_ids(f);
}

}  // namespace

Sensors::Sensors(int width, int height, const LidarConfig& lidar, const SensorNoise& noise)
    : width_(width), height_(height), lidar_(lidar), noise_(noise) {}

Sensors::~Sensors() = default;

void Sensors::reset(std::optional<uint64_t> seed) {
  if (seed) rng_.seed(derive_seed(*seed, kSensorStream));
  has_before_ = false;
}

const Segmentation& Sensors::segmentation(const World& world) const {
  if (!segmentation_) segmentation_ = std::make_unique<Segmentation>(world);
  return *segmentation_;
}

std::vector<CameraView> Sensors::views(World& world, const SensorFrame& frame) {
  if (!frame.rgb && !needs_depth(frame)) return {};
  const size_t pixels = size_t(width_) * height_;
  float* depth = frame.depth;
  if (!depth && needs_depth(frame)) {
    depth_.resize(pixels);
    depth = depth_.data();
  }
  std::int32_t* geom = nullptr;
  if (needs_ids(frame)) {
    geom_.resize(pixels);
    geom = geom_.data();
  }
  CameraView view{world.model(), world.data(), world.scene().camera(), frame.rgb, depth};
  view.world = &world;
  view.segment = geom;
  return {view};
}

void Sensors::finish(const World& world, const SensorFrame& frame) {
  const mjModel* m = world.model();
  const int camera = world.scene().camera();
  const Pinhole pinhole = Pinhole::of(m, camera, width_, height_);
  const float* depth = frame.depth ? frame.depth : depth_.data();
  if (frame.semantic || frame.instance) {
    segmentation(world).label(pinhole, CameraPose::of(world.data(), camera), geom_.data(), depth, frame.instance,
                              frame.semantic);
  }
  if (frame.normal) {
    // What the far plane bounds was not seen.
    const double far = 0.99 * m->vis.map.zfar * m->stat.extent;
    surface_normals(pinhole, depth, far, frame.normal);
  }
  if (frame.flow) {
    now_.capture(m, world.data(), camera);
    if (has_before_) {
      optical_flow(m, pinhole, before_, now_, geom_.data(), depth, frame.flow);
    } else {
      std::fill(frame.flow, frame.flow + 2 * size_t(width_) * height_, 0.f);
    }
    std::swap(before_, now_);
    has_before_ = true;
  }
  if (frame.lidar) {
    lidar_scan(world, lidar_, frame.lidar);
    if (noise_.lidar()) add_lidar_noise(noise_, rng_, frame.lidar, lidar_.beams, lidar_.range);
  }
  if (frame.rgb && noise_.rgb()) add_rgb_noise(noise_, rng_, frame.rgb, 3 * size_t(width_) * height_);
  if (frame.depth && noise_.depth()) add_depth_noise(noise_, rng_, frame.depth, width_, height_);
}

}  // namespace chore
