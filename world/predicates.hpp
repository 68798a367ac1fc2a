// Logical predicates as checking functions (seed Table A.8), computed from the
// physical state the way BEHAVIOR's public code does: ray casts from an
// object's centre for vertical and horizontal neighbours, AABB gaps, contacts,
// and the 5% rule for articulated joints. Objects are indices into
// world.scene().objects(); rooms are indices into world.scene().rooms().
#pragma once

#include <string>

#include "world/world.hpp"

namespace chore {

bool touching(const World& world, int a, int b);
// a rests on b: in contact, b below a's centre (a cloth's middle) and not above it.
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
// The robot's camera sees part of a (its box centre, unoccluded, in the frustum).
bool infov(const World& world, int a);
// a's box is within the arm's reach (1 m) of the robot's shoulder axis.
bool inreach(const World& world, int a);
bool insameroom(const World& world, int a, int b);
// Cloths: the farthest pair of corner keypoints spans under 75% of the flat
// diagonal (folded) or over 90% (unfolded); in between, neither.
bool folded(const World& world, int a);
bool unfolded(const World& world, int a);
// Cloths on b, as OmniGibson's Overlaid and Draped: in contact with b, and
// covering at least half of b's horizontal extent from above (overlaid), or
// lying over b's top with part of it hanging 5 cm or more below it (draped).
// False for objects that are not cloths.
bool overlaid(const World& world, int a, int b);
bool draped(const World& world, int a, int b);
// a and b are held together by an active equality constraint (b = -1: the
// robot, e.g. through the assistive grasp's weld).
bool attached(const World& world, int a, int b);

// Predicates on extended states (false for objects that do not keep the state).
bool cooked(const World& world, int a);   // highest temperature reached >= cook temperature
bool burnt(const World& world, int a);    // highest temperature reached >= burn temperature
bool frozen(const World& world, int a);   // temperature <= freeze temperature
bool hot(const World& world, int a);      // temperature >= hot temperature (OmniGibson "heated")
bool on_fire(const World& world, int a);  // temperature >= ignition temperature
// Liquids by name ("water"): absorbed at least half of it, or all of it.
bool soaked(const World& world, int a, const std::string& liquid = "water");
bool saturated(const World& world, int a, const std::string& liquid = "water");
bool covered(const World& world, int a, const std::string& substance);
// BEHAVIOR-100's stained and dusty, as iGibson computes them: dirty while more
// than half of the particles sampled remain (covered asks for all but four gone).
bool dirty(const World& world, int a, const std::string& substance);
// A container holds `substance` up to a fifth of its inner height or more
// (filled), or any of it (contains).
bool filled(const World& world, int a, const std::string& substance = "water");
bool contains(const World& world, int a, const std::string& substance);
// Whether any object holds `substance`, is covered with it or has soaked it up
// (BDDL's (real substance)).
bool substance_exists(const World& world, const std::string& substance);
bool toggled_on(const World& world, int a);
bool sliced(const World& world, int a);
bool broken(const World& world, int a);

}  // namespace chore
