#include "world/pair_early_outs.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Core>
#include <mutex>

namespace chore {
namespace {

// Beyond the margin, so that rounding in MuJoCo's own tests (and libccd's
// tolerance, 1e-6) cannot turn a rejected pair into a contact.
constexpr double kSlack = 1e-5;

using Rotation = Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>;
using Point = Eigen::Map<const Eigen::Vector3d>;

// Half-extents of a box around the geom, in its own frame (its axis is z).
Eigen::Vector3d half_extents(int type, const double* size) {
  switch (type) {
    case mjGEOM_CAPSULE:
      return {size[0], size[0], size[1] + size[0]};
    case mjGEOM_CYLINDER:
      return {size[0], size[0], size[1]};
    default:
      return {size[0], size[1], size[2]};
  }
}

std::once_flag installed;
mjfCollision original[mjNGEOMTYPES][mjNGEOMTYPES];

template <int Type1>
int early_out(const mjModel* m, const mjData* d, mjContact* con, int g1, int g2, mjtNum margin) {
  if (geoms_apart(m, d, g1, g2, margin)) return 0;
  return original[Type1][mjGEOM_BOX](m, d, con, g1, g2, margin);
}

}  // namespace

bool geoms_apart(const mjModel* m, const mjData* d, int g1, int g2, double margin) {
  const Rotation r1(d->geom_xmat + 9 * g1), r2(d->geom_xmat + 9 * g2);
  const Eigen::Vector3d e1 = half_extents(m->geom_type[g1], m->geom_size + 3 * g1);
  const Eigen::Vector3d e2 = half_extents(m->geom_type[g2], m->geom_size + 3 * g2);
  const Eigen::Vector3d between = Point(d->geom_xpos + 3 * g2) - Point(d->geom_xpos + 3 * g1);
  const Eigen::Matrix3d turn = (r1.transpose() * r2).cwiseAbs();  // g2's axes in g1's frame
  // Twice the margin: MuJoCo's MPR grows each of the two shapes by it.
  const double reach = 2 * margin + kSlack;
  const Eigen::Vector3d along1 = (r1.transpose() * between).cwiseAbs() - e1 - turn * e2;
  const Eigen::Vector3d along2 = (r2.transpose() * between).cwiseAbs() - e2 - turn.transpose() * e1;
  return (along1.array() > reach).any() || (along2.array() > reach).any();
}

void install_pair_early_outs() {
  std::call_once(installed, [] {
    for (int a = 0; a < mjNGEOMTYPES; ++a) {
      for (int b = 0; b < mjNGEOMTYPES; ++b) original[a][b] = mjCOLLISIONFUNC[a][b];
    }
    mjCOLLISIONFUNC[mjGEOM_CAPSULE][mjGEOM_BOX] = early_out<mjGEOM_CAPSULE>;
    mjCOLLISIONFUNC[mjGEOM_CYLINDER][mjGEOM_BOX] = early_out<mjGEOM_CYLINDER>;
    mjCOLLISIONFUNC[mjGEOM_BOX][mjGEOM_BOX] = early_out<mjGEOM_BOX>;
  });
}

mjfCollision mujoco_pair_function(int type1, int type2) {
  install_pair_early_outs();
  return original[type1][type2];
}

}  // namespace chore
