#include "primitives/primitive.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <random>

#include "base/error.hpp"
#include "primitives/arm_planner.hpp"
#include "primitives/base_planner.hpp"
#include "primitives/motion.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

const Eigen::Vector3d kDown(0, 0, -1), kUp(0, 0, 1);
constexpr double kFingerReach = 0.04;   // m from the hand's centre to the fingertips
constexpr double kClearance = 0.10;     // m above a target before descending
constexpr double kLift = 0.15;          // m raised after grasping or releasing
constexpr double kContactDepth = 0.05;  // m below an object's top the fingertips may need to reach
constexpr double kToolHang = 0.05;      // m a tool held for dip or wipe is taken to hang below the hand (a rag: 3.4 cm)
constexpr double kSoakDepth = 0.04;     // m under a liquid's surface that dip lowers the held object
// Wipe strokes: kRows rows kRowSpacing apart, the first kFarRow beyond the approach point.
constexpr int kRows = 4;
constexpr double kRowSpacing = 0.08, kFarRow = 1.5 * kRowSpacing;
constexpr double kWipeYawSpread = 0.6;   // rad: a base pose to wipe from faces the dirt within +-0.3
constexpr double kSlim = 0.08;           // m: objects this narrow fit between the open fingers
constexpr double kPullFraction = 0.9;    // of a drawer's range, push opens it this far
constexpr double kApproachSpeed = 0.15;  // m/s of the hand towards a contact
constexpr double kRetreatSpeed = 0.2;    // m/s of the hand away from one
constexpr int kDrawsPerSample = 20;      // base-pose draws per free candidate, at most
constexpr double kCorridorStep = 0.02;   // m between the hand poses checked along an approach
constexpr double kFlatTolerance = 0.02;  // m: a place spot's support heights may differ this much
// No hand pose is this far (horizontally) from the base's axis: shoulder 0.09 m
// ahead of it, arm and gripper ~1 m long. Farther targets skip the IK solve.
constexpr double kArmReachBound = 1.5;

const char* const kTypeNames[] = {"navigate", "pick", "place", "push", "dip", "wipe"};
const char* const kModeNames[] = {"physical", "symbolic"};
const char* const kStatusNames[] = {"success", "motion_planning_failure", "grasp_failure", "place_failure",
                                    "precondition_failure"};

// The articulated joint a push opens, and the geometry it moves.
struct Articulation {
  int joint = -1, link = -1;
  Eigen::Vector3d axis;    // world direction in which the link opens
  Eigen::Vector3d handle;  // centre of the link's geom furthest along axis
  double low = 0, high = 0, value = 0;
};

