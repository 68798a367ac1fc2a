// The primitive action space of an activity (BEHAVIOR-1K appendix F.4):
// Discrete over (primitive, object) pairs, derived from the activity's BDDL
// and the bound objects' kinds, never written per task:
//   navigate  every object the activity declares (its relevant locations)
//   pick      those the gripper can lift (free, under the mass limit)
//   place     the supports and containers: second arguments of ontop/inside
//             in :init or :goal (a quantified variable: every object of its
//             type), when the :goal has such a literal at all
//   push      articulated ones (drawers) that an open literal names or the
//             :goal puts something on or in
//   dip       liquid containers and sources
//   wipe      those a stained/dusty/covered literal names (and dirt can lie on)
//   toggle_on/off  toggleable objects
//   pour      what a goal's contains/filled/covered fills or covers
//   place_next_to  what a goal's nextto names
//   cut       sliceable objects, where the activity has a slicer
//   attach    what a goal's attached attaches to
//   fold/unfold    cloths a folded/unfolded literal names (symbolic mode only)
// Objects in :objects order, primitives in that order for each.
#pragma once

#include <string>
#include <vector>

#include "primitives/primitive.hpp"
#include "tasks/activity.hpp"
#include "world/world.hpp"

namespace chore {

struct PrimitiveAction {
  PrimitiveType type;
  int object;            // index into the scene's objects
  std::string instance;  // the BDDL instance, e.g. pumpkin.n.02_1
};

// "pick(pumpkin.n.02_1)"
std::string to_string(const PrimitiveAction& action);

// `world` must be configured by the activity (its extended states say which
// objects hold liquid or can be dirty).
// Primitives that execute symbolically only (fold) are left out in physical mode.
std::vector<PrimitiveAction> primitive_actions(const Activity& activity, const World& world, ExecutionMode mode);

}  // namespace chore
