#include "world/static_mesh.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "base/error.hpp"

namespace chore {
namespace {

// Each palette colour fills a block of texels; texture coordinates point at a
// block's centre, so neither filtering nor a texel of rounding can bleed colours.
constexpr int kBlock = 4;
constexpr int kBlocksPerRow = 16;
// Largest edge of a quad after subdivision (metres): fixed-function lighting is
// evaluated per vertex.
constexpr double kMaxEdge = 0.5;
constexpr int kRoundSegments = 16;

std::string format_numbers(const std::vector<double>& values) {
  std::string out;
  char buf[32];
  for (size_t i = 0; i < values.size(); ++i) {
    std::snprintf(buf, sizeof buf, i ? " %.5g" : "%.5g", values[i]);
    out += buf;
  }
  return out;
}

// Face indices exactly: %g would write 100000 as 1e+05.
std::string format_indices(const std::vector<std::array<int, 3>>& faces) {
  std::string out;
  for (const auto& f : faces) {
    for (int i : f) out += (out.empty() ? "" : " ") + std::to_string(i);
  }
  return out;
}

}  // namespace

int StaticMesh::start_shape(const Eigen::Vector3d& center, const Rgb& color) {
  auto index = [](double v) { return static_cast<long>(std::floor(std::clamp(v, -1e6, 1e6) / kChunk)); };
  chunk_ = {index(center.x()), index(center.y())};
  return color_index(color);
}

void StaticMesh::add_face(int a, int b, int c) {
  faces_.push_back({a, b, c});
  face_chunk_.push_back(chunk_);
}

int StaticMesh::color_index(const Rgb& color) {
  std::array<int, 3> key;
  for (int i = 0; i < 3; ++i) {
    key[i] = static_cast<int>(std::lround(std::clamp(color[i], 0.0, 1.0) * 255.0));
  }
  const auto [it, inserted] = palette_.try_emplace(key, static_cast<int>(palette_.size()));
  return it->second;
}

int StaticMesh::add_vertex(const Eigen::Vector3d& p, const Eigen::Vector3d& n, int color) {
  vertices_.push_back({p, n.normalized(), color});
  return static_cast<int>(vertices_.size()) - 1;
}

void StaticMesh::add_quad(const Eigen::Vector3d& corner, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                          int color) {
  const Eigen::Vector3d normal = u.cross(v).normalized();
  const int nu = std::max(1, static_cast<int>(std::ceil(u.norm() / kMaxEdge)));
  const int nv = std::max(1, static_cast<int>(std::ceil(v.norm() / kMaxEdge)));
  const int first = static_cast<int>(vertices_.size());
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      add_vertex(corner + u * (double(i) / nu) + v * (double(j) / nv), normal, color);
    }
  }
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      const int a = first + j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
      add_face(a, b, d);  // counter-clockwise seen from the normal side
      add_face(a, d, c);
    }
  }
}

void StaticMesh::add_box(const Eigen::Isometry3d& pose, const Eigen::Vector3d& half, const Rgb& color) {
  const int c = start_shape(pose.translation(), color);
  const Eigen::Matrix3d r = pose.linear();
  const Eigen::Vector3d center = pose.translation();
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      // Face of the box normal to `axis`; edges along the other two axes,
      // ordered so that u x v points outwards.
      Eigen::Vector3d u = r.col(a) * (2 * half[a]);
      Eigen::Vector3d v = r.col(b) * (2 * half[b]);
      if (sign < 0) std::swap(u, v);
      const Eigen::Vector3d corner =
          center + r.col(axis) * (sign * half[axis]) - r.col(a) * half[a] - r.col(b) * half[b];
      add_quad(corner, u, v, c);
    }
  }
}