std::optional<Articulation> articulation(const World& w, int object) {
  const SceneObject& o = w.scene().objects()[object];
  const mjModel* m = w.model();
  const mjData* d = w.data();
  for (int joint : o.joints) {
    if (m->jnt_type[joint] != mjJNT_SLIDE) continue;  // hinged doors: not yet (docs/primitives.md)
    Articulation a;
    a.joint = joint;
    a.link = m->jnt_bodyid[joint];
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(d->xmat + 9 * a.link);
    a.axis = r * Eigen::Vector3d(m->jnt_axis[3 * joint], m->jnt_axis[3 * joint + 1], m->jnt_axis[3 * joint + 2]);
    a.low = m->jnt_range[2 * joint];
    a.high = m->jnt_range[2 * joint + 1];
    a.value = d->qpos[m->jnt_qposadr[joint]];
    double furthest = -1e9;
    for (int g = 0; g < m->ngeom; ++g) {
      if (m->geom_bodyid[g] != a.link) continue;
      const Eigen::Vector3d c(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
      const Aabb box = geom_aabb(w, g);
      const double reach = std::max(a.axis.dot(box.lo), a.axis.dot(box.hi));
      if (reach > furthest + 1e-6) {
        furthest = reach;
        a.handle = c;
      }
    }
    return a;
  }
  return std::nullopt;
}

double open_fraction(const Articulation& a) {
  return (a.value - a.low) / (a.high - a.low);
}

// Where a primitive acts on an object: the hand's target and approach.
struct Approach {
  Eigen::Vector3d point;      // on the object: top centre, handle, dirt, ...
  Eigen::Vector3d direction;  // the hand's approach axis there
  std::optional<Eigen::Vector3d> closing;
};

// Where a place or dip aims: over an open drawer's exposed part, else over
// the object's box, at the spot farthest from the free objects already there
// (the second pumpkin goes beside the first), on top.
Eigen::Vector3d top_centre(const World& w, int object) {
  Eigen::Vector3d centre, along, across;  // the region: centre +- along +- across
  double top = 0;
  if (const auto a = articulation(w, object); a && open_fraction(*a) > 0.3) {
    Aabb link;
    for (int g = 0; g < w.model()->ngeom; ++g) {
      if (w.model()->geom_bodyid[g] == a->link) link.grow(geom_aabb(w, g));
    }
    // The part outside the cabinet: from the drawer's front back by how far it is open.
    const double front = std::max(a->axis.dot(link.lo), a->axis.dot(link.hi));
    const double open = a->value - a->low;
    centre = link.center() + a->axis * (front - open / 2 - a->axis.dot(link.center()));
    along = a->axis * (open / 2);
    const Eigen::Vector3d side = kUp.cross(a->axis);
    across = side * std::abs(side.dot(link.hi - link.lo)) / 2;
    top = link.hi.z();
  } else {
    const Aabb box = object_aabb(w, object);
    centre = box.center();
    along = Eigen::Vector3d((box.hi.x() - box.lo.x()) / 2, 0, 0);
    across = Eigen::Vector3d(0, (box.hi.y() - box.lo.y()) / 2, 0);
    top = box.hi.z();
  }
  // Keep the carried object's half width inside the region.
  double margin = 0.03;
  if (const int held = w.carried_object(); held >= 0) {
    const Aabb h = object_aabb(w, held);
    margin += std::max(h.hi.x() - h.lo.x(), h.hi.y() - h.lo.y()) / 2;
  }
  const double fa = std::max(0.0, 1 - margin / std::max(along.norm(), 1e-9));
  const double fc = std::max(0.0, 1 - margin / std::max(across.norm(), 1e-9));
  const auto& objects = w.scene().objects();
  if (w.carried_object() < 0) return {centre.x(), centre.y(), top};  // nothing to set down
  // A spot is flat when rays down through the load's footprint all land on
  // the target at one height: not half on a bin's rim or off a table's edge.
  const Aabb load = object_aabb(w, w.carried_object());
  const double half_x = (load.hi.x() - load.lo.x()) / 2, half_y = (load.hi.y() - load.lo.y()) / 2;
  const auto flat = [&](const Eigen::Vector3d& p) {
    double lowest = 1e9, highest = -1e9;
    for (const auto& [dx, dy] :
         {std::pair{0.0, 0.0}, {half_x, half_y}, {half_x, -half_y}, {-half_x, half_y}, {-half_x, -half_y}}) {
      const double d = ray_to_object(w, object, Eigen::Vector3d(p.x() + dx, p.y() + dy, top + 0.05), -kUp, 1.0);
      if (d < 0) return false;
      lowest = std::min(lowest, d);
      highest = std::max(highest, d);
    }
    return highest - lowest < kFlatTolerance;
  };
  Eigen::Vector3d best = centre;
  double best_clearance = -1;
  for (int i = -2; i <= 2; ++i) {
    for (int j = -2; j <= 2; ++j) {
      const Eigen::Vector3d p = centre + along * (fa * i / 2.0) + across * (fc * j / 2.0);
      if (!flat(p)) continue;
      double clearance = 1e9;
      for (size_t o = 0; o < objects.size(); ++o) {
        if (objects[o].fixed || static_cast<int>(o) == w.carried_object() || static_cast<int>(o) == object) continue;
        const Eigen::Vector3d c = object_aabb(w, static_cast<int>(o)).center();
        if (c.z() < top - 0.4 || c.z() > top + 0.4) continue;
        clearance = std::min(clearance, (c - p).head<2>().norm());
      }
      // Ties (nothing near): a spot at one side, centred along, so the next
      // object fits beside this one.
      clearance = std::min(clearance, 1.0) + 1e-3 * (std::abs(j) - std::abs(i));
      if (clearance > best_clearance + 1e-9) best = p, best_clearance = clearance;
    }
  }
  best.z() = top;
  return best;
}

// Where the dirt on an object lies (world frame).
std::vector<Eigen::Vector3d> dirt_particles(const World& w, int object) {
  std::vector<Eigen::Vector3d> particles;
  const ObjectStates& states = w.states();
  if (!states.tracked(object)) return particles;
  const Frame frame = object_frame(w, object);
  for (const auto& [name, local] : states.state(object).dirt) {
    for (const Eigen::Vector3d& p : local) particles.push_back(frame.to_world(p));
  }
  return particles;
}

// Where to wipe, densest dirt first: particles ordered by how many lie
// within kPatchRadius of them (the strokes sweep about that far), each kept
// unless within kPatchSpacing of one kept before; then the particles passed
// over, so that a last reachable one beside an unreachable patch is still
// aimed at. Particles themselves, not the means of their neighbourhoods: a
// mean can lie beyond reach where every particle does not. The top centre
// when clean.
std::vector<Eigen::Vector3d> dirt_patches(const World& w, int object) {
  constexpr double kPatchRadius = 0.25, kPatchSpacing = 0.15;
  const std::vector<Eigen::Vector3d> particles = dirt_particles(w, object);
  if (particles.empty()) return {top_centre(w, object)};
  std::vector<std::pair<int, size_t>> density;  // (-neighbours, particle): sorted densest first
  for (size_t i = 0; i < particles.size(); ++i) {
    int n = 0;
    for (const Eigen::Vector3d& q : particles) n += (q - particles[i]).head<2>().norm() < kPatchRadius;
    density.push_back({-n, i});
  }
  std::sort(density.begin(), density.end());
  std::vector<Eigen::Vector3d> patches, passed;
  for (const auto& [count, i] : density) {
    const bool near_kept = std::any_of(patches.begin(), patches.end(), [&](const Eigen::Vector3d& kept) {
      return (kept - particles[i]).head<2>().norm() < kPatchSpacing;
    });
    (near_kept ? passed : patches).push_back(particles[i]);
  }
  patches.insert(patches.end(), passed.begin(), passed.end());
  return patches;
}

// Where the hand may act, in order of preference. Picks come from above, or
// for slim upright objects (a bottle on a high counter, out of reach from
// above) from the side, the fingers closing horizontally.
std::vector<Approach> approaches(const World& w, PrimitiveType type, int object, const Pose2& base) {
  if (type == PrimitiveType::push) {
    if (const auto a = articulation(w, object)) return {{a->handle, -a->axis, kUp}};
  }
  if (type == PrimitiveType::wipe) {
    std::vector<Approach> out;
    for (const Eigen::Vector3d& patch : dirt_patches(w, object)) out.push_back({patch, kDown, std::nullopt});
    return out;
  }
  std::vector<Approach> out = {{top_centre(w, object), kDown, std::nullopt}};
  if (type == PrimitiveType::pick) {
    const Aabb box = object_aabb(w, object);
    const Eigen::Vector3d size = box.hi - box.lo;
    Eigen::Vector3d towards(box.center().x() - base.x, box.center().y() - base.y, 0);
    if (std::max(size.x(), size.y()) <= kSlim && size.z() >= kSlim && towards.norm() > 1e-6) {
      towards.normalize();
      const Eigen::Vector3d point(box.center().x(), box.center().y(), box.lo.z() + 0.6 * size.z());
      out.push_back({point - towards * std::max(size.x(), size.y()) / 2, towards, kUp.cross(towards)});
    }
  }
  return out;
}

// How far a held object hangs below the hand's centre (0 with an empty hand).
double load_below_hand(const World& w) {
  const int held = w.carried_object();
  if (held < 0) return 0;
  const double hand = w.data()->site_xpos[3 * w.robot()->gripper_site + 2];
  return std::max(0.0, hand - object_aabb(w, held).lo.z());
}

// The hand's pre-pose: kClearance before the approach point, fingertips (or
// a load hanging `load` below the hand) first.
IkTarget pre_pose(const Approach& a, double load) {
  const double standoff = kClearance + (a.direction.z() < -0.5 ? std::max(kFingerReach, load) : kFingerReach);
  return {a.point - a.direction * standoff, a.direction, a.closing};
}

bool holding_free_object(const World& w) {
  return w.carried_object() >= 0;
}

// How far past the approach point the fingertips may need to go: kContactDepth,
// or half way through a thinner object (a rag in a drawer: not into the drawer).
double contact_depth(const World& w, int object, const Approach& a) {
  const Aabb box = object_aabb(w, object);
  return std::min(kContactDepth, std::abs(a.direction.dot(box.hi - box.lo)) / 2);
}

// Where the hand's centre ends the line along an approach from a base at
// `base`: at contact, fingertips contact_depth() into the object; for dip,
// where the held object's bottom is kSoakDepth under the liquid's surface;
// for wipe, at contact where the strokes begin, their farthest row.
Eigen::Vector3d line_end(const World& w, PrimitiveType type, int object, const Approach& a, const Pose2& base,
                         double load) {
  if (type == PrimitiveType::dip) {
    const Aabb box = object_aabb(w, object);
    const double surface = box.lo.z() + w.states().state(object).liquid_level * (box.hi.z() - box.lo.z());
    return {a.point.x(), a.point.y(), surface - kSoakDepth + load};
  }
  const Eigen::Vector3d contact = a.point + a.direction * (contact_depth(w, object, a) - kFingerReach);
  if (type == PrimitiveType::wipe)
    return contact + Eigen::Vector3d(std::cos(base.yaw), std::sin(base.yaw), 0) * kFarRow;
  return contact;
}

bool descends(PrimitiveType type) {
  return type != PrimitiveType::place && type != PrimitiveType::navigate;
}

// A collision-free IK solution for the pre-pose of the first approach that
// works with the base at `base` (from the untucked arm), from which, when the
// primitive descends, the hand can follow the approach to its line_end()
// touching nothing but the object itself (a neighbour in the way would stop it).
struct Reach {
  ArmConfiguration joints;
  Approach approach;
};
std::optional<Reach> reach(IkSolver& ik, ArmCollisionChecker& checker, const World& w, int object,
                           const std::vector<Approach>& candidates, const Pose2& base, PrimitiveType type,
                           double load) {
  for (const Approach& a : candidates) {
    if (std::hypot(a.point.x() - base.x, a.point.y() - base.y) > kArmReachBound) continue;
    IkOptions options;
    options.base = base;
    options.start = kUntuckedConfiguration;
    options.iterations = 100;
    const IkTarget pre = pre_pose(a, load);
    const IkResult r = ik.solve(pre, options);
    if (!r.success || checker.collides(r.joints.data(), &base)) continue;
    bool clear = true;
    if (descends(type)) {
      options.start = r.joints;
      // As Motion::line follows it: the approach axis held, the roll free.
      IkTarget along{pre.position, pre.approach, std::nullopt};
      const Eigen::Vector3d end = line_end(w, type, object, a, base, load);
      const int steps = std::max(1, static_cast<int>(std::ceil((end - pre.position).norm() / kCorridorStep)));
      for (int i = 1; i <= steps && clear; ++i) {
        along.position = pre.position + (end - pre.position) * (static_cast<double>(i) / steps);
        const IkResult c = ik.solve(along, options);
        clear = c.success && !checker.hand_touches(c.joints, &base, object);
        options.start = c.joints;
      }
    }
    if (clear) return Reach{r.joints, a};
  }
  return std::nullopt;
}

// Navigation aims at what will be done there: an articulated object's handle
// (to push it) while the hand is empty; while holding, dirt lying on it to
// wipe, a liquid to dip into, or a place to put the load.
PrimitiveType purpose_of_navigation(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  if (w.grasped_object() < 0 && articulation(w, object) && !is_open(w, object)) return PrimitiveType::push;
  if (w.grasped_object() >= 0 && ab && ab->covered && !dirt_particles(w, object).empty()) return PrimitiveType::wipe;
  if (w.grasped_object() >= 0 && primitive_applies(w, PrimitiveType::dip, object)) return PrimitiveType::dip;
  return w.grasped_object() >= 0 ? PrimitiveType::place : PrimitiveType::pick;
}

bool reachable_here(const World& w, IkSolver& ik, ArmCollisionChecker& checker, int object) {
  const PrimitiveType purpose = purpose_of_navigation(w, object);
  const std::vector<Approach> a = approaches(w, purpose, object, w.base_pose());
  const Scene& scene = w.scene();
  return scene.room_at(w.base_pose().x, w.base_pose().y) == scene.room_at(a[0].point.x(), a[0].point.y()) &&
         reach(ik, checker, w, object, a, w.base_pose(), purpose, load_below_hand(w)).has_value();
}

// Whether the base standing at p can back away along the drawer's axis as
// far as push will pull it.
bool room_to_pull(const Footprint& footprint, const Pose2& p, const Articulation& a) {
  const double pull = (a.high - a.low) * kPullFraction - (a.value - a.low);
  for (double d = 0; d <= pull; d += OccupancyMap::kResolution) {
    if (!footprint.body_map().free(p.x + a.axis.x() * d, p.y + a.axis.y() * d)) return false;
  }
  return true;
}

// OmniGibson's base-pose sampler: candidate poses near the object, kept when
// in the same room, collision-free and within reach (IK). Draws in collision
// cost a map lookup, so they do not count against the budget of `samples`
// free candidates (up to kDrawsPerSample times as many draws): an object in a
// pocket between furniture is still found. Draws go round the points of
// `around` (the target's approaches); a pose is within reach when reach()
// finds one of `targets(pose)` with `load` hanging below the hand. `use`
// gets each pose kept and ends the
// search by returning true, which is then returned.
struct BasePoseTally {
  int blocked = 0, elsewhere = 0, unreachable = 0;
};
bool sample_base_poses(const World& w, IkSolver& ik, ArmCollisionChecker& checker, const Footprint& footprint,
                       PrimitiveType purpose, int object, const std::vector<Approach>& around,
                       const std::function<std::vector<Approach>(const Pose2&)>& targets, uint64_t seed, double load,
                       int samples, BasePoseTally& tally, const std::function<bool(const Pose2&)>& use) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Aabb box = object_aabb(w, object);
  const auto articulated = purpose == PrimitiveType::push ? articulation(w, object) : std::nullopt;
  const Room* room = w.scene().room_at(around[0].point.x(), around[0].point.y());
  const ArmConfiguration& travel = w.carried_object() >= 0 ? kCarryConfiguration : kTuckedConfiguration;
  for (int i = 0; i < kDrawsPerSample * samples && i - tally.blocked < samples; ++i) {
    const Approach& a = around[i % around.size()];
    Pose2 p;
    if (articulated) {
      // In front of the drawer, facing it, far enough to pull it open.
      const Eigen::Vector3d side = kUp.cross(articulated->axis);
      const Eigen::Vector3d at =
          a.point + articulated->axis * (0.5 + 0.4 * unit(rng)) + side * (0.7 * unit(rng) - 0.35);
      p = {at.x(), at.y(), std::atan2(-articulated->axis.y(), -articulated->axis.x()) + 0.8 * unit(rng) - 0.4};
    } else {
      // Anywhere around the target, facing it, or side-on (the arm reaches sideways too).
      const double theta = 2 * M_PI * unit(rng), c = std::cos(theta), s = std::sin(theta);
      // Leave the object's box along (c, s) from the target point, then stand off.
      double exit = 1e9;
      for (const auto& [d, from, lo, hi] :
           {std::tuple{c, a.point.x(), box.lo.x(), box.hi.x()}, std::tuple{s, a.point.y(), box.lo.y(), box.hi.y()}}) {
        if (std::abs(d) > 1e-9) exit = std::min(exit, std::max(0.0, ((d > 0 ? hi : lo) - from) / d));
      }
      // Within the arm's reach of the point (0.6 m at the floor, 1 m at
      // table height) and clear of the object's box by the body's radius.
      const double near = exit + 0.25, far = std::max(near + 0.05, a.point.z() < 0.45 ? 0.62 : 1.0);
      // Biased towards the object: at arm's length, tracking is fragile.
      const double u = unit(rng), distance = near + (far - near) * u * u;
      p = {a.point.x() + c * distance, a.point.y() + s * distance, 0};
      // Wipe strokes run across the robot's front: it faces the dirt.
      const double spread = purpose == PrimitiveType::wipe ? kWipeYawSpread : M_PI;
      p.yaw = std::atan2(-s, -c) + spread * (unit(rng) - 0.5);
    }
    // The arm arrives as it drives (tucked, or carrying): where that pose
    // already touches a wall, the footprint's disks missed the elbow, and the
    // arm has no room to swing to its work (a dip beside the wall).
    if (!footprint.free(p) || (articulated && !room_to_pull(footprint, p, *articulated)) ||
        checker.collides(travel.data(), &p)) {
      ++tally.blocked;
    } else if (w.scene().room_at(p.x, p.y) != room) {
      ++tally.elsewhere;
    } else if (!reach(ik, checker, w, object, targets(p), p, purpose, load)) {
      ++tally.unreachable;
    } else if (use(p)) {
      return true;
    }
  }
  return false;
}

