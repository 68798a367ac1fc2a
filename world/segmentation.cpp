#include "world/segmentation.hpp"

#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include "world/world.hpp"

namespace chore {
namespace {

constexpr int kResolve = -2;  // the merged static mesh: resolved per pixel

}  // namespace

struct Segmentation::Part {
  int instance, type;
  double size[3], pos[3], mat[9];

  // Distance from a world point to the geom's surface (signed: negative inside).
  double distance(const double world[3]) const {
    double rel[3], p[3];
    mju_sub3(rel, world, pos);
    mju_mulMatTVec3(p, mat, rel);
    // Exterior distance plus (negative) interior depth of an axis-aligned box of half sizes h.
    auto box = [](std::initializer_list<double> q) {
      double outside = 0, inside = -std::numeric_limits<double>::infinity();
      for (double v : q) {
        outside += std::max(v, 0.0) * std::max(v, 0.0);
        inside = std::max(inside, v);
      }
      return std::sqrt(outside) + std::min(inside, 0.0);
    };
    switch (type) {
      case mjGEOM_BOX:
        return box({std::abs(p[0]) - size[0], std::abs(p[1]) - size[1], std::abs(p[2]) - size[2]});
      case mjGEOM_CYLINDER:
        return box({std::hypot(p[0], p[1]) - size[0], std::abs(p[2]) - size[1]});
      case mjGEOM_SPHERE:
        return mju_norm3(p) - size[0];
      case mjGEOM_CAPSULE: {
        const double z = std::clamp(p[2], -size[1], size[1]);
        return std::sqrt(p[0] * p[0] + p[1] * p[1] + (p[2] - z) * (p[2] - z)) - size[0];
      }
      case mjGEOM_ELLIPSOID: {  // approximate, and no object model uses one
        const double s[3] = {p[0] / size[0], p[1] / size[1], p[2] / size[2]};
        return (mju_norm3(s) - 1) * std::min({size[0], size[1], size[2]});
      }
      case mjGEOM_PLANE:
        return p[2];
      default:
        return std::numeric_limits<double>::infinity();
    }
  }