void StaticMesh::add_cylinder(const Eigen::Isometry3d& pose, double radius, double half_height, const Rgb& color) {
  const int c = start_shape(pose.translation(), color);
  const Eigen::Matrix3d r = pose.linear();
  const Eigen::Vector3d center = pose.translation(), z = r.col(2);
  auto rim = [&](int k) {
    const double t = 2 * M_PI * k / kRoundSegments;
    return Eigen::Vector3d(r.col(0) * std::cos(t) + r.col(1) * std::sin(t));
  };
  const int first = static_cast<int>(vertices_.size());
  for (int k = 0; k < kRoundSegments; ++k) {
    add_vertex(center + rim(k) * radius - z * half_height, rim(k), c);
    add_vertex(center + rim(k) * radius + z * half_height, rim(k), c);
  }
  for (int k = 0; k < kRoundSegments; ++k) {
    const int k1 = (k + 1) % kRoundSegments;
    const int a = first + 2 * k, b = first + 2 * k1;
    add_face(a, b, b + 1);
    add_face(a, b + 1, a + 1);
  }
  for (int sign : {-1, 1}) {
    const Eigen::Vector3d n = z * sign;
    const int hub = add_vertex(center + n * half_height, n, c);
    const int ring = static_cast<int>(vertices_.size());
    for (int k = 0; k < kRoundSegments; ++k) add_vertex(center + rim(k) * radius + n * half_height, n, c);
    for (int k = 0; k < kRoundSegments; ++k) {
      const int a = ring + k, b = ring + (k + 1) % kRoundSegments;
      if (sign > 0)
        add_face(hub, a, b);
      else
        add_face(hub, b, a);
    }
  }
}

void StaticMesh::add_sphere(const Eigen::Isometry3d& pose, double radius, const Rgb& color) {
  add_capsule(pose, radius, 0.0, color);
}

void StaticMesh::add_capsule(const Eigen::Isometry3d& pose, double radius, double half_length, const Rgb& color) {
  // Latitude rings from the bottom pole to the top pole; the two hemispheres are
  // pulled apart by +-half_length along z.
  const int c = start_shape(pose.translation(), color);
  const Eigen::Matrix3d r = pose.linear();
  const Eigen::Vector3d center = pose.translation();
  const int stacks = kRoundSegments / 2;  // even: the equator is a ring
  const int first = static_cast<int>(vertices_.size());
  int rings = 0;
  for (int i = 0; i <= stacks; ++i) {
    const double phi = -M_PI / 2 + M_PI * i / stacks;
    // The equator ring appears twice when the capsule has a cylinder part.
    const int copies = (i == stacks / 2 && half_length > 0) ? 2 : 1;
    for (int copy = 0; copy < copies; ++copy) {
      const double offset =
          (i < stacks / 2 || (i == stacks / 2 && copy == 0 && copies == 2)) ? -half_length : half_length;
      for (int k = 0; k < kRoundSegments; ++k) {
        const double t = 2 * M_PI * k / kRoundSegments;
        const Eigen::Vector3d n =
            r * Eigen::Vector3d(std::cos(phi) * std::cos(t), std::cos(phi) * std::sin(t), std::sin(phi));
        add_vertex(center + n * radius + r.col(2) * offset, n, c);
      }
      ++rings;
    }
  }
  for (int j = 0; j + 1 < rings; ++j) {
    for (int k = 0; k < kRoundSegments; ++k) {
      const int k1 = (k + 1) % kRoundSegments;
      const int a = first + j * kRoundSegments + k, b = first + j * kRoundSegments + k1;
      const int a2 = a + kRoundSegments, b2 = b + kRoundSegments;
      add_face(a, b, b2);
      add_face(a, b2, a2);
    }
  }
}

int StaticMesh::texture_width() const {
  return kBlock * kBlocksPerRow;
}

int StaticMesh::texture_height() const {
  const int rows = (static_cast<int>(palette_.size()) + kBlocksPerRow - 1) / kBlocksPerRow;
  return kBlock * std::max(1, rows);
}

std::array<double, 2> StaticMesh::texcoord(int color) const {
  const int bx = color % kBlocksPerRow, by = color / kBlocksPerRow;
  return {(bx * kBlock + kBlock / 2.0) / texture_width(), (by * kBlock + kBlock / 2.0) / texture_height()};
}

