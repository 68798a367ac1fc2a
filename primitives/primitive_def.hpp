// What one primitive is, for the executor and the reach checks: internal to
// primitives/. Each primitive defines its PrimitiveDef in its own file
// (navigate.cpp, pick.cpp, ...), and CHORE_PRIMITIVES in primitive_types.hpp
// lists them; primitive.cpp holds what they share: where the hand acts, the
// base-pose sampler, the reach test and the Executor that runs a primitive.
#pragma once

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "primitives/arm_planner.hpp"
#include "primitives/base_planner.hpp"
#include "primitives/ik.hpp"
#include "primitives/motion.hpp"
#include "primitives/primitive.hpp"
#include "primitives/symbolic_model.hpp"
#include "world/robot.hpp"

namespace chore {

// Wall time since t, for PrimitiveResult's planning and execution seconds.
using Clock = std::chrono::steady_clock;
inline double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

inline const Eigen::Vector3d kDown(0, 0, -1), kUp(0, 0, 1);
// The hand's direction tilted 45 degrees from straight down towards a
// horizontal direction: where nothing reaches down onto a point (a shelf
// above it; a top higher than a hand pointing down gets).
inline Eigen::Vector3d tilted_towards(const Eigen::Vector3d& horizontal) {
  return (horizontal.normalized() + kDown).normalized();
}
inline constexpr double kFingerReach = Robot::kFingertips;  // m from the hand's centre to the fingertips
inline constexpr double kClearance = 0.10;                  // m above a target before descending
inline constexpr double kHighestDown = 1.2;     // m: the hand pointing down gets no higher (tilted 45 degrees: 1.3-1.4)
inline constexpr double kLift = 0.15;           // m raised after grasping or releasing
inline constexpr double kContactDepth = 0.05;   // m below an object's top the fingertips may need to reach
inline constexpr double kPullFraction = 0.9;    // of a drawer's range, push opens it this far
inline constexpr double kApproachSpeed = 0.15;  // m/s of the hand towards a contact
inline constexpr double kRetreatSpeed = 0.2;    // m/s of the hand away from one

// The articulated joint a push opens, and the geometry it moves: a drawer
// (a slide joint) or a door or lid (a hinge).
struct Articulation {
  int joint = -1, link = -1;
  bool hinge = false;
  Eigen::Vector3d axis;   // world: a drawer's opening direction; a hinge's axis (opening turns about it right-handed)
  Eigen::Vector3d pivot;  // world: a point on a hinge's axis
  // Where the hand takes hold: a drawer's front (the centre of its geom
  // furthest along axis); on a door, its front face a hand's width in from
  // the edge furthest from the hinge, half way along the hinge.
  Eigen::Vector3d handle;
  Eigen::Vector3d pull;                 // world direction in which the handle moves as the link opens (a drawer's axis)
  double low = 0, high = 0, value = 0;  // m, or rad
};
std::optional<Articulation> articulation(const World& w, int object);
double open_fraction(const Articulation& a);
// Sets the link's joint to `value` (clamped to its range), without physics:
// a drawer carries what lies in it along, as its floor does when pulled (set
// alone, the joint would leave the contents standing in the carcass).
void set_articulation(World& w, const Articulation& a, double value);

// Where a primitive acts on an object: the hand's target and approach.
struct Approach {
  Eigen::Vector3d point;      // on the object: top centre, handle, dirt, ...
  Eigen::Vector3d direction;  // the hand's approach axis there
  std::optional<Eigen::Vector3d> closing;
  // Tried only with every start (the base-pose search's second pass): where
  // nothing else reaches from any pose (a pick from the side).
  bool last_resort = false;
};

// Whether the hand comes down onto the approach point (a load hanging below
// it first), rather than in from the side (a shelf, an upright object).
inline bool from_above(const Approach& a) {
  return a.direction.z() < -0.5;
}

// Where a place or dip aims (an open drawer's exposed part, else the
// object's top, at the spot farthest from what lies there already), with
// the robot standing at `base`: the carried load's footprint turns with the
// base.
Eigen::Vector3d top_centre(const World& w, int object, const Pose2& base);
// top_centre(), then, with a load, the flat spot of the top nearest the base
// (a deep counter's near side: the arm reaches less far with a load; not in
// an open drawer).
std::vector<Eigen::Vector3d> top_spots(const World& w, int object, const Pose2& base);
// From above onto each of top_spots() and, with a load, tilted_onto() them:
// the default approaches.
std::vector<Approach> onto_top(const World& w, int object, const Pose2& base);
// Onto `spot` with a load, where the hand pointing down would be higher than
// it gets (kHighestDown; a tall load over a counter): tilted 45 degrees
// towards the spot from the base, which reaches higher, and the load, hanging
// along the hand's axis, a third lower. A last resort (Approach::last_resort).
std::optional<Approach> tilted_onto(const World& w, const Eigen::Vector3d& spot, const Pose2& base);
// How far, in the plane, p lies from the nearest loose object (not fixed,
// not carried, not `object`) whose centre is between heights lo and hi; 1e9
// with none: where a load set down leaves the most room.
double room_among_loose(const World& w, const Eigen::Vector3d& p, int object, double lo, double hi);
// Where the dirt on an object lies (world frame).
std::vector<Eigen::Vector3d> dirt_particles(const World& w, int object);
// How far a held object hangs below the hand's centre (0 with an empty hand).
double load_below_hand(const World& w);
// Where the hand's centre is when the fingertips reach as deep past the
// approach point as they may need to (an object's top, or half way through a
// thin one).
Eigen::Vector3d contact_point(const World& w, int object, const Approach& a);
// How far past the approach point the fingertips may need to go.
double contact_depth(const World& w, int object, const Approach& a);
// Where the hand may act on `object` for `type`, in order of preference.
std::vector<Approach> approaches(const World& w, PrimitiveType type, int object, const Pose2& base);

// A collision-free IK solution for the pre-pose of the first of `candidates`
// that works with the base at `base`, from which, when the primitive touches
// the object, the hand can follow the approach to its line end touching
// nothing but the object itself; the IK starts from each of the first
// `starts` of kReachStarts in turn (last-resort approaches only with all of them).
struct Reach {
  ArmConfiguration joints;
  Approach approach;
};
std::optional<Reach> reach(IkSolver& ik, ArmCollisionChecker& checker, const World& w, int object,
                           const std::vector<Approach>& candidates, const Pose2& base, PrimitiveType type, double load,
                           size_t starts = kReachStarts.size());

// OmniGibson's base-pose sampler (primitive.cpp): candidate poses near the
// object, kept when in the same room, collision-free and within reach (from
// the untucked start alone first, then from any of kReachStarts). Draws
// go round the points of `around`; a pose is within reach when reach() finds
// one of `targets(pose)`. `use` gets each pose kept, with how many of
// kReachStarts reached from it, and ends the search by returning true, which
// is then returned.
struct BasePoseTally {
  int blocked = 0, elsewhere = 0, unreachable = 0;
  int cut_off = 0;  // within reach, but the base cannot drive there from where it stands (the reach checks)
  std::string to_string() const;  // "of N draws: B blocked, ..." for a reason
};
bool sample_base_poses(const World& w, IkSolver& ik, ArmCollisionChecker& checker, const Footprint& footprint,
                       PrimitiveType purpose, int object, const std::vector<Approach>& around,
                       const std::function<std::vector<Approach>(const Pose2&)>& targets, uint64_t seed, double load,
                       int samples, BasePoseTally& tally, const std::function<bool(const Pose2&, size_t)>& use);

// out_of_reach()'s search: base poses the robot can drive to from where it
// stands, and those found within reach so far.
struct ReachSearch {
  const World& w;
  PrimitiveType type;
  int object;
  uint64_t seed;  // of the search; a primitive searching more than once takes the next ones
  double load;    // m hanging below the hand: dip and wipe count a tool in hand
  const PrimitiveOptions& options;
  IkSolver& ik;
  ArmCollisionChecker& checker;
  const Footprint& footprint;
  OccupancyMap drivable;    // the free space joined to the base
  std::vector<Pose2> kept;  // poses within reach that the base can drive to
  BasePoseTally tally;
  // Whether a drivable base pose brings one of targets(pose) within reach,
  // draws going round the points of `around`; the pose found is kept.
  bool sample(const std::vector<Approach>& around, const std::function<std::vector<Approach>(const Pose2&)>& targets,
              uint64_t sample_seed);
  // Whether a kept pose brings one of targets(pose) within reach.
  bool kept_reaches(const std::function<std::vector<Approach>(const Pose2&)>& targets);
};

struct PrimitiveDef;

// Runs one primitive: what the primitives' act() functions build on.
class Executor {
 public:
  Executor(World& w, PrimitiveType type, int object, uint64_t seed, const PrimitiveOptions& options);
  PrimitiveResult run();

