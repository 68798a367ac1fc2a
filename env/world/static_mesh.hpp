// The geometry that never moves (floors, walls, ceilings, fixed furniture)
// merged into one MuJoCo mesh, coloured through a palette texture. MuJoCo
// 2.2.2's renderer pays ~30 us per drawn geom on llvmpipe; merged, the whole
// static scene is a single draw call. Collision keeps the original geoms.
#pragma once

#include <Eigen/Geometry>

#include <array>
#include <map>
#include <string>
#include <vector>

struct mjModel_;

namespace chore {

using Rgb = std::array<double, 3>;

class StaticMesh {
 public:
  // `name` names the MJCF mesh, texture and material; `group` is the geom group
  // that draws it.
  StaticMesh(std::string name, int group) : name_(std::move(name)), group_(group) {}

  // Shapes in MuJoCo's conventions (half sizes), placed by `pose`.
  void add_box(const Eigen::Isometry3d& pose, const Eigen::Vector3d& half, const Rgb& color);
  void add_cylinder(const Eigen::Isometry3d& pose, double radius, double half_height,
                    const Rgb& color);
  void add_sphere(const Eigen::Isometry3d& pose, double radius, const Rgb& color);
  void add_capsule(const Eigen::Isometry3d& pose, double radius, double half_length,
                   const Rgb& color);

  bool empty() const { return faces_.empty(); }
  size_t vertex_count() const { return vertices_.size(); }
  size_t color_count() const { return palette_.size(); }

  // <texture>, <material> and <mesh> elements for the <asset> section.
  std::string mjcf_assets() const;
  // The one <geom> that draws it (visual only).
  std::string mjcf_geom() const;
  // MuJoCo's builtin texture is flat white; this paints the palette into it.
  void paint_palette(mjModel_* model) const;

 private:
  struct Vertex {
    Eigen::Vector3d position, normal;
    int color;
  };
  int color_index(const Rgb& color);
  int add_vertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n, int color);
  // A planar quad (corner, two edges), subdivided so that per-vertex lighting
  // of large faces looks right.
  void add_quad(const Eigen::Vector3d& corner, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                int color);
  std::array<double, 2> texcoord(int color) const;
  int texture_width() const;
  int texture_height() const;

  std::string name_;
  int group_;
  std::vector<Vertex> vertices_;
  std::vector<std::array<int, 3>> faces_;
  std::map<std::array<int, 3>, int> palette_;  // 8-bit rgb -> index
};

}  // namespace chore