std::map<StaticMesh::Chunk, std::vector<size_t>> StaticMesh::faces_by_chunk() const {
  std::map<Chunk, std::vector<size_t>> chunks;
  for (size_t f = 0; f < faces_.size(); ++f) chunks[face_chunk_[f]].push_back(f);
  return chunks;
}

std::string StaticMesh::mjcf_assets() const {
  if (empty()) return "";
  std::string xml = "    <texture name=\"" + name_ + "\" type=\"2d\" builtin=\"flat\" width=\"" +
                    std::to_string(texture_width()) + "\" height=\"" + std::to_string(texture_height()) +
                    "\" rgb1=\"1 1 1\"/>\n"
                    "    <material name=\"" +
                    name_ + "\" texture=\"" + name_ + "\" specular=\"0.05\" shininess=\"0.1\"/>\n";
  int index = 0;
  for (const auto& [chunk, faces] : faces_by_chunk()) {
    // The chunk's own vertices, renumbered in order of first use.
    std::map<int, int> renumbered;
    std::vector<std::array<int, 3>> local;
    std::vector<double> positions, normals, texcoords;
    for (size_t f : faces) {
      std::array<int, 3>& face = local.emplace_back();
      for (int k = 0; k < 3; ++k) {
        const int v = faces_[f][k];
        const auto [it, fresh] = renumbered.try_emplace(v, static_cast<int>(renumbered.size()));
        face[k] = it->second;
        if (!fresh) continue;
        const Vertex& vertex = vertices_[static_cast<size_t>(v)];
        for (int i = 0; i < 3; ++i) positions.push_back(vertex.position[i]);
        for (int i = 0; i < 3; ++i) normals.push_back(vertex.normal[i]);
        const auto uv = texcoord(vertex.color);
        texcoords.push_back(uv[0]);
        texcoords.push_back(uv[1]);
      }
    }
    xml += "    <mesh name=\"" + name_ + "_" + std::to_string(index++) + "\" vertex=\"" + format_numbers(positions) +
           "\" normal=\"" + format_numbers(normals) + "\" texcoord=\"" + format_numbers(texcoords) + "\" face=\"" +
           format_indices(local) + "\"/>\n";
  }
  return xml;
}

std::string StaticMesh::mjcf_geom() const {
  std::string xml;
  const size_t chunks = faces_by_chunk().size();
  for (size_t i = 0; i < chunks; ++i) {
    const std::string mesh = name_ + "_" + std::to_string(i);
    xml += "    <geom name=\"" + mesh + "\" class=\"visual\" group=\"" + std::to_string(group_) +
           "\" type=\"mesh\" mesh=\"" + mesh + "\" material=\"" + name_ + "\"/>\n";
  }
  return xml;
}

void StaticMesh::paint_palette(mjModel_* model) const {
  if (empty()) return;
  const int id = mj_name2id(model, mjOBJ_TEXTURE, name_.c_str());
  if (id < 0 || model->tex_width[id] != texture_width() || model->tex_height[id] != texture_height() ||
      model->tex_nchannel[id] != 3) {
    throw Error("static mesh '" + name_ + "': palette texture missing from the compiled model");
  }
  unsigned char* texels = model->tex_data + model->tex_adr[id];  // tex_adr counts bytes
  for (const auto& [rgb, index] : palette_) {
    const int bx = index % kBlocksPerRow, by = index / kBlocksPerRow;
    for (int y = by * kBlock; y < (by + 1) * kBlock; ++y) {
      for (int x = bx * kBlock; x < (bx + 1) * kBlock; ++x) {
        unsigned char* t = texels + 3 * (y * texture_width() + x);
        for (int i = 0; i < 3; ++i) t[i] = static_cast<unsigned char>(rgb[i]);
      }
    }
  }
}

}  // namespace chore
