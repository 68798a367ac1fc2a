// Logical predicates as sampling functions (seed Table A.9): each finds a
// physical state of a free object that makes the predicate true, by a ray-cast
// search for a support surface, a collision test and a short physical settle,
// as BEHAVIOR's samplers do. They never consult the checking functions
// (predicates.hpp): the tests measure how often the checkers agree.
#pragma once

#include <Eigen/Core>

#include <functional>
#include <string>

#include "base/random.hpp"
#include "world/world.hpp"

namespace chore {

struct SampleOptions {
  int attempts = 100;            // candidate poses before giving up
  double settle_seconds = 0.25;  // physics after placing (objects drop from 5 mm)
  // Where the robot can act: when set, the first half of the attempts keep
  // only candidates whose support point (x, y and the height the object
  // would stand at) it accepts for an object `height` tall, `covered` when
  // something of the support lies above (inside, under), and inside keeps
  // room for fingers (kHandRoom) between the object and the container's
  // walls; the rest take any. BEHAVIOR samples uniformly over scenes whose
  // shelves and counters a person's arm reaches; chore's generated analogs
  // are not tuned so, and this keeps an instance's objects where the
  // robot's arm reaches them when the predicate allows (Env: the
  // primitives' arm_reach_preference()).
  std::function<bool(const Eigen::Vector3d& support, double height, bool covered)> prefer;
};

// Each returns false when no valid pose was found in options.attempts tries;
// `a` must be a free object (chore::Error otherwise).
bool sample_ontop(World& world, int a, int b, Rng& rng, const SampleOptions& options = {});
bool sample_inside(World& world, int a, int b, Rng& rng, const SampleOptions& options = {});
bool sample_under(World& world, int a, int b, Rng& rng, const SampleOptions& options = {});
bool sample_onfloor(World& world, int a, int room, Rng& rng, const SampleOptions& options = {});
// a attached to b (BDDL's attached): a on top of b's box at a random point of
// it, turned a quarter turn at a time, clear of all but b, held there by
// their attachment weld (Scene::attachments()); false when the scene has none
// for the pair or no pose is clear.
bool sample_attached(World& world, int a, int b, Rng& rng, const SampleOptions& options = {});
// The robot's base at a collision-free pose in `room` (200 tries).
bool sample_robot_in_room(World& world, int room, Rng& rng);
// Sets an articulated object open (one joint, at random, between 30% and 100%
// of its range) or closed (every joint at its lower limit; an object without
// joints is closed as it is). chore::Error for opening one without joints.
void sample_open(World& world, int a, bool open, Rng& rng);

// A unary predicate on extended states made `value`: cooked, burnt, frozen, hot,
// on_fire, soaked, saturated, filled, contains, toggled_on, sliced, broken. It writes the
// state the checker reads, as OmniGibson's samplers do (cooked: the highest
// temperature reached is past the cook temperature). chore::Error for an
// unknown predicate, or for `value` true on an object that does not keep that
// state (missing_for_state); false on such an object holds as it is.
// soaked, saturated, filled and contains name their substance.
void sample_state(World& world, const std::string& predicate, int a, bool value, const std::string& liquid = "water");
// Dirt particles of `substance` on a's upward-facing surfaces (value true:
// `particles` of them, found by rays from above that hit a first), or none;
// chore::Error for value true on what keeps no dirt.
bool sample_covered(World& world, int a, const std::string& substance, bool value, Rng& rng, int particles = 20);

}  // namespace chore
