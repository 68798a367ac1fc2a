#include "world/optical_flow.hpp"

#include <mujoco/mujoco.h>

namespace chore {

void FramePoses::capture(const mjModel* model, const mjData* data, int cam) {
  camera = CameraPose::of(data, cam);
  xpos.assign(data->xpos, data->xpos + 3 * model->nbody);
  xmat.assign(data->xmat, data->xmat + 9 * model->nbody);
}

void optical_flow(const mjModel* model, const Pinhole& pinhole, const FramePoses& before, const FramePoses& now,
                  const std::int32_t* geom, const float* depth, float* flow) {
  const int w = pinhole.width;
  for (int row = 0, i = 0; row < pinhole.height; ++row) {
    for (int col = 0; col < w; ++col, ++i) {
      double local[3], then[3];
      if (geom[i] < 0) {
        // A point at infinity: its direction, turned with the camera.
        double direction[3];
        pinhole.unproject(col, row, 1.0, local);
        mju_mulMatVec3(direction, now.camera.mat, local);
        mju_mulMatTVec3(then, before.camera.mat, direction);
      } else {
        // Where the point was: the same point of its body, at the body's previous pose.
        const int b = model->geom_bodyid[geom[i]];
        double point[3], rel[3], on_body[3], moved[3];
        pinhole.unproject(col, row, depth[i], local);
        now.camera.to_world(local, point);
        mju_sub3(rel, point, now.xpos.data() + 3 * b);
        mju_mulMatTVec3(on_body, now.xmat.data() + 9 * b, rel);
        mju_mulMatVec3(moved, before.xmat.data() + 9 * b, on_body);
        mju_addTo3(moved, before.xpos.data() + 3 * b);
        before.camera.to_camera(moved, then);
      }
      double u, v;
      float* f = flow + 2 * size_t(i);
      if (!pinhole.project(then, u, v)) {  // behind the previous camera: no defined flow
        f[0] = f[1] = 0;
        continue;
      }
      f[0] = static_cast<float>(col + 0.5 - u);
      f[1] = static_cast<float>(row + 0.5 - v);
    }
  }
}

}  // namespace chore
