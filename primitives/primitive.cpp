#include "primitives/primitive.hpp"

#include <mujoco/mujoco.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <random>

#include "base/error.hpp"
#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/transitions.hpp"

namespace chore {
namespace {

constexpr double kToolHang = 0.05;      // m a tool held for dip or wipe is taken to hang below the hand (a rag: 3.4 cm)
constexpr int kDrawsPerSample = 20;     // base-pose draws per free candidate, at most
constexpr double kCorridorStep = 0.02;  // m between the hand poses checked along an approach
constexpr double kFlatTolerance = 0.02;  // m: a place spot's support heights may differ this much
// No hand pose is this far (horizontally) from the base's axis: shoulder 0.09 m
// ahead of it, arm and gripper ~1 m long. Farther targets skip the IK solve.
constexpr double kArmReachBound = 1.5;

#define CHORE_PRIMITIVE_NAME(name) #name,
const char* const kTypeNames[] = {CHORE_PRIMITIVES(CHORE_PRIMITIVE_NAME)};
#undef CHORE_PRIMITIVE_NAME
const char* const kModeNames[] = {"physical", "symbolic"};
const char* const kStatusNames[] = {"success", "motion_planning_failure", "grasp_failure", "place_failure",
                                    "precondition_failure"};

// Where the hand's centre ends the line along an approach: the primitive's
// line_end, or at contact.
Eigen::Vector3d line_end(const World& w, const PrimitiveDef& def, int object, const Approach& a, const Pose2& base,
                         double load) {
  return def.line_end ? def.line_end(w, object, a, base, load) : contact_point(w, object, a);
}

// An object transitions have not made yet, or have used up.
std::string not_real(const World& w, int object) {
  return "'" + w.scene().objects()[object].name + "' does not exist (not made yet, or used up)";
}

void check_object(const World& w, int object) {
  if (object < 0 || object >= static_cast<int>(w.scene().objects().size())) {
    throw Error("primitives: no object " + std::to_string(object) + " in scene '" + w.scene().name() + "'");
  }
}

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

const PrimitiveDef& primitive_def(PrimitiveType type) {
#define CHORE_PRIMITIVE_DEF(name) &name##_primitive(),
  static const PrimitiveDef* const defs[] = {CHORE_PRIMITIVES(CHORE_PRIMITIVE_DEF)};
#undef CHORE_PRIMITIVE_DEF
  return *defs[static_cast<int>(type)];
}

namespace {

constexpr double kHandleInset = 0.05;  // m from a door's free edge to where the hand takes hold

// The corners of a geom's box (its own frame's box for boxes, else its
// world box's).
std::vector<Eigen::Vector3d> geom_corners(const World& w, int g) {
  const mjModel* m = w.model();
  const mjData* d = w.data();
  std::vector<Eigen::Vector3d> out;
  if (m->geom_type[g] == mjGEOM_BOX) {
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(d->geom_xmat + 9 * g);
    const Eigen::Vector3d c(d->geom_xpos[3 * g], d->geom_xpos[3 * g + 1], d->geom_xpos[3 * g + 2]);
    for (int k = 0; k < 8; ++k) {
      const Eigen::Vector3d s((k & 1 ? 1 : -1) * m->geom_size[3 * g], (k & 2 ? 1 : -1) * m->geom_size[3 * g + 1],
                              (k & 4 ? 1 : -1) * m->geom_size[3 * g + 2]);
      out.push_back(c + r * s);
    }
    return out;
  }
  const Aabb box = geom_aabb(w, g);
  for (int k = 0; k < 8; ++k) {
    out.emplace_back(k & 1 ? box.hi.x() : box.lo.x(), k & 2 ? box.hi.y() : box.lo.y(), k & 4 ? box.hi.z() : box.lo.z());
  }
  return out;
}

// A hinge's handle: on the face the free edge turns towards, kHandleInset in
// from that edge, half way along the hinge (over the link's geoms).
void hinge_handle(const World& w, Articulation& a) {
  std::vector<Eigen::Vector3d> corners;
  for (int g = 0; g < w.model()->ngeom; ++g) {
    if (w.model()->geom_bodyid[g] != a.link) continue;
    const std::vector<Eigen::Vector3d> c = geom_corners(w, g);
    corners.insert(corners.end(), c.begin(), c.end());
  }
  // Radially outwards from the axis to the furthest corner.
  Eigen::Vector3d outwards = Eigen::Vector3d::Zero();
  double along_lo = 1e9, along_hi = -1e9;
  for (const Eigen::Vector3d& c : corners) {
    const Eigen::Vector3d r = c - a.pivot, radial = r - a.axis * a.axis.dot(r);
    if (radial.norm() > outwards.norm()) outwards = radial;
    along_lo = std::min(along_lo, a.axis.dot(r));
    along_hi = std::max(along_hi, a.axis.dot(r));
  }
  const double radius = outwards.norm();
  const Eigen::Vector3d u = radius > 1e-9 ? Eigen::Vector3d(outwards / radius) : Eigen::Vector3d::UnitX();
  a.pull = a.axis.cross(u);
  double face = -1e9;
  for (const Eigen::Vector3d& c : corners) face = std::max(face, a.pull.dot(c - a.pivot));
  a.handle = a.pivot + a.axis * (along_lo + along_hi) / 2 + u * std::max(0.0, radius - kHandleInset) + a.pull * face;
}

}  // namespace

std::optional<Articulation> articulation(const World& w, int object) {
  const SceneObject& o = w.scene().objects()[object];
  const mjModel* m = w.model();
  const mjData* d = w.data();
  for (int joint : o.joints) {
    if (m->jnt_type[joint] != mjJNT_SLIDE && m->jnt_type[joint] != mjJNT_HINGE) continue;
    Articulation a;
    a.joint = joint;
    a.link = m->jnt_bodyid[joint];
    a.hinge = m->jnt_type[joint] == mjJNT_HINGE;
    const Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> r(d->xmat + 9 * a.link);
    a.axis = r * Eigen::Vector3d(m->jnt_axis[3 * joint], m->jnt_axis[3 * joint + 1], m->jnt_axis[3 * joint + 2]);
    a.pivot = Eigen::Vector3d(d->xanchor[3 * joint], d->xanchor[3 * joint + 1], d->xanchor[3 * joint + 2]);
    a.low = m->jnt_range[2 * joint];
    a.high = m->jnt_range[2 * joint + 1];
    a.value = d->qpos[m->jnt_qposadr[joint]];
    if (a.hinge) {
      hinge_handle(w, a);
      return a;
    }
    a.pull = a.axis;
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

void set_articulation(World& w, const Articulation& a, double value) {
  const mjModel* m = w.model();
  mjData* d = w.data();
  const double to = std::clamp(value, a.low, a.high);
  if (!a.hinge) {
    // What lies in the drawer: free objects whose boxes are centred in the link's.
    Aabb link;
    for (int g = 0; g < m->ngeom; ++g) {
      if (m->geom_bodyid[g] == a.link) link.grow(geom_aabb(w, g));
    }
    const Eigen::Vector3d shift = a.axis * (to - d->qpos[m->jnt_qposadr[a.joint]]);
    const auto& objects = w.scene().objects();
    for (int o = 0; o < static_cast<int>(objects.size()); ++o) {
      const int body = objects[o].body;
      if (objects[o].fixed || body < 0 || !w.real(o) || o == w.grasped_object()) continue;
      if (m->body_jntnum[body] < 1 || m->jnt_type[m->body_jntadr[body]] != mjJNT_FREE) continue;
      const Aabb box = object_aabb(w, o);
      const Eigen::Vector3d centre = (box.lo + box.hi) / 2;
      if ((centre.array() < link.lo.array()).any() || (centre.array() > link.hi.array()).any()) continue;
      double* qpos = d->qpos + m->jnt_qposadr[m->body_jntadr[body]];
      for (int k = 0; k < 3; ++k) qpos[k] += shift[k];
    }
  }
  d->qpos[m->jnt_qposadr[a.joint]] = to;
  mj_forward(m, d);
}

// Where a place or dip aims: over an open drawer's exposed part, else over
// the object's box, at the spot farthest from the free objects already there
// (the second pumpkin goes beside the first), on top.
namespace {
// The carried load's box were the base at `base`, the arm as it is: its
// geoms turned about the base with it.
Aabb carried_aabb_at(const World& w, const Pose2& base) {
  const Pose2 now = w.base_pose();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(base.yaw - now.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d from(now.x, now.y, 0), to(base.x, base.y, 0);
  const mjData* d = w.data();
  Aabb box;
  for (int g : w.scene().objects()[w.carried_object()].geoms) {
    const Eigen::Vector3d pos = turn * (Eigen::Map<const Eigen::Vector3d>(d->geom_xpos + 3 * g) - from) + to;
    using RowMajor = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;  // MuJoCo's xmat
    const RowMajor mat = turn * Eigen::Map<const RowMajor>(d->geom_xmat + 9 * g);
    box.grow(geom_aabb(w.model(), g, pos.data(), mat.data()));
  }
  return box;
}
}  // namespace

std::vector<Eigen::Vector3d> top_spots(const World& w, int object, const Pose2& base) {
  Eigen::Vector3d centre, along, across;  // the region: centre +- along +- across
  double top = 0;
  const auto a = articulation(w, object);
  const bool drawer = a && !a->hinge && open_fraction(*a) > 0.3;
  if (drawer) {
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
  const int held = w.carried_object();
  const Aabb load = held < 0 ? Aabb{} : carried_aabb_at(w, base);
  if (held >= 0) margin += std::max(load.hi.x() - load.lo.x(), load.hi.y() - load.lo.y()) / 2;
  const double fa = std::max(0.0, 1 - margin / std::max(along.norm(), 1e-9));
  const double fc = std::max(0.0, 1 - margin / std::max(across.norm(), 1e-9));
  if (held < 0) return {{centre.x(), centre.y(), top}};  // nothing to set down
  // A spot is flat when rays down through the load's footprint all land on
  // the target at one height: not half on a bin's rim or off a table's edge.
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
  Eigen::Vector3d best = centre, nearest = centre;
  double best_clearance = -1, nearest_distance = 1e9;
  for (int i = -2; i <= 2; ++i) {
    for (int j = -2; j <= 2; ++j) {
      const Eigen::Vector3d p = centre + along * (fa * i / 2.0) + across * (fc * j / 2.0);
      if (!flat(p)) continue;
      const double distance = std::hypot(p.x() - base.x, p.y() - base.y);
      if (distance < nearest_distance - 1e-9) nearest = p, nearest_distance = distance;
      double clearance = room_among_loose(w, p, object, top - 0.4, top + 0.4);
      // Ties (nothing near): a spot at one side, centred along, so the next
      // object fits beside this one.
      clearance = std::min(clearance, 1.0) + 1e-3 * (std::abs(j) - std::abs(i));
      if (clearance > best_clearance + 1e-9) best = p, best_clearance = clearance;
    }
  }
  best.z() = nearest.z() = top;
  // (An open drawer's exposed part is all within reach of its front: its
  // nearest spot is its edge, where a load settles on the rim.)
  if (drawer || (nearest - best).norm() < 1e-9) return {best};
  return {best, nearest};
}

double room_among_loose(const World& w, const Eigen::Vector3d& p, int object, double lo, double hi) {
  const auto& objects = w.scene().objects();
  double room = 1e9;
  for (size_t o = 0; o < objects.size(); ++o) {
    if (objects[o].fixed || static_cast<int>(o) == w.carried_object() || static_cast<int>(o) == object) continue;
    const Eigen::Vector3d c = object_aabb(w, static_cast<int>(o)).center();
    if (c.z() >= lo && c.z() <= hi) room = std::min(room, (c - p).head<2>().norm());
  }
  return room;
}

Eigen::Vector3d top_centre(const World& w, int object, const Pose2& base) {
  return top_spots(w, object, base).front();
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

std::vector<Approach> approaches(const World& w, PrimitiveType type, int object, const Pose2& base) {
  const PrimitiveDef& def = primitive_def(type);
  return def.approaches ? def.approaches(w, object, base) : onto_top(w, object, base);
}

std::vector<Approach> onto_top(const World& w, int object, const Pose2& base) {
  std::vector<Approach> out;
  for (const Eigen::Vector3d& spot : top_spots(w, object, base)) {
    out.push_back({spot, kDown, std::nullopt});
    if (const auto tilted = tilted_onto(w, spot, base)) out.push_back(*tilted);
  }
  return out;
}

std::optional<Approach> tilted_onto(const World& w, const Eigen::Vector3d& spot, const Pose2& base) {
  const Eigen::Vector3d towards(spot.x() - base.x, spot.y() - base.y, 0);
  if (w.carried_object() < 0 || towards.norm() < 1e-6 || spot.z() + kClearance + load_below_hand(w) <= kHighestDown) {
    return std::nullopt;
  }
  return Approach{spot, tilted_towards(towards), std::nullopt, true};
}

// How far a held object hangs below the hand's centre (0 with an empty hand).
double load_below_hand(const World& w) {
  const int held = w.carried_object();
  if (held < 0) return 0;
  const double hand = w.data()->site_xpos[3 * w.robot()->gripper_site + 2];
  return std::max(0.0, hand - object_aabb(w, held).lo.z());
}

namespace {
// The hand's pre-pose: `clearance` before the approach point, fingertips (or
// a load hanging `load` below the hand) first.
IkTarget pre_pose(const Approach& a, double load, double clearance) {
  const double standoff = clearance + (from_above(a) ? std::max(kFingerReach, load) : kFingerReach);
  return {a.point - a.direction * standoff, a.direction, a.closing};
}

// How far from `point` along `direction` the first thing is that is neither
// `object` nor the robot (MuJoCo's ray through their geoms, one after another);
// `limit` when nothing is nearer.
double room_past(const World& w, int object, const Eigen::Vector3d& point, const Eigen::Vector3d& direction,
                 double limit) {
  const mjModel* m = w.model();
  const int robot = m->body_rootid[w.robot()->gripper_body];
  mjtByte groups[mjNGROUP] = {};
  groups[kStaticGroup] = groups[kCollisionGroup] = 1;
  constexpr int kMostSkipped = 256;  // a cloth's particles along the ray
  constexpr double kPast = 1e-6;     // m beyond a skipped geom's surface
  Eigen::Vector3d from = point;
  double travelled = 0;
  for (int i = 0; i < kMostSkipped && travelled < limit; ++i) {
    int geom = -1;
    const double hit = mj_ray(m, w.data(), from.data(), direction.data(), groups, 1, -1, &geom, nullptr);
    if (hit < 0) return limit;
    if (w.scene().object_of_geom(geom) != object && m->body_rootid[m->geom_bodyid[geom]] != robot) {
      return std::min(limit, travelled + hit);
    }
    travelled += hit + kPast;
    from += direction * (hit + kPast);
  }
  return std::min(limit, travelled);
}
}  // namespace

// How far past the approach point the fingertips may need to go: kContactDepth,
// or half way through a thinner object (a rag in a drawer: not into the
// drawer), or half way to what lies beyond the point (a cloth hanging over a
// counter's edge is as thick as it hangs in its box, not under the hand).
double contact_depth(const World& w, int object, const Approach& a) {
  const Aabb box = object_aabb(w, object);
  const double through = std::abs(a.direction.dot(box.hi - box.lo));
  return std::min({kContactDepth, through / 2, room_past(w, object, a.point, a.direction, through) / 2});
}

Eigen::Vector3d contact_point(const World& w, int object, const Approach& a) {
  return a.point + a.direction * (contact_depth(w, object, a) - kFingerReach);
}

std::optional<Reach> reach(IkSolver& ik, ArmCollisionChecker& checker, const World& w, int object,
                           const std::vector<Approach>& candidates, const Pose2& base, PrimitiveType type, double load,
                           size_t starts) {
  const PrimitiveDef& def = primitive_def(type);
  for (const Approach& a : candidates) {
    if (a.last_resort && starts < kReachStarts.size()) continue;
    if (std::hypot(a.point.x() - base.x, a.point.y() - base.y) > kArmReachBound) continue;
    const double off_facing =
        std::remainder(std::atan2(a.point.y() - base.y, a.point.x() - base.x) - base.yaw, 2 * M_PI);
    if (std::abs(off_facing) > def.yaw_spread) continue;
    const IkTarget pre = pre_pose(a, load, def.clearance);
    for (size_t k = 0; k < std::min(starts, kReachStarts.size()); ++k) {
      IkOptions options;
      options.base = base;
      options.start = kReachStarts[k];
      options.iterations = 100;
      const IkResult r = ik.solve(pre, options);
      if (!r.success || checker.collides(r.joints.data(), &base)) continue;
      bool clear = true;
      if (def.touches) {
        options.start = r.joints;
        // As Motion::line follows it: the approach axis held, the roll free.
        IkTarget along{pre.position, pre.approach, std::nullopt};
        const Eigen::Vector3d end = line_end(w, def, object, a, base, load);
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
  }
  return std::nullopt;
}

namespace {
// Whether the base standing at p can back away along the drawer's axis as
// far as push will pull it.
bool room_to_pull(const Footprint& footprint, const Pose2& p, const Articulation& a) {
  const double pull = (a.high - a.low) * kPullFraction - (a.value - a.low);
  for (double d = 0; d <= pull; d += OccupancyMap::kResolution) {
    if (!footprint.body_map().free(p.x + a.axis.x() * d, p.y + a.axis.y() * d)) return false;
  }
  return true;
}
}  // namespace

// Draws in collision cost a map lookup, so they do not count against the
// budget of `samples` free candidates (up to kDrawsPerSample times as many
// draws): an object in a pocket between furniture is still found.
bool sample_base_poses(const World& w, IkSolver& ik, ArmCollisionChecker& checker, const Footprint& footprint,
                       PrimitiveType purpose, int object, const std::vector<Approach>& around,
                       const std::function<std::vector<Approach>(const Pose2&)>& targets, uint64_t seed, double load,
                       int samples, BasePoseTally& tally, const std::function<bool(const Pose2&, size_t)>& use) {
  const Aabb box = object_aabb(w, object);
  const PrimitiveDef& def = primitive_def(purpose);
  // (A lid opens upwards: the robot may stand anywhere around it.)
  auto articulated = def.opens ? articulation(w, object) : std::nullopt;
  if (articulated && std::abs(articulated->pull.z()) > 0.7) articulated.reset();
  const Room* room = w.scene().room_at(around[0].point.x(), around[0].point.y());
  const ArmConfiguration& travel = w.carried_object() >= 0 ? kCarryConfiguration : kTuckedConfiguration;
  // Poses from which the arm reaches from the untucked start first, over the
  // whole budget: the configurations the physical primitives were tuned on
  // (from the low or high start the hand reaches farther, and closes a door
  // less surely). Then from any of kReachStarts; then from those, standing
  // clear of what the object stands on or in too (below). The tally is the
  // last pass's.
  struct Pass {
    size_t starts;
    bool clear_of_support;
  };
  for (const Pass pass : {Pass{1, false}, Pass{kReachStarts.size(), false}, Pass{kReachStarts.size(), true}}) {
    const size_t starts = pass.starts;
    tally = {};
    std::mt19937_64 rng(seed + starts - 1 + pass.clear_of_support);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (int i = 0; i < kDrawsPerSample * samples && i - tally.blocked < samples; ++i) {
      const Approach& a = around[i % around.size()];
      Pose2 p;
      if (articulated) {
        // In front of the handle, facing it, far enough to pull it open.
        const Eigen::Vector3d& pull = articulated->pull;
        const Eigen::Vector3d side = kUp.cross(pull);
        const Eigen::Vector3d at = a.point + pull * (0.5 + 0.4 * unit(rng)) + side * (0.7 * unit(rng) - 0.35);
        p = {at.x(), at.y(), std::atan2(-pull.y(), -pull.x()) + 0.8 * unit(rng) - 0.4};
      } else {
        // Anywhere around the target, facing it, or side-on (the arm reaches sideways too).
        const double theta = 2 * M_PI * unit(rng), c = std::cos(theta), s = std::sin(theta);
        // Leave the object's box along (c, s) from the target point, then
        // stand off; not what the base drives over (a floor, a rug).
        double exit = box.hi.z() < Robot::kDrivesOver ? 0 : 1e9;
        for (const auto& [d, from, lo, hi] :
             {std::tuple{c, a.point.x(), box.lo.x(), box.hi.x()}, std::tuple{s, a.point.y(), box.lo.y(), box.hi.y()}}) {
          if (std::abs(d) > 1e-9) exit = std::min(exit, std::max(0.0, ((d > 0 ? hi : lo) - from) / d));
        }
        // Clear of the object's box by the body's radius, within the arm's
        // reach of the point (0.62 m at the floor, 1 m from 0.45 m up, and
        // between: a teddy 0.23 m up in a packing box 0.8 m across is
        // reached from 0.65 m, beyond the floor's bound). In
        // the last pass clear of what it stands on or in too: from the first
        // cell along (c, s) where the base fits (a tupperware in a fridge is
        // left where the fridge ends, not where the tupperware does: 2,000
        // draws of 2,000 fell inside the fridge), none along (c, s) if that
        // cell lies beyond reach (a draw in collision).
        const double reach = 0.62 + 0.38 * std::clamp(a.point.z() / 0.45, 0.0, 1.0);
        double near = exit + 0.25;
        while (pass.clear_of_support && near <= reach &&
               !footprint.body_map().free(a.point.x() + c * near, a.point.y() + s * near)) {
          near += OccupancyMap::kResolution;
        }
        if (pass.clear_of_support && near > reach) {
          ++tally.blocked;
          continue;
        }
        const double far = std::max(near + 0.05, reach);
        // Biased towards the object: at arm's length, tracking is fragile.
        const double u = unit(rng), distance = near + (far - near) * u * u;
        p = {a.point.x() + c * distance, a.point.y() + s * distance, 0};
        // (Wipe strokes run across the robot's front: it faces the dirt.)
        p.yaw = std::atan2(-s, -c) + def.yaw_spread * (unit(rng) - 0.5);
      }
      // The arm arrives as it drives (tucked, or carrying): where that pose
      // already touches a wall, the footprint's disks missed the elbow, and the
      // arm has no room to swing to its work (a dip beside the wall).
      if (!footprint.free(p) || (articulated && !room_to_pull(footprint, p, *articulated)) ||
          checker.collides(travel.data(), &p)) {
        ++tally.blocked;
      } else if (w.scene().room_at(p.x, p.y) != room) {
        ++tally.elsewhere;
      } else if (!reach(ik, checker, w, object, targets(p), p, purpose, load, starts)) {
        ++tally.unreachable;
      } else if (use(p, starts)) {
        return true;
      }
    }
  }
  return false;
}

std::string BasePoseTally::to_string() const {
  const int draws = blocked + elsewhere + unreachable + cut_off;
  return "of " + std::to_string(draws) + " base poses drawn round it: " + std::to_string(blocked) + " in collision, " +
         std::to_string(elsewhere) + " in another room, " + std::to_string(unreachable) + " out of the arm's reach, " +
         std::to_string(cut_off) + " cut off from the robot";
}

bool ReachSearch::sample(const std::vector<Approach>& around,
                         const std::function<std::vector<Approach>(const Pose2&)>& targets, uint64_t sample_seed) {
  return sample_base_poses(w, ik, checker, footprint, type, object, around, targets, sample_seed, load,
                           options.base_pose_samples, tally, [&](const Pose2& p, size_t) {
                             if (!drivable.free(p.x, p.y)) return ++tally.cut_off, false;
                             kept.push_back(p);
                             return true;
                           });
}

bool ReachSearch::kept_reaches(const std::function<std::vector<Approach>(const Pose2&)>& targets) {
  return std::any_of(kept.begin(), kept.end(), [&](const Pose2& p) {
    return reach(ik, checker, w, object, targets(p), p, type, load).has_value();
  });
}

Executor::Executor(World& w, PrimitiveType type, int object, uint64_t seed, const PrimitiveOptions& options)
    : w_(w),
      type_(type),
      def_(primitive_def(type)),
      object_(object),
      options_(options),
      motion_(w, options, seed, object, result_) {
  result_.mode = options.mode;
}

PrimitiveResult Executor::run() {
  // navigate checks the rest of its precondition itself, after tucking, with its own IK solver.
  std::string unmet = w_.real(object_) ? "" : not_real(w_, object_);
  if (unmet.empty() && !def_.drives) unmet = def_.unmet_precondition(w_, object_);
  const bool ok = unmet.empty() ? def_.act(*this) : fail(PrimitiveStatus::precondition_failure, unmet);
  // A failed manipulation still ends tucked where it can, so the robot can drive on.
  if (!ok && !result_.diverged && !def_.drives) {
    const PrimitiveResult failed = result_;
    motion_.tuck();
    const double planning = result_.planning_seconds, execution = result_.execution_seconds;
    const int64_t steps = result_.physics_steps;
    result_ = failed;
    result_.planning_seconds = planning;
    result_.execution_seconds = execution;
    result_.physics_steps = steps;
  }
  if (!motion_.physical()) {
    motion_.look_at_object();  // physical motions turned the head as they went
    // What the primitive did makes its transitions at once (physically they
    // are made every env step, as the motion went).
    if (w_.state_updates()) make_transitions(w_);
  }
  return result_;
}

bool Executor::at(const ArmConfiguration& q) const {
  const ArmConfiguration now = arm_configuration(w_);
  for (size_t k = 0; k < q.size(); ++k) {
    if (std::abs(now[k] - q[k]) > 0.05) return false;
  }
  return true;
}

// The hand's pre-pose for this primitive, solved from where the base stands.
bool Executor::reach_pre_pose(ArmConfiguration& q) {
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

bool Executor::tuck_where_possible() {
  if (motion_.tuck()) return true;
  if (result_.diverged) return false;
  result_.status = PrimitiveStatus::success;
  result_.reason.clear();
  return true;
}

bool Executor::go_to_pre_pose() {
  ArmConfiguration q;
  if (!reach_pre_pose(q)) return false;
  // Untucked first, as the seed's primitives start, unless furniture is in the way.
  if (w_.grasped_object() < 0 && !arm_in_collision(w_, kUntuckedConfiguration) &&
      !motion_.arm_to(kUntuckedConfiguration)) {
    return false;
  }
  return motion_.arm_to(q);
}

namespace {
constexpr double kRestingDepth = 0.0005;  // m

// Symbolic release: the object drops straight down onto what is below it.
void settle_kinematically(World& w, int held) {
  const SceneObject& o = w.scene().objects()[held];
  const Aabb box = object_aabb(w, held);
  std::vector<int> others;
  const mjModel* m = w.model();
  for (int g = 0; g < m->ngeom; ++g) {
    const int root = m->body_rootid[m->geom_bodyid[g]];
    if ((m->geom_contype[g] || m->geom_conaffinity[g]) && root != o.body &&
        root != m->body_rootid[w.robot()->gripper_body]) {
      others.push_back(g);
    }
  }
  double drop = 1e9;
  const Eigen::Vector3d c = box.center();
  const double hx = (box.hi.x() - box.lo.x()) / 2 * 0.8, hy = (box.hi.y() - box.lo.y()) / 2 * 0.8;
  for (const auto& [dx, dy] : {std::pair{0.0, 0.0}, {hx, hy}, {-hx, hy}, {hx, -hy}, {-hx, -hy}}) {
    const double hit = ray_to_geoms(w, others, Eigen::Vector3d(c.x() + dx, c.y() + dy, box.lo.z()), kDown, 5.0);
    if (hit >= 0) drop = std::min(drop, hit);
  }
  if (drop < 1e9) {
    const int adr = m->jnt_qposadr[m->body_jntadr[o.body]];
    // Half a millimetre into the support, as MuJoCo's soft contacts rest:
    // a gap, however small, is no contact, and ontop needs one.
    w.data()->qpos[adr + 2] -= std::max(0.0, drop + kRestingDepth);
    mj_forward(m, w.data());
  }
}

}  // namespace

bool Executor::release() {
  const int held = w_.grasped_object();
  motion_.gripper(true);
  if (!motion_.physical() && held >= 0) {
    const Clock::time_point t = Clock::now();
    settle_kinematically(w_, held);
    result_.execution_seconds += since(t);
  }
  motion_.wait(0.3);
  // Up, or out of a shelf the way the hand came in.
  motion_.line(from_above(approach_) ? Eigen::Vector3d(kUp * kLift) : Eigen::Vector3d(-approach_.direction * kLift),
               false, kRetreatSpeed, 0.0);
  return tuck_where_possible();
}

bool Executor::go_to_pre_pose_with_load() {
  if (!go_to_pre_pose()) return false;
  if (!from_above(approach_)) return true;  // into a shelf: the pre-pose is the place
  const Eigen::Vector3d spot = approach_.point;
  Eigen::Vector3d shift = spot - object_aabb(w_, w_.carried_object()).center();
  shift.z() = 0;
  motion_.line(shift, false, kRetreatSpeed, 0.0);
  return true;
}

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

std::string out_of_reach(const World& w, PrimitiveType type, int object, uint64_t seed,
                         const PrimitiveOptions& options) {
  const Footprint footprint(w);
  const std::optional<Pose2> start = free_pose_near(footprint, w.base_pose());
  if (!start) return "the robot is boxed in where it stands";
  IkSolver ik(w);
  ArmCollisionChecker checker(w);
  const PrimitiveDef& def = primitive_def(type);
  // A tool for dip and wipe may not be held yet.
  const double load = def.with_tool ? std::max(load_below_hand(w), kToolHang) : load_below_hand(w);
  ReachSearch search{w,       type, object,  seed,      load,
                     options, ik,   checker, footprint, footprint.body_map().reachable_from(start->x, start->y)};
  if (def.out_of_reach) return def.out_of_reach(search);
  const auto targets = [&](const Pose2& p) { return approaches(w, type, object, p); };
  if (search.sample(targets(w.base_pose()), targets, seed)) return "";
  const Aabb box = object_aabb(w, object);
  char height[64];
  std::snprintf(height, sizeof height, "%.2f-%.2f m", std::max(0.0, box.lo.z()), std::max(0.0, box.hi.z()));
  return "no base pose the robot can drive to brings '" + w.scene().objects().at(object).name + "' (at " + height +
         " above the floor) within reach to " + to_string(type) + " it (" + search.tally.to_string() + ")";
}

std::function<bool(const Eigen::Vector3d&, double, bool)> arm_reach_preference(const World& w) {
  constexpr double kHighestTop = 1.15, kLowestCovered = 0.3, kHighTop = 1.0;
  constexpr double kNearest = 0.35, kFarthest = 0.55, kFarthestHigh = 0.45, kRing = 0.05;
  constexpr int kDirections = 16;
  auto map = std::make_shared<const OccupancyMap>(Footprint(w).body_map());
  return [map](const Eigen::Vector3d& p, double height, bool covered) {
    const double top = p.z() + height;
    if (top > kHighestTop || (covered && p.z() < kLowestCovered)) return false;
    const double farthest = top > kHighTop ? kFarthestHigh : kFarthest;
    for (double r = kNearest; r <= farthest + 1e-9; r += kRing) {
      for (int k = 0; k < kDirections; ++k) {
        const double angle = 2 * M_PI * k / kDirections;
        if (map->free(p.x() + r * std::cos(angle), p.y() + r * std::sin(angle))) return true;
      }
    }
    return false;
  };
}

ReachProblem first_out_of_reach(World& w, const std::vector<PrimitiveType>& types, const std::vector<int>& objects,
                                uint64_t seed) {
  if (types.size() != objects.size()) throw Error("first_out_of_reach: as many types as objects are needed");
  ReachProblem problem;
  const auto check = [&](size_t i) {
    // What transitions have not made yet is not anywhere to reach (it will
    // be where what it is made of was).
    if (!w.real(objects[i])) return true;
    problem.reason = out_of_reach(w, types[i], objects[i], seed + i);
    if (!problem.reason.empty()) problem.index = static_cast<int>(i);
    return problem.reason.empty();
  };
  // (An opening or closing primitive whose drawer is already as it would
  // leave it has nothing to reach.)
  for (size_t i = 0; i < types.size(); ++i) {
    const PrimitiveDef& def = primitive_def(types[i]);
    if (def.opens && def.unmet_precondition(w, objects[i]).empty() && !check(i)) return problem;
  }
  // The rest with the drawers pulled open as push leaves them, what is in them along.
  const std::vector<double> saved(w.data()->qpos, w.data()->qpos + w.model()->nq);
  bool pulled = false;
  for (size_t i = 0; i < types.size(); ++i) {
    const auto a = primitive_def(types[i]).opens ? articulation(w, objects[i]) : std::nullopt;
    if (!a || open_fraction(*a) >= kPullFraction) continue;
    set_articulation(w, *a, a->low + (a->high - a->low) * kPullFraction);
    pulled = true;
  }
  for (size_t i = 0; i < types.size(); ++i) {
    const PrimitiveDef& def = primitive_def(types[i]);
    if (def.opens) continue;
    const auto own = def.own_doors_as_they_are && pulled ? articulation(w, objects[i]) : std::nullopt;
    const double pulled_to = own ? own->value : 0;
    if (own) set_articulation(w, *own, saved[w.model()->jnt_qposadr[own->joint]]);
    const bool reached = check(i);
    if (own) set_articulation(w, *own, pulled_to);
    if (!reached) break;
  }
  if (pulled) {
    std::copy(saved.begin(), saved.end(), w.data()->qpos);
    mj_forward(w.model(), w.data());
  }
  return problem;
}

std::string unmet_precondition(const World& w, PrimitiveType type, int object) {
  check_object(w, object);
  return w.real(object) ? primitive_def(type).unmet_precondition(w, object) : not_real(w, object);
}

bool primitive_applies(const World& w, PrimitiveType type, int object) {
  check_object(w, object);
  return primitive_def(type).applies(w, object);
}

std::vector<SymbolicStep> primitive_model(PrimitiveType type, const std::vector<SymbolicObject>& objects,
                                          const SymbolicArgs& args) {
  for (const int i : {args.target, args.held, args.substance}) {
    if (i < -1 || i >= static_cast<int>(objects.size())) {
      throw Error("primitives: symbolic object " + std::to_string(i) + " out of range (" +
                  std::to_string(objects.size()) + " objects)");
    }
  }
  if (args.target < 0) throw Error("primitives: a symbolic step needs a target");
  std::vector<SymbolicStep> steps = primitive_def(type).model(objects, args);
  const std::string name = std::string(to_string(type)) + "(" + objects[args.target].name + ")";
  for (SymbolicStep& s : steps) s.name = name;
  return steps;
}

bool primitive_about_substance(PrimitiveType type) {
  return primitive_def(type).about_substance;
}

bool primitive_touches(PrimitiveType type) {
  return primitive_def(type).touches;
}

bool primitive_is_physical(PrimitiveType type) {
  return !primitive_def(type).symbolic_only;
}

PrimitiveResult execute_primitive(World& world, PrimitiveType type, int object, uint64_t seed,
                                  const PrimitiveOptions& options) {
  if (!world.robot()) throw Error("primitives: the scene has no robot");
  check_object(world, object);
  return Executor(world, type, object, seed, options).run();
}

}  // namespace chore
