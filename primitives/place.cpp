// place(object): the carried object over a flat spot on (or in) the object,
// or through the open side of a container closed on top, released, and the
// hand back: on or in it, or a place failure.
#include <algorithm>
#include <array>
#include <cmath>

#include <mujoco/mujoco.h>

#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/sampling.hpp"

namespace chore {
namespace {

bool applies(const World&, int) {
  return true;  // which objects are placement targets is the activity's to say
}

std::string unmet_precondition(const World& w, int object) {
  if (w.carried_object() < 0) return "the hand holds nothing";
  return w.grasped_object() == object ? "cannot place an object on itself" : "";
}

constexpr double kRoofDepth = 0.1;          // m: a top this close below the box's is closed (a bookcase, a fridge)
constexpr double kLevelStep = 0.05;         // m between the heights rays look down for a level from
constexpr double kInset = 0.05;             // m from the opening to the load's near side
constexpr double kHandRoom = 0.1;           // m above a load for the hand and wrist
constexpr double kForearmAbove = 0.4;       // m above the hand's centre the arm takes, the hand pointing down
constexpr double kComfortableHeight = 0.9;  // m: a level's hand height nearest this is tried first
constexpr double kSlant = 0.7;              // rad: the most the hand's way in turns from straight in
constexpr double kNearHand = 0.3;           // m: a symbolic place's sampled spot is preferred this near the hand
constexpr int kSetDownAttempts = 1000;      // sampler tries (an instance's take 100, then another instance is drawn)

// Into a container closed on top (a bookcase, a shelf, a fridge or cabinet
// with its door open), as a person puts things away: through its open side,
// horizontally, over a level (its floor or a shelf) with room for the load
// and the hand above it, the load just inside the opening (where the hand
// gets it out again). Levels nearest a hand's comfortable height first.
// None with an empty hand, or into what is open on top: place lowers the
// load into that from above (top_spots).
std::vector<Approach> through_open_side(const World& w, int object, const Pose2& base) {
  const int held = w.carried_object();
  if (held < 0) return {};
  // The carcass: an open door swung out is not where things go.
  const auto door = articulation(w, object);
  Aabb box;
  for (const int g : w.scene().objects()[object].geoms) {
    if (!door || w.model()->geom_bodyid[g] != door->link) box.grow(geom_aabb(w, g));
  }
  const Eigen::Vector3d c = box.center();
  const double roof = ray_to_object(w, object, {c.x(), c.y(), box.hi.z() + 0.05}, kDown, box.extent().z() + 0.05);
  if (roof < 0 || roof > kRoofDepth + 0.05) return {};
  const double under_roof = box.hi.z() + 0.05 - roof;  // (a shallow bowl's roof is its floor: no room under it)
  // The load's largest side, every way: held horizontally it turns with the hand.
  const double size = object_aabb(w, held).extent().maxCoeff();
  const double hand = size / 2 + 0.04;  // the hand's height over the level, the load below it clear of it
  const double room = hand + kHandRoom;
  std::vector<std::pair<double, Approach>> found;  // (preference, approach)
  for (const auto& out :
       {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0)}) {
    const double depth = std::abs(out.dot(box.extent()));
    if (depth < 2 * kInset) continue;
    const Eigen::Vector3d across = kUp.cross(out);
    const double width = std::abs(across.dot(box.extent()));
    if (width < 2 * kInset) continue;
    // The load's centre just inside the opening (a large one over the
    // middle, sticking out); of three places across, the one farthest from
    // what already stands there (the nearest the base if none is near).
    const Eigen::Vector3d inner = c + out * std::max(0.0, depth / 2 - kInset - size / 2);
    std::vector<double> levels;
    for (double z = box.hi.z() - 0.02; z > box.lo.z(); z -= kLevelStep) {
      const double down = ray_to_object(w, object, {inner.x(), inner.y(), z}, kDown, z - box.lo.z() + 0.01);
      if (down < 0) continue;
      const double level = z - down;
      if (std::any_of(levels.begin(), levels.end(), [&](double l) { return std::abs(l - level) < 0.02; })) continue;
      levels.push_back(level);
      // (A level found from inside a shelf's board has no room above it.)
      const double up = ray_to_object(w, object, {inner.x(), inner.y(), level + 0.01}, kUp, room);
      if (up >= 0 || level + room > under_roof) continue;
      // Open on this side: nothing of the object (a panel, a closed door) before the opening.
      const Eigen::Vector3d middle(inner.x(), inner.y(), level + room / 2);
      if (ray_to_object(w, object, middle, out, depth / 2 + 0.3) >= 0) continue;
      double best_clearance = -1;
      Eigen::Vector3d spot = inner;
      for (const double f : {0.0, -0.3, 0.3}) {
        const Eigen::Vector3d p = inner + across * (f * std::max(0.0, width - size - 2 * kInset));
        const double clearance = std::min(room_among_loose(w, p, object, level, level + room), 1.0) -
                                 1e-3 * std::hypot(p.x() - base.x, p.y() - base.y);
        if (clearance > best_clearance + 1e-9) best_clearance = clearance, spot = p;
      }
      spot.z() = level + hand;
      // The hand stops at the pre-pose, a clearance short of the approach
      // point (Executor::go_to_pre_pose_with_load): the arm's planner takes
      // the load in through the opening, and reach() checks it there.
      // In at a slant from where the base stands (a door swung open beside
      // the opening keeps it off the middle), at most kSlant off straight in.
      Eigen::Vector3d in(spot.x() - base.x, spot.y() - base.y, 0);
      in = in.norm() > 1e-6 && in.normalized().dot(-out) > std::cos(kSlant) ? in.normalized() : Eigen::Vector3d(-out);
      const Eigen::Vector3d point = spot + in * (kClearance + kFingerReach);
      found.push_back({std::abs(spot.z() - kComfortableHeight), {point, in, std::nullopt}});
    }
  }
  std::stable_sort(found.begin(), found.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Approach> out;
  for (const auto& [preference, a] : found) out.push_back(a);
  return out;
}

// Over a spot under a roof (a jar on a cabinet's shelf, a pencil box in a
// bookcase), where the arm may have no room to come down from above: in
// horizontally from where the base stands, as through_open_side goes in, the
// load just over the top, and let go. None where the arm has room above
// (from above is surer) or none for the load and the hand under the roof.
std::optional<Approach> under_roof(const World& w, int object, const Eigen::Vector3d& spot, const Pose2& base) {
  const int held = w.carried_object();
  const double size = object_aabb(w, held).extent().maxCoeff();
  // Pointing down, the hand's pre-pose and the wrist and forearm over it.
  const double above = kClearance + std::max(kFingerReach, load_below_hand(w)) + kForearmAbove;
  const mjtNum up[3] = {0, 0, 1};
  int geom = -1;
  const double roof =
      mj_ray(w.model(), w.data(), spot.data(), up, nullptr, 1, w.scene().objects()[object].body, &geom, nullptr);
  const double hand = size / 2 + 0.04;  // over the top, the load below the hand clear of it
  if (roof < 0 || roof > above || hand + kHandRoom > roof) return std::nullopt;
  Eigen::Vector3d in(spot.x() - base.x, spot.y() - base.y, 0);
  if (in.norm() < 1e-6) return std::nullopt;
  in.normalize();
  const Eigen::Vector3d at(spot.x(), spot.y(), spot.z() + hand);
  return Approach{at + in * (kClearance + kFingerReach), in, std::nullopt};
}

// Onto the top: from above; under a roof, in under it; else, too high for the
// hand pointing down, tilted.
std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  std::vector<Approach> out = through_open_side(w, object, base);
  for (const Eigen::Vector3d& spot : top_spots(w, object, base)) {
    out.push_back({spot, kDown, std::nullopt});
    if (w.carried_object() < 0) continue;
    if (const auto in = under_roof(w, object, spot, base)) {
      out.push_back(*in);
    } else if (const auto tilted = tilted_onto(w, spot, base)) {
      out.push_back(*tilted);
    }
  }
  return out;
}

// Symbolically, what goes into a container is set where the world's sampler
// puts it inside (upright, clear of what is there already, near the hand),
// as OmniGibson's symbolic place samples the load's pose with the predicate:
// dropped as the hand holds it, a load lies as the hand turned it, and loads
// pile up over the rim (six cans into a bucket). What came to rest neither
// in nor on anything else is sampled on it. Where the sampler finds no pose,
// the load stays as it dropped.
void set_down_symbolically(Executor& e, int held) {
  World& w = e.world();
  const int object = e.object();
  const ObjectAbilities* ab = w.states().abilities(object);
  const bool container = ab && ab->holds_liquid;
  if (!container && (inside(w, held, object) || ontop(w, held, object))) return;
  const mjModel* m = w.model();
  mjData* d = w.data();
  const int joint = m->body_jntadr[w.scene().objects()[held].body];
  mjtNum* qpos = d->qpos + m->jnt_qposadr[joint];
  std::array<mjtNum, 7> dropped;
  std::copy_n(qpos, dropped.size(), dropped.begin());
  const auto restore = [&] {
    std::copy(dropped.begin(), dropped.end(), qpos);
    std::fill_n(d->qvel + m->jnt_dofadr[joint], 6, 0.0);
    mj_forward(m, d);
  };
  Rng rng(e.motion().next_seed());
  SampleOptions options;
  options.attempts = kSetDownAttempts;
  const Eigen::Vector3d hand = e.approach().point;
  options.prefer = [&](const Eigen::Vector3d& support, double, bool) {
    return std::hypot(support.x() - hand.x(), support.y() - hand.y()) < kNearHand;
  };
  if (container && sample_inside(w, held, object, rng, options)) return;
  if (container) restore();
  if (inside(w, held, object) || ontop(w, held, object)) return;
  if (!sample_ontop(w, held, object, rng, options)) restore();
}

bool act(Executor& e) {
  World& w = e.world();
  const int held = w.grasped_object();
  if (!e.go_to_pre_pose_with_load() || !e.release()) return false;
  if (!e.motion().physical()) set_down_symbolically(e, held);
  if (!inside(w, held, e.object()) && !ontop(w, held, e.object())) {
    return e.fail(PrimitiveStatus::place_failure,
                  "'" + w.scene().objects()[held].name + "' is neither on nor in '" + e.name() + "'");
  }
  return true;
}

// Symbolically: what the hand holds ends on the object (or the floor), or,
// for a container, in it: the paper's place (appendix F.4 c) is OmniGibson's
// PLACE_ON_TOP and PLACE_INSIDE at once, releasing over the top or over an
// open drawer's exposed part (top_centre). An openable container must be open.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  const SymbolicObject& target = objects[a.target];
  if (agent < 0 || a.held < 0 || a.held == a.target ||
      (target.kind != SymbolicObject::Kind::object && target.kind != SymbolicObject::Kind::floor)) {
    return {};
  }
  // On it, it touches it.
  const SymbolicStep on = setting_down(agent, a,
                                       {literal("touching", {a.held, a.target}),
                                        literal("touching", {a.target, a.held}), literal("ontop", {a.held, a.target})});
  if (!target.has("fillable")) return {on};
  // In it, it rests on it too (a spoon put into a mug touches it: a mixing tool stirs).
  SymbolicStep in = setting_down(agent, a,
                                 {literal("inside", {a.held, a.target}), literal("touching", {a.held, a.target}),
                                  literal("touching", {a.target, a.held})});
  if (target.has("openable")) in.needs.push_back(literal("open", {a.target}));
  return {on, in};
}

}  // namespace

const PrimitiveDef& place_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .approaches = approaches,
                                .touches = false};
  return def;
}

}  // namespace chore
