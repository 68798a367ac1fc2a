// The pinhole model of a MuJoCo camera rendered at width x height: square
// pixels, principal point at the image centre, focal length from fovy. Camera
// frame as MuJoCo's (and OpenGL's): x right, y up, looking along -z. Image
// coordinates are continuous: pixel (col, row) covers [col, col+1) x [row, row+1),
// top row first, so its centre is at (col + 0.5, row + 0.5).
#pragma once

struct mjModel_;
struct mjData_;

namespace chore {

struct Pinhole {
  int width = 0, height = 0;
  double focal = 0;  // pixels

  static Pinhole of(const mjModel_* model, int camera, int width, int height);

  // The camera-frame point seen at the centre of pixel (col, row) at `depth`
  // metres along the optical axis.
  void unproject(int col, int row, double depth, double point[3]) const {
    point[0] = depth * (col + 0.5 - 0.5 * width) / focal;
    point[1] = -depth * (row + 0.5 - 0.5 * height) / focal;
    point[2] = -depth;
  }
  // Image coordinates (u right, v down) of a camera-frame point; false behind the camera.
  bool project(const double point[3], double& u, double& v) const {
    if (point[2] >= 0) return false;
    u = 0.5 * width + focal * point[0] / -point[2];
    v = 0.5 * height - focal * point[1] / -point[2];
    return true;
  }
};

// A camera's pose in the world (MuJoCo's cam_xpos, cam_xmat).
struct CameraPose {
  double pos[3], mat[9];
  static CameraPose of(const mjData_* data, int camera);
  void to_world(const double local[3], double world[3]) const;
  void to_camera(const double world[3], double local[3]) const;
};

}  // namespace chore
