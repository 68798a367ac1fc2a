// The rules that update the extended object states (object_states.hpp) as the
// world moves, after every physics step (contacts, liquids, cleaning) and every
// env step (heat, toggling), and how the states look in a rendered scene.
#pragma once

#include <vector>

#include "world/aabb.hpp"
#include "world/world.hpp"

struct mjContact_;
struct mjvScene_;

namespace chore {

// Contact- and liquid-driven rules, after each physics step: soaking by the
// objects' boxes, cleaning, breaking and slicing by the world's contacts.
void update_states_after_physics_step(World& world, double dt);
// The same rules at a waypoint of a symbolic motion, where only `moved` (what
// the robot carries) has moved since the world's contacts were computed: its
// box and its contacts (no forces: nothing is solved) are given. The world's
// other contacts are left out: they acted when computed, and without new
// forces or positions they act the same again.
void update_states_at_motion_waypoint(World& world, double dt, int moved, const Aabb& moved_box,
                                      const std::vector<mjContact_>& moved_contacts);
// Where the hand presses to toggle an object: the top centre of its box;
// for what opens, the front edge of its carcass's top (its frame's -y). The
// rule toggles it after ObjectStates::kToggleSteps consecutive env steps with
// the fingers (from the hand's centre to the fingertips) held within
// ObjectStates::kToggleDistance of it (the hand slower than
// ObjectStates::kToggleSpeed).
Eigen::Vector3d toggle_point(const World& world, int object);
// Whether heat or cold source `source` (its ThermalSource `t`) acts on
// `object` now: on, closed, near or inside, as it requires.
bool thermal_source_acts(const World& world, int source, const ThermalSource& t, int object);
// Whether `object` is where the source would act on it were it on (and closed).
bool within_thermal_reach(const World& world, int source, const ThermalSource& t, int object);
// Heat transfer, toggling and the transitions (world/transitions.hpp), after
// each env step of `dt` seconds.
void update_states_after_env_step(World& world, double dt);

// How the states look, in a scene being rendered (after mjv_updateScene):
// OmniGibson's texture change recolours frozen, burnt, cooked and soaked
// objects (the first that holds, in that order), and the dirt particles are
// drawn as small flat discs.
void draw_states(const World& world, mjvScene_* scene);

}  // namespace chore