class Executor {
 public:
  Executor(World& w, PrimitiveType type, int object, uint64_t seed, const PrimitiveOptions& options)
      : w_(w), type_(type), object_(object), options_(options), motion_(w, options, seed, object, result_) {
    result_.mode = options.mode;
  }

  PrimitiveResult run() {
    // navigate checks its precondition itself, after tucking, with its own IK solver.
    const std::string unmet = type_ == PrimitiveType::navigate ? "" : unmet_precondition(w_, type_, object_);
    const bool ok = unmet.empty() ? act() : fail(PrimitiveStatus::precondition_failure, unmet);
    // A failed manipulation still ends tucked where it can, so the robot can drive on.
    if (!ok && !result_.diverged && type_ != PrimitiveType::navigate) {
      const PrimitiveResult failed = result_;
      motion_.tuck();
      const double planning = result_.planning_seconds, execution = result_.execution_seconds;
      const int64_t steps = result_.physics_steps;
      result_ = failed;
      result_.planning_seconds = planning;
      result_.execution_seconds = execution;
      result_.physics_steps = steps;
    }
    if (!motion_.physical()) motion_.look_at_object();  // physical motions turned the head as they went
    return result_;
  }

 private:
  bool act() {
    switch (type_) {
      case PrimitiveType::navigate:
        return navigate();
      case PrimitiveType::pick:
        return pick();
      case PrimitiveType::place:
        return place();
      case PrimitiveType::push:
        return push();
      case PrimitiveType::dip:
        return dip();
      case PrimitiveType::wipe:
        return wipe();
    }
    return false;
  }
  const std::string& name() const { return w_.scene().objects()[object_].name; }
  bool at(const ArmConfiguration& q) const {
    const ArmConfiguration now = arm_configuration(w_);
    for (size_t k = 0; k < q.size(); ++k) {
      if (std::abs(now[k] - q[k]) > 0.05) return false;
    }
    return true;
  }
  bool fail(PrimitiveStatus s, const std::string& why) { return motion_.fail(s, why); }