  World& world() { return w_; }
  int object() const { return object_; }
  const std::string& name() const { return w_.scene().objects()[object_].name; }
  Motion& motion() { return motion_; }
  PrimitiveResult& result() { return result_; }
  const PrimitiveOptions& options() const { return options_; }
  const Approach& approach() const { return approach_; }  // the one reach_pre_pose() chose

  bool fail(PrimitiveStatus s, const std::string& why) { return motion_.fail(s, why); }
  // Whether the arm is at q (each joint within 0.05 rad).
  bool at(const ArmConfiguration& q) const;
  // The end of a manipulation: tucked (or carrying) where the arm fits. Where
  // furniture blocks that pose the effect still holds and the arm stays as it
  // is: navigate tucks before driving, or drives with the arm as it is.
  bool tuck_where_possible();
  // Untuck, then a collision-free path to the pre-pose.
  bool go_to_pre_pose();
  // The pre-pose, then the load (which hangs off-centre from the hand) moved
  // over the spot it is aimed at.
  bool go_to_pre_pose_with_load();
  // Opens the hand where it is (symbolically the load drops straight onto
  // what is below it), waits 0.3 s, lifts and tucks: the end of a place.
  bool release();

 private:
  bool reach_pre_pose(ArmConfiguration& q);

  World& w_;
  PrimitiveType type_;
  const PrimitiveDef& def_;
  int object_;
  PrimitiveOptions options_;
  PrimitiveResult result_;
  Motion motion_;
  Approach approach_;
};

struct PrimitiveDef {
  // Whether it can apply to the object at all (its kind, not the state).
  bool (*applies)(const World& w, int object);
  // Why executing it now would fail its precondition, or empty.
  std::string (*unmet_precondition)(const World& w, int object);
  // Acts, after the precondition held; false after e.fail().
  bool (*act)(Executor& e);
  // Its symbolic model (symbolic_model.hpp): the steps it can be with `args`
  // on these objects (alternatives, e.g. one per solvent a stain needs), none
  // where it cannot act on them.
  std::vector<SymbolicStep> (*model)(const std::vector<SymbolicObject>& objects, const SymbolicArgs& args);
  // Where the hand acts: null for the default, onto_top().
  std::vector<Approach> (*approaches)(const World& w, int object, const Pose2& base) = nullptr;
  // Where the hand's centre ends the line along approach `a` from a base at
  // `base`, with `load` hanging below the hand: null for at contact,
  // fingertips contact_depth() into the object.
  Eigen::Vector3d (*line_end)(const World& w, int object, const Approach& a, const Pose2& base, double load) = nullptr;
  // Why out_of_reach() fails: null for the default, no base pose reaching
  // one of approaches().
  std::string (*out_of_reach)(ReachSearch& search) = nullptr;
  bool about_substance = false;  // the model takes a substance (dip: the liquid; wipe: the dirt)
  bool touches = true;           // the hand follows the approach into contact with the object
  bool with_tool = false;        // acts with a tool in hand (reach checks count one hanging below it)
  bool opens = false;            // opens an articulated object: the base stands in front of it, room to pull
  // Reach checks (first_out_of_reach) leave its object's own doors as the
  // world has them, not pulled open as the other checks have them: a plan
  // shuts them first where it must (an oven heats shut), and an oven's door,
  // open, stands where the base would be to press its knob.
  bool own_doors_as_they_are = false;
  bool drives = false;         // moves the base: checks its own precondition, no tuck after failing
  bool symbolic_only = false;  // no physical execution (act fails it); offered in symbolic action spaces only
  // rad: base poses drawn face the target within +-half this (side-on: pi);
  // reach() takes an approach from a base facing its point within +-this
  // (the base arrives a little turned).
  double yaw_spread = M_PI;
  double clearance = kClearance;  // m the pre-pose keeps above the approach point (fingertips or load first)
};

// The registry: the PrimitiveDef of each type, name_primitive() for each
// name of CHORE_PRIMITIVES, defined in primitives/<name>.cpp.
#define CHORE_PRIMITIVE_DEF(name) const PrimitiveDef& name##_primitive();
CHORE_PRIMITIVES(CHORE_PRIMITIVE_DEF)
#undef CHORE_PRIMITIVE_DEF
const PrimitiveDef& primitive_def(PrimitiveType type);

}  // namespace chore
