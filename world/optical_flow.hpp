// Exact optical flow from depth and the scene's motion: each pixel's point is
// carried back to where it was in the previous frame (the camera's motion,
// and the motion of the body it lies on) and projected into the previous camera.
//
// flow[row][col] = (u, v) - (u', v'), in pixels (u right, v down): the motion
// since the previous frame of the surface point now seen at pixel (col, row),
// which the previous frame saw at (u', v'). Every pixel has a value: pixels
// that see nothing are points at infinity (only the camera's turn moves them).
#pragma once

#include <cstdint>
#include <vector>

#include "world/pinhole.hpp"

struct mjModel_;
struct mjData_;

namespace chore {

// The camera's and every body's pose at one frame.
struct FramePoses {
  CameraPose camera;
  std::vector<double> xpos, xmat;  // per body, as mjData's
  void capture(const mjModel_* model, const mjData_* data, int camera);
};

// `geom` per pixel (the renderer's segmentation pass; -1: nothing), metric
// `depth`; `flow` is height x width x 2.
void optical_flow(const mjModel_* model, const Pinhole& pinhole, const FramePoses& before, const FramePoses& now,
                  const std::int32_t* geom, const float* depth, float* flow);

}  // namespace chore