  // Half extents of its world-aligned bounding box.
  void half_extent(double out[3]) const {
    double local[3] = {size[0], size[1], size[2]};
    if (type == mjGEOM_SPHERE) local[1] = local[2] = size[0];
    if (type == mjGEOM_CYLINDER) local[1] = size[0], local[2] = size[1];
    if (type == mjGEOM_CAPSULE) local[1] = size[0], local[2] = size[1] + size[0];
    for (int i = 0; i < 3; ++i) {
      out[i] = 0;
      for (int k = 0; k < 3; ++k) out[i] += std::abs(mat[3 * i + k]) * local[k];
    }
  }
};

Segmentation::Segmentation(const World& world) {
  const Scene& scene = world.scene();
  const mjModel* m = world.model();
  const mjData* d = world.data();
  classes_ = {{"background", ""},
              {"floors", "floor.n.01"},
              {"walls", "wall.n.01"},
              {"ceilings", "ceiling.n.01"},
              {"agent", "agent.n.01"}};
  std::vector<std::pair<std::string, std::string>> object_classes;
  for (const SceneObject& o : scene.objects()) object_classes.push_back({o.category, o.synset});
  std::sort(object_classes.begin(), object_classes.end());
  object_classes.erase(std::unique(object_classes.begin(), object_classes.end()), object_classes.end());
  for (const auto& [category, synset] : object_classes) classes_.push_back({category, synset});
  auto class_of = [&](const SceneObject& o) {
    const auto at = std::lower_bound(object_classes.begin(), object_classes.end(), std::pair{o.category, o.synset});
    return kAgent + 1 + static_cast<int>(at - object_classes.begin());
  };

  instances_.push_back({"background", Instance::Kind::background, 0});
  const auto& objects = scene.objects();
  for (size_t i = 0; i < objects.size(); ++i) {
    instances_.push_back({objects[i].name, Instance::Kind::object, class_of(objects[i]), static_cast<int>(i)});
  }
  std::vector<int> body_instance(m->nbody, 0);
  const int robot = scene.has_robot() ? mj_name2id(m, mjOBJ_BODY, "robot") : -1;
  for (int b = 1; robot >= 0 && b < m->nbody; ++b) {
    if (m->body_rootid[b] != robot) continue;
    body_instance[b] = static_cast<int>(instances_.size());
    instances_.push_back({mj_id2name(m, mjOBJ_BODY, b), Instance::Kind::robot_link, kAgent, -1, b});
  }
  geom_instance_.assign(m->ngeom, 0);
  for (int g = 0; g < m->ngeom; ++g) {
    const int o = scene.object_of_geom(g);
    geom_instance_[g] = o >= 0 ? instance_of_object(o) : body_instance[m->geom_bodyid[g]];
  }
  for (size_t r = 0; r < scene.rooms().size(); ++r) {
    const int id = static_cast<int>(instances_.size());
    instances_.push_back({"floor_" + scene.rooms()[r].name, Instance::Kind::structure, kFloors});
    for (int g : scene.floor_geoms(static_cast<int>(r))) geom_instance_[g] = id;
  }
  for (int g = 0; g < m->ngeom; ++g) {
    const char* name = mj_id2name(m, mjOBJ_GEOM, g);
    if (m->geom_bodyid[g] != 0 || !name || !std::string_view(name).starts_with("wall_")) continue;
    geom_instance_[g] = static_cast<int>(instances_.size());
    instances_.push_back({name, Instance::Kind::structure, kWalls});
  }
  const int ceilings = static_cast<int>(instances_.size());
  instances_.push_back({"ceilings", Instance::Kind::structure, kCeilings});
  // What the merged meshes draw: ceilings, and the collision geoms welded to the world.
  for (int g = 0; g < m->ngeom; ++g) {
    if (m->geom_group[g] == kCeilingGroup) geom_instance_[g] = ceilings;
    if (m->geom_group[g] == kMergedGroup) geom_instance_[g] = kResolve;
  }
  double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
  for (int g = 0; g < m->ngeom; ++g) {
    const bool collides = m->geom_contype[g] || m->geom_conaffinity[g];
    if (!collides || geom_instance_[g] <= 0 || m->body_weldid[m->geom_bodyid[g]] != 0) continue;
    Part p{geom_instance_[g], m->geom_type[g], {}, {}, {}};
    mju_copy3(p.size, m->geom_size + 3 * g);
    mju_copy3(p.pos, d->geom_xpos + 3 * g);
    mju_copy(p.mat, d->geom_xmat + 9 * g, 9);
    double half[3];
    p.half_extent(half);
    for (int i = 0; i < 2; ++i) {
      lo[i] = std::min(lo[i], p.pos[i] - half[i]);
      hi[i] = std::max(hi[i], p.pos[i] + half[i]);
    }
    parts_.push_back(p);
  }
  if (parts_.empty()) return;
  // A grid over the floor plan: each cell lists the parts whose box (a little
  // enlarged) overlaps it, so a pixel tests only the few parts near its point.
  constexpr double kMargin = 0.05;
  x0_ = lo[0] - kMargin;
  y0_ = lo[1] - kMargin;
  nx_ = static_cast<int>((hi[0] - lo[0] + 2 * kMargin) / cell_) + 1;
  ny_ = static_cast<int>((hi[1] - lo[1] + 2 * kMargin) / cell_) + 1;
  cells_.assign(size_t(nx_) * ny_, {});
  for (size_t i = 0; i < parts_.size(); ++i) {
    double half[3];
    parts_[i].half_extent(half);
    const int ix0 = static_cast<int>((parts_[i].pos[0] - half[0] - kMargin - x0_) / cell_);
    const int ix1 = static_cast<int>((parts_[i].pos[0] + half[0] + kMargin - x0_) / cell_);
    const int iy0 = static_cast<int>((parts_[i].pos[1] - half[1] - kMargin - y0_) / cell_);
    const int iy1 = static_cast<int>((parts_[i].pos[1] + half[1] + kMargin - y0_) / cell_);
    for (int ix = std::max(0, ix0); ix <= std::min(nx_ - 1, ix1); ++ix) {
      for (int iy = std::max(0, iy0); iy <= std::min(ny_ - 1, iy1); ++iy) {
        cells_[size_t(iy) * nx_ + ix].push_back(static_cast<int>(i));
      }
    }
  }
}

Segmentation::~Segmentation() = default;

int Segmentation::resolve(const double point[3], int& part) const {
  // A point on the surface of the last pixel's part is on that part (depth is
  // good to ~0.1 mm at 10 m): neighbouring pixels mostly are.
  constexpr double kOnSurface = 1e-3;
  if (part >= 0 && std::abs(parts_[part].distance(point)) < kOnSurface) return parts_[part].instance;
  if (cells_.empty()) return 0;
  const int ix = std::clamp(static_cast<int>(std::floor((point[0] - x0_) / cell_)), 0, nx_ - 1);
  const int iy = std::clamp(static_cast<int>(std::floor((point[1] - y0_) / cell_)), 0, ny_ - 1);
  double nearest = std::numeric_limits<double>::infinity();
  part = -1;
  for (int i : cells_[size_t(iy) * nx_ + ix]) {
    const double distance = std::abs(parts_[i].distance(point));
    if (distance < nearest) {
      nearest = distance;
      part = i;
    }
  }
  return part < 0 ? 0 : parts_[part].instance;
}

void Segmentation::label(const Pinhole& camera, const CameraPose& pose, const std::int32_t* geom, const float* depth,
                         std::int32_t* instance, std::int32_t* semantic) const {
  int part = -1;  // the static part the last resolved pixel lay on
  for (int row = 0, i = 0; row < camera.height; ++row) {
    for (int col = 0; col < camera.width; ++col, ++i) {
      int id = geom[i] < 0 ? 0 : geom_instance_[geom[i]];
      if (id == kResolve) {
        double local[3], world[3];
        camera.unproject(col, row, depth[i], local);
        pose.to_world(local, world);
        id = resolve(world, part);
      }
      if (instance) instance[i] = id;
      if (semantic) semantic[i] = instances_[id].semantic;
    }
  }
}

}  // namespace chore
