// The action primitives of BEHAVIOR-1K (appendix F.4): navigate, pick, place,
// push, dip and wipe, each applied to one object of the scene.
//
//   PrimitiveResult r = execute_primitive(world, PrimitiveType::pick, cup, seed);
//   if (!r.ok()) std::cout << to_string(r.status) << ": " << r.reason;
//
// They are composed of collision-free base paths (OMPL, occupancy map),
// collision-free arm paths (OMPL RRTConnect, MuJoCo collision checks),
// Cartesian straight lines of the hand (IK), gripper open/close and tuck
// motions. In physical mode the smoothed, time-parameterised trajectories are
// tracked by the robot's controllers in physics (contacts, slips and drops
// happen); in symbolic mode the same plans are checked for feasibility and
// their end state is applied kinematically. Ordinary failures are results,
// never exceptions.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "primitives/primitive_types.hpp"
#include "primitives/symbolic_model.hpp"
#include "world/world.hpp"

namespace chore {

struct PrimitiveResult {
  PrimitiveStatus status = PrimitiveStatus::success;
  std::string reason;  // why it failed, briefly
  ExecutionMode mode = ExecutionMode::physical;
  double planning_seconds = 0;   // wall time in samplers, IK and planners
  double execution_seconds = 0;  // wall time in physics (or kinematic updates)
  int64_t physics_steps = 0;     // steps of 1/120 s simulated
  bool diverged = false;         // physics became unstable during execution
  bool grasp_refused = false;    // the hand closed on an object over the mass limit
  bool ok() const { return status == PrimitiveStatus::success; }
};

struct PrimitiveOptions {
  ExecutionMode mode = ExecutionMode::physical;
  int base_pose_samples = 100;       // candidate base poses navigate tries
  unsigned base_iterations = 50000;  // RRTConnect iterations for a base path (grid checks are cheap)
  unsigned arm_iterations = 3000;    // ... and for an arm path
};

// Executes one primitive on scene object `object` (an index into
// world.scene().objects()). The seed fixes every random choice (base pose
// samples, planner samples): the same world state and seed give the same result.
PrimitiveResult execute_primitive(World& world, PrimitiveType type, int object, uint64_t seed,
                                  const PrimitiveOptions& options = {});

// Whether navigate(object) has nothing to do: from where the base stands the
// hand already reaches what the next primitive on it would need (the handle
// of a closed drawer, a place to put what it holds, dirt to wipe, the object
// to pick), in the object's room. navigate fails its precondition then.
bool within_reach(const World& world, int object);

// Why no base pose that the robot could drive to from where it stands brings
// `object` within the arm's reach for `type` (navigate's base-pose search and
// reach test, without driving; the free space joined to the base by a flood
// fill of its occupancy map stands in for base paths), or empty when one
// does. For wipe, the dirt on `object`: the particles out of reach of every
// such pose must be too few for the object to count as covered. dip and wipe
// are checked with a tool hanging 5 cm below the hand (it may not be held
// yet; a rag hangs 3.4 cm). Instance
// sampling uses it to refuse activities the robot could not complete.
std::string out_of_reach(const World& world, PrimitiveType type, int object, uint64_t seed,
                         const PrimitiveOptions& options = {});

// Supports from which an object is likely within the arm's reach, for the
// instance samplers (SampleOptions::prefer): its top not above 1.15 m (the
// hand points down at most 1.2 m high), inside or under something not below
// 0.3 m (the hand points down into a cavity from above), and floor the base
// stands on (the occupancy map of the world as it is now) 0.35-0.55 m away,
// 0.45 m for a top above 1 m (the envelope narrows: Ik tests; nearer than
// the empty hand needs, since a load narrows it too). A preference, cheap to
// test: out_of_reach() decides.
std::function<bool(const Eigen::Vector3d& support, double height, bool covered)> arm_reach_preference(
    const World& world);

// out_of_reach() of (types[i], objects[i]) for each i, as an activity would
// be done: pushes first, from the world as it is, then the others with what
// the pushes open pulled open as push leaves it (the hand holds one thing at
// a time, so what it picks must be within reach once the drawers are open).
// The world is left as it was. The first check that fails (index -1: none);
// objects that are not real (World::real: not made yet) are not checked.
struct ReachProblem {
  int index = -1;
  std::string reason;
};
ReachProblem first_out_of_reach(World& world, const std::vector<PrimitiveType>& types, const std::vector<int>& objects,
                                uint64_t seed);

// Why executing `type` on `object` now would fail its precondition, or empty
// when it holds: the state checks each primitive starts with (pick and push
// need an empty hand, place, dip and wipe a carried object, push a drawer not
// yet open, navigate an object not already within_reach). The primitive
// action space's action_mask observation is where this is empty.
std::string unmet_precondition(const World& world, PrimitiveType type, int object);

// Whether a primitive can apply to an object at all (its kind, not the state):
// pick for free objects the gripper can lift, push for articulated ones, dip
// for liquid containers, wipe for objects dirt can lie on; navigate and place
// for any (which objects are placement targets is the activity's to say).
bool primitive_applies(const World& world, PrimitiveType type, int object);

// The symbolic model of `type` (primitives/symbolic_model.hpp), as the task
// planner uses it: the steps it can be with `args` on these objects (none
// where it cannot act on them), and whether it takes a substance.
std::vector<SymbolicStep> primitive_model(PrimitiveType type, const std::vector<SymbolicObject>& objects,
                                          const SymbolicArgs& args);
bool primitive_about_substance(PrimitiveType type);

// Whether the hand acts on the object itself (pick, push, dip, wipe), not
// from beside it (navigate) or above it (place).
bool primitive_touches(PrimitiveType type);
// Whether it executes physically too (fold and unfold are symbolic only).
bool primitive_is_physical(PrimitiveType type);

}  // namespace chore