  // The hand's pre-pose for this primitive, solved from where the base stands.
  bool reach_pre_pose(ArmConfiguration& q) {
    const Clock::time_point t = Clock::now();
    ArmCollisionChecker checker(w_);
    const auto solution = reach(motion_.ik(), checker, w_, object_, approaches(w_, type_, object_, w_.base_pose()),
                                w_.base_pose(), type_, load_below_hand(w_));
    result_.planning_seconds += since(t);
    if (!solution) return fail(PrimitiveStatus::motion_planning_failure, "'" + name() + "' is out of reach from here");
    q = solution->joints;
    approach_ = solution->approach;
    return true;
  }

  // The end of a manipulation: tucked (or carrying) where the arm fits. Where
  // furniture blocks that pose the effect still holds and the arm stays as it
  // is: navigate tucks before driving, or drives with the arm as it is.
  bool tuck_where_possible() {
    if (motion_.tuck()) return true;
    if (result_.diverged) return false;
    result_.status = PrimitiveStatus::success;
    result_.reason.clear();
    return true;
  }

  // Untuck, then a collision-free path to the pre-pose.
  bool go_to_pre_pose() {
    ArmConfiguration q;
    if (!reach_pre_pose(q)) return false;
    // Untucked first, as the seed's primitives start, unless furniture is in the way.
    if (w_.grasped_object() < 0 && !arm_in_collision(w_, kUntuckedConfiguration) &&
        !motion_.arm_to(kUntuckedConfiguration)) {
      return false;
    }
    return motion_.arm_to(q);
  }

