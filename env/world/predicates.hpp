// Logical predicates as checking functions (seed Table A.8), computed from the
// physical state the way BEHAVIOR's public code does: ray casts from an
// object's centre for vertical and horizontal neighbours, AABB gaps, contacts,
// and the 5% rule for articulated joints. Objects are indices into
// world.scene().objects(); rooms are indices into world.scene().rooms().
#pragma once

#include "env/world/world.hpp"

namespace chore {

bool touching(const World& world, int a, int b);
// a rests on b: in contact, b below a's centre and not above it.
bool ontop(const World& world, int a, int b);
// a's centre is in b's box and b encloses it on both sides along at least two
// of three axes (vertical, and two horizontal ones).
bool inside(const World& world, int a, int b);
// Boxes closer than a sixth of their mean size, and b in a's horizontal plane.
bool nextto(const World& world, int a, int b);
// b above a's centre and not below it.
bool under(const World& world, int a, int b);
// a rests on the floor of `room`.
bool onfloor(const World& world, int a, int room);
// a's centre is over the floor of `room`.
bool inroom(const World& world, int a, int room);
// Any articulated joint of a is past 5% of its range from closed (its lower limit).
bool is_open(const World& world, int a);
bool grasped(const World& world, int a);

}  // namespace chore
