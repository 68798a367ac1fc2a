// The geometry that never moves (floors, walls, ceilings, fixed furniture)
// merged into MuJoCo meshes, coloured through one palette texture. MuJoCo
// 2.2.2's renderer pays ~30 us per drawn geom on llvmpipe, and llvmpipe about
// as much per thousand triangles: each shape joins the mesh of the kChunk x
// kChunk m cell its centre lies in, so that the renderer's frustum culling
// drops the chunks out of view (a few draw calls, a fraction of the
// triangles). Collision keeps the original geoms.
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "world/scene_file.hpp"  // Rgb

struct mjModel_;

namespace chore {

class StaticMesh {
 public:
  // `name` names the MJCF mesh, texture and material; `group` is the geom group
  // that draws it.
  StaticMesh(std::string name, int group) : name_(std::move(name)), group_(group) {}

  // Shapes in MuJoCo's conventions (half sizes), placed by `pose`.
  void add_box(const Eigen::Isometry3d& pose, const Eigen::Vector3d& half, const Rgb& color);
  void add_cylinder(const Eigen::Isometry3d& pose, double radius, double half_height, const Rgb& color);
  void add_sphere(const Eigen::Isometry3d& pose, double radius, const Rgb& color);
  void add_capsule(const Eigen::Isometry3d& pose, double radius, double half_length, const Rgb& color);

  bool empty() const { return faces_.empty(); }
  size_t vertex_count() const { return vertices_.size(); }
  size_t color_count() const { return palette_.size(); }

  // <texture>, <material> and <mesh> elements for the <asset> section.
  std::string mjcf_assets() const;
  // Its <geom>s, one per chunk (visual only), named "<name>_<i>".
  std::string mjcf_geom() const;
  // MuJoCo's builtin texture is flat white; this paints the palette into it.
  void paint_palette(mjModel_* model) const;

 private:
  struct Vertex {
    Eigen::Vector3d position, normal;
    int color;
  };
  using Chunk = std::pair<long, long>;
  static constexpr double kChunk = 2.0;  // 1-2 m measured best in the restaurant (docs/benchmarks.md)
  // Sets the chunk the shape centred at `center` goes to; its colour's index.
  int start_shape(const Eigen::Vector3d& center, const Rgb& color);
  void add_face(int a, int b, int c);
  std::map<Chunk, std::vector<size_t>> faces_by_chunk() const;
  int color_index(const Rgb& color);
  int add_vertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n, int color);
  // A planar quad (corner, two edges), subdivided so that per-vertex lighting
  // of large faces looks right.
  void add_quad(const Eigen::Vector3d& corner, const Eigen::Vector3d& u, const Eigen::Vector3d& v, int color);
  std::array<double, 2> texcoord(int color) const;
  int texture_width() const;
  int texture_height() const;

  std::string name_;
  int group_;
  std::vector<Vertex> vertices_;
  std::vector<std::array<int, 3>> faces_;
  std::vector<Chunk> face_chunk_;              // per face
  Chunk chunk_;                                // of the shape being added
  std::map<std::array<int, 3>, int> palette_;  // 8-bit rgb -> index
};

}  // namespace chore