  // The pre-pose, then the load (which hangs off-centre from the hand) moved
  // over the spot it is aimed at.
  bool go_to_pre_pose_with_load() {
    if (!go_to_pre_pose()) return false;
    const Eigen::Vector3d spot = approach_.point;
    Eigen::Vector3d shift = spot - object_aabb(w_, w_.carried_object()).center();
    shift.z() = 0;
    motion_.line(shift, false, kRetreatSpeed, 0.0);
    return true;
  }

  bool navigate() {
    // Tucked (or carrying) if it can be; where furniture is in the way the
    // footprint measures the arm as it is.
    if (!at(w_.carried_object() >= 0 ? kCarryConfiguration : kTuckedConfiguration) && !tuck_where_possible()) {
      return false;
    }
    const Clock::time_point t = Clock::now();
    const PrimitiveType purpose = purpose_of_navigation(w_, object_);
    const std::vector<Approach> here = approaches(w_, purpose, object_, w_.base_pose());
    ArmCollisionChecker checker(w_);
    if (reachable_here(w_, motion_.ik(), checker, object_)) {
      result_.planning_seconds += since(t);
      return fail(PrimitiveStatus::precondition_failure, "already within reach of '" + name() + "'");
    }
    const Footprint footprint(w_);
    const auto targets = [&](const Pose2& p) { return approaches(w_, purpose, object_, p); };
    BasePoseTally tally;
    int path_failures = 0;
    bool arrived = false;
    Clock::time_point planning = t;
    sample_base_poses(w_, motion_.ik(), checker, footprint, purpose, object_, here, targets, motion_.next_seed(),
                      load_below_hand(w_), options_.base_pose_samples, tally, [&](const Pose2& p) {
                        // Reachable with the arm; now the base must get there.
                        result_.planning_seconds += since(planning);
                        arrived = motion_.base_to(p, footprint);
                        planning = Clock::now();
                        if (arrived || result_.diverged || ++path_failures == 3) return true;
                        result_.status = PrimitiveStatus::success;  // try the next candidate
                        result_.reason.clear();
                        return false;
                      });
    result_.planning_seconds += since(planning);
    if (arrived || result_.diverged || path_failures == 3) return arrived;
    return fail(PrimitiveStatus::motion_planning_failure,
                "no collision-free base pose within reach of '" + name() + "' in its room (" +
                    std::to_string(tally.blocked) + " samples in collision, then of " +
                    std::to_string(tally.elsewhere + tally.unreachable + path_failures) + " free ones: " +
                    std::to_string(tally.elsewhere) + " in another room, " + std::to_string(tally.unreachable) +
                    " out of the arm's reach, " + std::to_string(path_failures) + " without a path)");
  }

