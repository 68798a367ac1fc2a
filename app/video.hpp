// `chore video`: one episode of a policy recorded to an MP4 with OpenCV's
// VideoWriter through FFmpeg (Debian 12: H.264 "avc1" via libx264, else MPEG-4
// Part 2 "mp4v"; both read back with cv::VideoCapture): the robot's head
// camera beside the top-down view of the scene, over a caption (step, action
// and its outcome, reward, Q).
//
// One video frame per env step, plus the first observation. In the primitive
// action space a step is a whole primitive: the video shows the state after
// each one (no frames from inside a primitive; at the default 2 frames/s).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>
#include <string>

#include "policies/evaluate.hpp"

namespace chore {

struct VideoOptions {
  uint64_t seed = 0;  // the episode's env seed (as `chore expert --seed`)
  std::string out;    // the .mp4 to write
  int size = 256;     // pixels of each (square) view
  double fps = 0;     // 0: 30 for low-level steps (real time), 2 for primitives
};

// Records the episode; returns what was written (frames, width, height, fps,
// codec, steps, success, q). chore::Error when the file cannot be written.
nlohmann::json record_video(const PolicySource& source, const VideoOptions& options, std::ostream& log);

}  // namespace chore
