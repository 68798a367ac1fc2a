#include "app/observe_command.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "app/png.hpp"
#include "base/error.hpp"
#include "env/env.hpp"
#include "world/segmentation.hpp"

namespace chore {
namespace {

// The noise of a real RGB-D head camera and base laser, roughly (G.1's gaps):
// a camera that clips highlights and crushes shadows, Kinect-like depth noise
// and shadows, a 3.5 m depth range, a slightly noisy laser.
SensorNoise typical_noise() {
  SensorNoise n;
  n.rgb_exposure = 1.3;
  n.rgb_black_level = 0.08;
  n.rgb_shot_noise = 0.6;
  n.rgb_read_noise = 2.0;
  n.depth_noise = 0.0012;
  n.depth_noise_quadratic = 0.0019;
  n.depth_edge = 0.05;
  n.depth_max = 3.5;
  n.lidar_noise = 0.01;
  n.lidar_dropout = 0.02;
  return n;
}

cv::Vec3b bgr_of_hsv(double hue, double saturation, double value) {
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(hue * 180, saturation * 255, value * 255)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  return bgr.at<cv::Vec3b>(0, 0);
}

// Distinct colours for ids (0, the background: black).
cv::Vec3b id_colour(int id) {
  if (id == 0) return {0, 0, 0};
  const double hue = std::fmod(id * 0.6180339887, 1.0);
  return bgr_of_hsv(hue, 0.55 + 0.15 * (id % 3), 0.75 + 0.1 * (id % 3));
}

cv::Mat rgb_tile(const Array& rgb, int size) {
  cv::Mat image(size, size, CV_8UC3, const_cast<void*>(rgb.item(0))), bgr;
  cv::cvtColor(image, bgr, cv::COLOR_RGB2BGR);
  return bgr;
}

// Near is bright; invalid (0) black.
cv::Mat depth_tile(const Array& depth, int size, double far) {
  cv::Mat grey(size, size, CV_8UC1);
  const float* z = depth.data<float>();
  for (int i = 0; i < size * size; ++i) {
    grey.data[i] = z[i] <= 0 ? 0 : static_cast<unsigned char>(255 * std::clamp(1.0 - z[i] / far, 0.0, 1.0));
  }
  cv::Mat out;
  cv::applyColorMap(grey, out, cv::COLORMAP_VIRIDIS);
  for (int i = 0; i < size * size; ++i) {
    if (z[i] <= 0) out.at<cv::Vec3b>(i / size, i % size) = {0, 0, 0};
  }
  return out;
}

cv::Mat id_tile(const Array& ids, int size) {
  cv::Mat out(size, size, CV_8UC3);
  for (int i = 0; i < size * size; ++i) out.at<cv::Vec3b>(i / size, i % size) = id_colour(ids.data<int32_t>()[i]);
  return out;
}

// Camera-frame normal (x right, y up, z to the viewer) as RGB = (n + 1) / 2.
cv::Mat normal_tile(const Array& normal, int size) {
  cv::Mat out(size, size, CV_8UC3);
  const float* n = normal.data<float>();
  for (int i = 0; i < size * size; ++i) {
    auto c = [&](int k) { return static_cast<unsigned char>(std::lround(127.5 * (n[3 * i + k] + 1))); };
    out.at<cv::Vec3b>(i / size, i % size) = {c(2), c(1), c(0)};
  }
  return out;
}

// Hue: direction; brightness: magnitude relative to the largest.
cv::Mat flow_tile(const Array& flow, int size, double largest) {
  cv::Mat out(size, size, CV_8UC3);
  const float* f = flow.data<float>();
  for (int i = 0; i < size * size; ++i) {
    const double angle = std::atan2(f[2 * i + 1], f[2 * i]), magnitude = std::hypot(f[2 * i], f[2 * i + 1]);
    out.at<cv::Vec3b>(i / size, i % size) =
        bgr_of_hsv((angle + M_PI) / (2 * M_PI), 1.0, largest > 0 ? std::min(1.0, magnitude / largest) : 0.0);
  }
  return out;
}

// From above, the robot's forward up the tile, out to `shown` metres (a circle
// each metre): the clean scan (white) and the noisy one (red).
cv::Mat lidar_tile(const Array& clean, const Array& noisy, const LidarConfig& lidar, double shown, int size) {
  cv::Mat out(size, size, CV_8UC3, cv::Scalar(30, 30, 30));
  const cv::Point2d centre(size / 2.0, size / 2.0);
  const double scale = 0.47 * size / shown;
  for (int r = 1; r <= shown; ++r)
    cv::circle(out, centre, static_cast<int>(scale * r), cv::Scalar(60, 60, 60), 1, cv::LINE_AA);
  auto at = [&](double angle, double r) {
    return centre + cv::Point2d(-std::sin(angle) * r * scale, -std::cos(angle) * r * scale);
  };
  for (double a : {-lidar.fov / 2, lidar.fov / 2})
    cv::line(out, centre, at(a, shown), cv::Scalar(90, 90, 90), 1, cv::LINE_AA);
  for (int i = 0; i < lidar.beams; ++i) {
    const double a = beam_angle(lidar, i);
    cv::circle(out, at(a, clean.data<float>()[i]), 2, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA);
    cv::circle(out, at(a, noisy.data<float>()[i]), 1, cv::Scalar(60, 60, 255), cv::FILLED, cv::LINE_AA);
  }
  cv::rectangle(out, centre - cv::Point2d(3, 3), centre + cv::Point2d(3, 3), cv::Scalar(0, 200, 255), cv::FILLED);
  return out;
}

void caption(cv::Mat& tile, const std::string& text) {
  cv::rectangle(tile, cv::Point(0, 0), cv::Point(tile.cols, 18), cv::Scalar(0, 0, 0), cv::FILLED);
  cv::putText(tile, text, cv::Point(4, 13), cv::FONT_HERSHEY_SIMPLEX, 0.42, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

// The names of the classes in view, each on its colour, from the bottom up.
void legend(cv::Mat& tile, const Array& semantic, const Segmentation& seg) {
  std::set<int> seen(semantic.data<int32_t>(), semantic.data<int32_t>() + semantic.item_bytes() / 4);
  int y = tile.rows - 6;
  for (auto it = seen.rbegin(); it != seen.rend(); ++it, y -= 14) {
    const cv::Vec3b c = id_colour(*it);
    cv::rectangle(tile, cv::Point(4, y - 9), cv::Point(14, y + 1), cv::Scalar(c[0], c[1], c[2]), cv::FILLED);
    cv::putText(tile, seg.classes()[*it].category, cv::Point(18, y), cv::FONT_HERSHEY_SIMPLEX, 0.36,
                cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
}

}  // namespace

nlohmann::json observe_panel(const ObserveOptions& o) {
  if (o.size < 32 || o.size > 2048) throw Error("observe: --size " + std::to_string(o.size) + " is outside 32..2048");
  if (o.steps < 1) throw Error("observe: --steps must be at least 1 (flow needs a previous frame)");
  EnvConfig config;
  config.activity = o.activity;
  config.scene = o.scene;
  config.width = config.height = o.size;
  config.observations = {"rgb", "depth", "seg_semantic", "seg_instance", "normal", "flow", "lidar"};
  const EnvAssets assets = load_assets(config);
  EnvConfig noisy_config = config, dim_config = config;
  noisy_config.noise = typical_noise();
  dim_config.lighting = Lighting::lamps_only;
  dim_config.randomization = {0.4, 0.3, 0.25};
  Env env(config, assets), noisy(noisy_config, assets), dim(dim_config, assets);
  // The same episode in each, driving straight ahead: the flow radiates from
  // the focus of expansion and grows with nearness.
  std::vector<float> action(kLowLevelActionSize, 0.f);
  action[0] = 1.0f;
  const ArrayDict* obs = nullptr;
  const ArrayDict* noisy_obs = nullptr;
  const ArrayDict* dim_obs = nullptr;
  env.reset(o.seed);
  noisy.reset(o.seed);
  dim.reset(o.seed);
  for (int i = 0; i < o.steps; ++i) {
    obs = &env.step(action).obs;
    noisy_obs = &noisy.step(action).obs;
    dim_obs = &dim.step(action).obs;
  }
  const int s = o.size;
  const Array& depth = (*obs)["depth"];
  const float* z = depth.data<float>();
  const double far = *std::max_element(z, z + s * s);
  const float* f = (*obs)["flow"].data<float>();
  double largest = 0;
  for (int i = 0; i < s * s; ++i) largest = std::max<double>(largest, std::hypot(f[2 * i], f[2 * i + 1]));
  char text[128];
  std::vector<cv::Mat> tiles;
  tiles.push_back(rgb_tile((*obs)["rgb"], s));
  caption(tiles.back(), "rgb");
  tiles.push_back(depth_tile(depth, s, far));
  std::snprintf(text, sizeof text, "depth (0 - %.1f m)", far);
  caption(tiles.back(), text);
  tiles.push_back(id_tile((*obs)["seg_semantic"], s));
  legend(tiles.back(), (*obs)["seg_semantic"], env.segmentation());
  caption(tiles.back(), "seg_semantic");
  tiles.push_back(id_tile((*obs)["seg_instance"], s));
  caption(tiles.back(), "seg_instance");
  tiles.push_back(normal_tile((*obs)["normal"], s));
  caption(tiles.back(), "normal (camera frame)");
  tiles.push_back(flow_tile((*obs)["flow"], s, largest));
  std::snprintf(text, sizeof text, "flow (max %.1f px)", largest);
  caption(tiles.back(), text);
  const float* ranges = (*obs)["lidar"].data<float>();
  const double shown = std::max<double>(1.0, std::ceil(*std::max_element(ranges, ranges + config.lidar.beams)));
  tiles.push_back(lidar_tile((*obs)["lidar"], (*noisy_obs)["lidar"], config.lidar, shown, s));
  std::snprintf(text, sizeof text, "lidar from above (to %.0f m; noisy: red)", shown);
  caption(tiles.back(), text);
  tiles.push_back(rgb_tile((*noisy_obs)["rgb"], s));
  caption(tiles.back(), "rgb, noise");
  tiles.push_back(depth_tile((*noisy_obs)["depth"], s, far));
  caption(tiles.back(), "depth, noise (0: invalid)");
  tiles.push_back(rgb_tile((*dim_obs)["rgb"], s));
  caption(tiles.back(), "rgb, lamps only, randomised");
  constexpr int kColumns = 5;
  cv::Mat panel(2 * s, kColumns * s, CV_8UC3, cv::Scalar(0, 0, 0));
  for (size_t i = 0; i < tiles.size(); ++i) {
    tiles[i].copyTo(panel(cv::Rect(static_cast<int>(i % kColumns) * s, static_cast<int>(i / kColumns) * s, s, s)));
  }
  write_png(o.out, panel, "observe");
  nlohmann::json out;
  out["out"] = o.out;
  out["scene"] = env.world().scene().name();
  std::set<int> seen((*obs)["seg_semantic"].data<int32_t>(), (*obs)["seg_semantic"].data<int32_t>() + s * s);
  for (int c : seen) out["classes"].push_back(env.segmentation().classes()[c].category);
  std::set<int> instances((*obs)["seg_instance"].data<int32_t>(), (*obs)["seg_instance"].data<int32_t>() + s * s);
  out["instances"] = instances.size();
  out["max_flow_px"] = largest;
  out["max_depth_m"] = far;
  return out;
}

}  // namespace chore