  bool pick() {
    if (!go_to_pre_pose()) return false;
    // Towards the object until contact: through its height from above, its width from the side.
    const Aabb box = object_aabb(w_, object_);
    // Within a waypoint (1 cm) of the contact point reach() checked, the line
    // may end without a touch: a slim object taken from the side sits between
    // the open fingers.
    const double extent = std::abs(approach_.direction.dot(box.hi - box.lo));
    const double length = kClearance + extent + 0.02;
    const double needed = kClearance + contact_depth(w_, object_, approach_) - 0.01;
    if (!motion_.line(approach_.direction * length, true, kApproachSpeed, needed / length)) return false;
    motion_.gripper(false);
    if (!motion_.physical()) {
      // The assistive grasp's condition, kinematically: the object between the fingers.
      const Eigen::Vector3d hand = motion_.hand_position();
      const Eigen::Vector3d nearest = hand.cwiseMax(box.lo).cwiseMin(box.hi);
      if ((nearest - hand).norm() < 0.05 && !w_.hold(object_)) result_.grasp_refused = true;
    }
    if (w_.grasped_object() != object_) {
      motion_.gripper(true);
      motion_.line(kUp * kLift, false, kRetreatSpeed, 0.0);
      return fail(PrimitiveStatus::grasp_failure,
                  result_.grasp_refused ? "'" + name() + "' is too heavy to hold" : "the hand closed on nothing");
    }
    motion_.line(kUp * kLift, false, kRetreatSpeed, 0.0);  // lift as far as the arm goes; tuck plans the rest
    if (!tuck_where_possible()) return false;
    if (w_.grasped_object() != object_) return fail(PrimitiveStatus::grasp_failure, "'" + name() + "' slipped out");
    return true;
  }

  bool place() {
    const int held = w_.grasped_object();
    if (!go_to_pre_pose_with_load()) return false;
    motion_.gripper(true);
    if (!motion_.physical()) settle_kinematically(held);
    motion_.wait(0.3);
    motion_.line(kUp * kLift, false, kRetreatSpeed, 0.0);
    if (!tuck_where_possible()) return false;
    if (!inside(w_, held, object_) && !ontop(w_, held, object_)) {
      return fail(PrimitiveStatus::place_failure,
                  "'" + w_.scene().objects()[held].name + "' is neither on nor in '" + name() + "'");
    }
    return true;
  }

