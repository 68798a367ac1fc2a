// Early-outs in front of MuJoCo 2.2.2's pair functions for a box against a
// capsule, a cylinder or a box (mjCOLLISIONFUNC, MuJoCo's public table).
// MuJoCo's only filter before a pair function is the geoms' bounding spheres,
// and a 2 m static body of furniture passes dozens of boxes to every capsule
// of a cloth or cylinder of a robot near it: in physical CleanTable ~1,500
// capsule-, cylinder- and box-box calls a physics step, 95% finding nothing,
// each 0.1-0.35 us (the cylinder through libccd's MPR). The early-out is a
// separating-axis test of the two geoms' oriented boxes, ~20 ns: a pair it
// rejects is one MuJoCo's function finds no contact for, so contacts, and
// physics, are the same bit for bit.
#pragma once

#include <mujoco/mjdata.h>
#include <mujoco/mjmodel.h>

namespace chore {

// Puts the early-outs in MuJoCo's table. Once per process; idempotent and
// thread-safe. install_mujoco_handlers() calls it.
void install_pair_early_outs();

// MuJoCo's own function for two geom types (type1 <= type2), as before the
// early-outs.
mjfCollision mujoco_pair_function(int type1, int type2);

// True when geom g1 (a capsule, cylinder or box) and geom g2 (a box) are
// apart by more than `margin` (and a micrometre of slack) along a face normal
// of either's oriented box, so MuJoCo's function would find no contact.
bool geoms_apart(const mjModel* m, const mjData* d, int g1, int g2, double margin);

}  // namespace chore
