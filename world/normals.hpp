// Surface normals from a depth image: in the camera frame (pinhole.hpp: x
// right, y up, z towards the viewer), unit length, facing the camera.
#pragma once

#include "world/pinhole.hpp"

namespace chore {

// `normal` is height x width x 3. Each pixel's tangents are differences to its
// right/left and lower/upper neighbours, on each axis the neighbour nearer in
// depth (so edges do not bend the normals of the surfaces they bound). Pixels
// that see nothing (depth >= `far`), or have no neighbour on some axis that
// does, get (0, 0, 0).
void surface_normals(const Pinhole& camera, const float* depth, double far, float* normal);

}  // namespace chore