  // Symbolic release: the object drops straight down onto what is below it.
  void settle_kinematically(int held) {
    const Clock::time_point t = Clock::now();
    const SceneObject& o = w_.scene().objects()[held];
    const Aabb box = object_aabb(w_, held);
    std::vector<int> others;
    const mjModel* m = w_.model();
    for (int g = 0; g < m->ngeom; ++g) {
      const int root = m->body_rootid[m->geom_bodyid[g]];
      if ((m->geom_contype[g] || m->geom_conaffinity[g]) && root != o.body &&
          root != m->body_rootid[w_.robot()->gripper_body]) {
        others.push_back(g);
      }
    }
    double drop = 1e9;
    const Eigen::Vector3d c = box.center();
    const double hx = (box.hi.x() - box.lo.x()) / 2 * 0.8, hy = (box.hi.y() - box.lo.y()) / 2 * 0.8;
    for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, {hx, hy}, {-hx, hy}, {hx, -hy}, {-hx, -hy}}) {
      const double hit = ray_to_geoms(w_, others, Eigen::Vector3d(c.x() + dx, c.y() + dy, box.lo.z()), kDown, 5.0);
      if (hit >= 0) drop = std::min(drop, hit);
    }
    if (drop < 1e9) {
      const int adr = m->jnt_qposadr[m->body_jntadr[o.body]];
      w_.data()->qpos[adr + 2] -= std::max(0.0, drop - 0.001);
      mj_forward(m, w_.data());
    }
    result_.execution_seconds += since(t);
  }

  bool push() {
    const auto a = articulation(w_, object_);  // there is one: the precondition held
    if (!go_to_pre_pose()) return false;
    // To the handle until the fingertips touch the front, close on the handle, pull.
    if (!motion_.line(-a->axis * (kClearance + 0.06), true, kApproachSpeed)) return false;
    if (!motion_.touched()) return fail(PrimitiveStatus::motion_planning_failure, "the hand did not reach the handle");
    motion_.gripper(false);
    if (motion_.physical() && w_.grasped_body() != a->link) {
      motion_.gripper(true);
      return fail(PrimitiveStatus::grasp_failure, "the hand missed the handle of '" + name() + "'");
    }
    // Pull most of the way open by backing the base away, the arm held.
    const double pull = (a->high - a->low) * kPullFraction - (a->value - a->low);
    const Eigen::Vector3d before = motion_.hand_position();
    if (!motion_.base_line(a->axis * pull)) return false;
    if (!motion_.physical()) {
      // The drawer follows the hand kinematically.
      const double moved = a->axis.dot(motion_.hand_position() - before);
      w_.data()->qpos[w_.model()->jnt_qposadr[a->joint]] = std::clamp(a->value + moved, a->low, a->high);
      mj_forward(w_.model(), w_.data());
    }
    motion_.gripper(true);
    motion_.line(a->axis * 0.08, false, kRetreatSpeed, 0.0);  // back off as far as the arm goes
    if (!tuck_where_possible()) return false;
    if (!is_open(w_, object_))
      return fail(PrimitiveStatus::grasp_failure, "the handle slipped: '" + name() + "' stays closed");
    return true;
  }

  bool dip() {
    if (!go_to_pre_pose_with_load()) return false;
    // Down until the held object's bottom is under the liquid's surface.
    const double end = line_end(w_, type_, object_, approach_, w_.base_pose(), load_below_hand(w_)).z();
    const Eigen::Vector3d down = kDown * std::max(0.0, motion_.hand_position().z() - end);
    // Not stopping at contact: a rag's corners brush the rim on the way in.
    if (!motion_.line(down, false, kApproachSpeed)) return false;
    motion_.wait(0.6);  // long enough to soak through (ObjectStates: 0.5 s)
    motion_.line(-down, false, kRetreatSpeed, 0.0);
    if (!tuck_where_possible()) return false;
    const int held = w_.grasped_object();
    if (held < 0) return fail(PrimitiveStatus::grasp_failure, "dropped what it held");
    const ObjectAbilities* ab = w_.states().abilities(held);
    if (ab && ab->soakable) {
      const auto& soaked = w_.states().state(held).soaked;
      const std::string& liquid = w_.states().state(object_).liquid;
      if (!soaked.count(liquid) || soaked.at(liquid) < ObjectStates::kSoakedLevel) {
        return fail(PrimitiveStatus::motion_planning_failure, "the held object did not reach the liquid");
      }
    }
    return true;
  }

  bool wipe() {
    if (!go_to_pre_pose()) return false;
    if (!motion_.line(kDown * (kClearance + 0.06), true, kApproachSpeed)) return false;
    if (!motion_.touched()) return fail(PrimitiveStatus::motion_planning_failure, "the tool did not reach the surface");
    // Strokes left-right, row by row towards the robot, pressing 1 cm in.
    const double yaw = w_.base_pose().yaw;
    const Eigen::Vector3d forward(std::cos(yaw), std::sin(yaw), 0), left(-std::sin(yaw), std::cos(yaw), 0);
    constexpr double kHalfWidth = 0.22;
    // Each stroke goes as far as the arm reaches along it.
    motion_.line(forward * kFarRow - left * kHalfWidth + kDown * 0.01, false, 0.25, 0.0);
    for (int row = 0; row < kRows; ++row) {
      const double side = row % 2 == 0 ? 1.0 : -1.0;
      motion_.line(left * (2 * kHalfWidth * side), false, 0.3, 0.0);
      if (row + 1 < kRows) motion_.line(-forward * kRowSpacing, false, 0.25, 0.0);
    }
    motion_.line(kUp * kLift, false, kRetreatSpeed, 0.0);
    if (!tuck_where_possible()) return false;
    if (w_.grasped_object() < 0) return fail(PrimitiveStatus::grasp_failure, "dropped the tool");
    return true;
  }

  World& w_;
  PrimitiveType type_;
  int object_;
  PrimitiveOptions options_;
  PrimitiveResult result_;
  Motion motion_;
  Approach approach_;  // the approach reach_pre_pose chose
};

template <size_t N>
int parse_name(const char* const (&names)[N], const std::string& name, const char* what) {
  for (size_t i = 0; i < N; ++i) {
    if (name == names[i]) return static_cast<int>(i);
  }
  std::string known;
  for (size_t i = 0; i < N; ++i) known += (i ? ", " : "") + std::string(names[i]);
  throw Error(std::string("unknown ") + what + " '" + name + "' (known: " + known + ")");
}

}  // namespace

const char* to_string(PrimitiveType type) {
  return kTypeNames[static_cast<int>(type)];
}
const char* to_string(ExecutionMode mode) {
  return kModeNames[static_cast<int>(mode)];
}
const char* to_string(PrimitiveStatus status) {
  return kStatusNames[static_cast<int>(status)];
}

PrimitiveType parse_primitive_type(const std::string& name) {
  return static_cast<PrimitiveType>(parse_name(kTypeNames, name, "primitive"));
}

ExecutionMode parse_execution_mode(const std::string& name) {
  return static_cast<ExecutionMode>(parse_name(kModeNames, name, "execution mode"));
}

bool within_reach(const World& world, int object) {
  IkSolver ik(world);
  ArmCollisionChecker checker(world);
  return reachable_here(world, ik, checker, object);
}

