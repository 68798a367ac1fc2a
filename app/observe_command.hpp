// `chore observe`: every observation modality of one frame of the robot's head
// camera as a PNG panel: RGB, depth, semantic and instance segmentation,
// surface normals, optical flow (of the last of a few steps of motion), the
// LiDAR scan from above, and the same frame through sensor noise and under
// lamps-only lighting with domain randomisation.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>
#include <string>

namespace chore {

struct ObserveOptions {
  std::string activity;  // an activity instance (in its scene), or
  std::string scene;     // a bare scene (the apartment when both are empty)
  uint64_t seed = 0;
  int size = 256;   // pixels of each (square) tile
  int steps = 3;    // steps of motion (forward and turning) before the frame
  std::string out;  // the PNG to write
};

// Writes the panel; returns what it saw (semantic classes in view, flow range,
// LiDAR range). chore::Error for bad options or an unwritable file.
nlohmann::json observe_panel(const ObserveOptions& options);

}  // namespace chore
