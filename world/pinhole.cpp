#include "world/pinhole.hpp"

#include <mujoco/mujoco.h>

#include <cmath>

namespace chore {

Pinhole Pinhole::of(const mjModel* model, int camera, int width, int height) {
  // MuJoCo's fovy is the vertical field of view, in degrees.
  return {width, height, 0.5 * height / std::tan(model->cam_fovy[camera] * M_PI / 360.0)};
}

CameraPose CameraPose::of(const mjData* data, int camera) {
  CameraPose p;
  mju_copy3(p.pos, data->cam_xpos + 3 * camera);
  mju_copy(p.mat, data->cam_xmat + 9 * camera, 9);
  return p;
}

void CameraPose::to_world(const double local[3], double world[3]) const {
  mju_mulMatVec3(world, mat, local);
  mju_addTo3(world, pos);
}

void CameraPose::to_camera(const double world[3], double local[3]) const {
  double rel[3];
  mju_sub3(rel, world, pos);
  mju_mulMatTVec3(local, mat, rel);
}

}  // namespace chore