std::string out_of_reach(const World& w, PrimitiveType type, int object, uint64_t seed,
                         const PrimitiveOptions& options) {
  const Footprint footprint(w);
  const std::optional<Pose2> start = free_pose_near(footprint, w.base_pose());
  if (!start) return "the robot is boxed in where it stands";
  const OccupancyMap drivable = footprint.body_map().reachable_from(start->x, start->y);
  IkSolver ik(w);
  ArmCollisionChecker checker(w);
  std::vector<Pose2> kept;  // poses within reach that the base can drive to
  const auto use = [&](const Pose2& p) {
    if (!drivable.free(p.x, p.y)) return false;
    kept.push_back(p);
    return true;
  };
  const std::string name = "'" + w.scene().objects().at(object).name + "'";
  // dip and wipe act with a tool in hand, which may not be held yet.
  const bool tool = type == PrimitiveType::dip || type == PrimitiveType::wipe;
  const double load = tool ? std::max(load_below_hand(w), kToolHang) : load_below_hand(w);
  BasePoseTally tally;
  if (type != PrimitiveType::wipe) {
    const auto targets = [&](const Pose2& p) { return approaches(w, type, object, p); };
    if (sample_base_poses(w, ik, checker, footprint, type, object, targets(w.base_pose()), targets, seed, load,
                          options.base_pose_samples, tally, use)) {
      return "";
    }
    return "no base pose the robot can drive to brings " + name + " within reach to " + to_string(type) + " it";
  }
  // Dirt: enough of it within reach that wiping all of that leaves the object clean.
  int missed = 0;
  for (const Eigen::Vector3d& particle : dirt_particles(w, object)) {
    const std::vector<Approach> at = {{particle, kDown, std::nullopt}};
    const bool reached =
        std::any_of(kept.begin(), kept.end(),
                    [&](const Pose2& p) { return reach(ik, checker, w, object, at, p, type, load).has_value(); }) ||
        sample_base_poses(
            w, ik, checker, footprint, type, object, at, [&](const Pose2&) { return at; }, seed++, load,
            options.base_pose_samples, tally, use);
    if (!reached && ++missed == ObjectStates::kCoveredParticles) {
      return std::to_string(missed) + " dirt particles on " + name +
             " lie out of reach of every base pose the robot can drive to";
    }
  }
  return "";
}

ReachProblem first_out_of_reach(World& w, const std::vector<PrimitiveType>& types, const std::vector<int>& objects,
                                uint64_t seed) {
  if (types.size() != objects.size()) throw Error("first_out_of_reach: as many types as objects are needed");
  ReachProblem problem;
  const auto check = [&](size_t i) {
    problem.reason = out_of_reach(w, types[i], objects[i], seed + i);
    if (!problem.reason.empty()) problem.index = static_cast<int>(i);
    return problem.reason.empty();
  };
  for (size_t i = 0; i < types.size(); ++i) {
    if (types[i] == PrimitiveType::push && !check(i)) return problem;
  }
  // The rest with the drawers pulled open as push leaves them.
  std::vector<std::pair<int, double>> saved;  // qpos address, value
  for (size_t i = 0; i < types.size(); ++i) {
    const auto a = types[i] == PrimitiveType::push ? articulation(w, objects[i]) : std::nullopt;
    if (!a) continue;
    const int adr = w.model()->jnt_qposadr[a->joint];
    saved.push_back({adr, w.data()->qpos[adr]});
    w.data()->qpos[adr] = a->low + (a->high - a->low) * kPullFraction;
  }
  if (!saved.empty()) mj_forward(w.model(), w.data());
  for (size_t i = 0; i < types.size(); ++i) {
    if (types[i] != PrimitiveType::push && !check(i)) break;
  }
  for (const auto& [adr, value] : saved) w.data()->qpos[adr] = value;
  if (!saved.empty()) mj_forward(w.model(), w.data());
  return problem;
}

std::string unmet_precondition(const World& w, PrimitiveType type, int object) {
  const std::string name = "'" + w.scene().objects().at(object).name + "'";
  const bool holding = holding_free_object(w);
  switch (type) {
    case PrimitiveType::navigate:
      return within_reach(w, object) ? "already within reach of " + name : "";
    case PrimitiveType::pick:
      if (w.grasped_object() >= 0) return "the hand is not empty";
      // Fixed objects cannot be picked; a heavy one is refused by the grasp itself.
      return w.scene().objects()[object].fixed ? name + " cannot be picked up" : "";
    case PrimitiveType::place:
      if (!holding) return "the hand holds nothing";
      return w.grasped_object() == object ? "cannot place an object on itself" : "";
    case PrimitiveType::push: {
      if (w.grasped_object() >= 0) return "the hand is not empty";
      const auto a = articulation(w, object);
      if (!a) return name + " has no drawer to open";
      return open_fraction(*a) > 0.9 ? name + " is already open" : "";
    }
    case PrimitiveType::dip:
    case PrimitiveType::wipe:  // a tool in hand, and a target of the right kind
      if (!holding) return "the hand holds nothing";
      if (primitive_applies(w, type, object)) return "";
      return name + (type == PrimitiveType::dip ? " holds no liquid" : " has nothing to wipe");
  }
  return "";
}

bool primitive_applies(const World& w, PrimitiveType type, int object) {
  const SceneObject& o = w.scene().objects().at(object);
  const ObjectAbilities* ab = w.states().abilities(object);
  switch (type) {
    case PrimitiveType::pick:
      return !o.fixed && o.grasp_weld >= 0 && w.model()->body_subtreemass[o.body] <= World::kGraspMassLimit;
    case PrimitiveType::push:
      return articulation(w, object).has_value();
    case PrimitiveType::dip:
      return ab && ab->holds_liquid;
    case PrimitiveType::wipe:
      return ab && ab->covered;
    case PrimitiveType::navigate:
    case PrimitiveType::place:
      return true;
  }
  return false;
}

PrimitiveResult execute_primitive(World& world, PrimitiveType type, int object, uint64_t seed,
                                  const PrimitiveOptions& options) {
  if (!world.robot()) throw Error("primitives: the scene has no robot");
  if (object < 0 || object >= static_cast<int>(world.scene().objects().size())) {
    throw Error("primitives: no object " + std::to_string(object) + " in scene '" + world.scene().name() + "'");
  }
  return Executor(world, type, object, seed, options).run();
}

}  // namespace chore
