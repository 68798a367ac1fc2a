// Geometric queries about scene objects: axis-aligned bounding boxes and ray
// casts restricted to one object's collision geoms. The predicate checkers
// (predicates.hpp) and samplers (sampling.hpp) are built on these.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "world/aabb.hpp"
#include "world/world.hpp"

namespace chore {

// An object's frame in the world: its root body's pose, or where furniture
// compiled into the world body stands (Scene's tables: it has no body of its own).
struct Frame {
  Eigen::Vector3d pos;
  Eigen::Matrix3d rot;
  Eigen::Vector3d to_world(const Eigen::Vector3d& local) const { return pos + rot * local; }
  Eigen::Vector3d to_local(const Eigen::Vector3d& world) const { return rot.transpose() * (world - pos); }
};
Frame object_frame(const World& world, int object);

// World-frame box of one geom (primitive shapes; meshes by their bounding sphere).
Aabb geom_aabb(const World& world, int geom);
// The same with the geom at xpos, xmat (MuJoCo layout) instead of where the world has it.
Aabb geom_aabb(const mjModel_* model, int geom, const double* xpos, const double* xmat);
// World-frame box of an object's collision geoms (links included).
Aabb object_aabb(const World& world, int object);

// Distance along the unit ray (p, dir) to the nearest of `geoms`, or -1 if
// none is hit within max_distance.
double ray_to_geoms(const World& world, const std::vector<int>& geoms, const Eigen::Vector3d& p,
                    const Eigen::Vector3d& dir, double max_distance);
// The same against one object's geoms.
double ray_to_object(const World& world, int object, const Eigen::Vector3d& p, const Eigen::Vector3d& dir,
                     double max_distance);

// Whether any geom of object `a` is in contact with any geom of object `b`
// (b = -1: with any geom of `geoms_b` instead).
bool in_contact(const World& world, int a, int b);
bool in_contact_with_geoms(const World& world, int a, const std::vector<int>& geoms);

}  // namespace chore
