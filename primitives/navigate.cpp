// navigate(object): drives the base to a pose from which the hand reaches
// what the next primitive on the object would need (OmniGibson's base-pose
// sampler, then a collision-free base path), the arm tucked.
#include <algorithm>
#include <cstdio>

#include "primitives/primitive_def.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

// Navigation aims at what will be done there, each aim the primitives a
// base pose must serve together, tried in turn. With the hand empty: an
// articulated object's handle (to push it open, or shut), else the object to
// pick, and its toggle point too where it can be toggled (an oven is opened,
// loaded, shut and turned on from one place); where no pose serves both,
// each alone. While holding, one at a time: dirt lying on it to wipe, a
// liquid to dip into, a container or surface to pour what the held container
// holds into or onto, something to cut with the held knife, to attach the
// held object to or to drape the held cloth over, then a place to put the
// load.
std::vector<std::vector<PrimitiveType>> aims_of_navigation(const World& w, int object) {
  std::vector<std::vector<PrimitiveType>> aims;
  if (w.grasped_object() < 0) {
    std::vector<PrimitiveType> both;
    if (articulation(w, object)) {
      both.push_back(is_open(w, object) ? PrimitiveType::close : PrimitiveType::push);
    } else if (primitive_def(PrimitiveType::pick).applies(w, object)) {
      both.push_back(PrimitiveType::pick);
    }
    for (const PrimitiveType toggle : {PrimitiveType::toggle_on, PrimitiveType::toggle_off}) {
      const PrimitiveDef& def = primitive_def(toggle);
      if (def.applies(w, object) && def.unmet_precondition(w, object).empty()) both.push_back(toggle);
    }
    if (both.empty()) return {{PrimitiveType::pick}};
    aims.push_back(both);
    if (both.size() > 1) {
      for (const PrimitiveType purpose : both) aims.push_back({purpose});
    }
    return aims;
  }
  const ObjectAbilities* ab = w.states().abilities(object);
  if (ab && ab->covered && !dirt_particles(w, object).empty()) aims.push_back({PrimitiveType::wipe});
  for (const PrimitiveType with_load :
       {PrimitiveType::dip, PrimitiveType::pour, PrimitiveType::cut, PrimitiveType::attach, PrimitiveType::drape}) {
    const PrimitiveDef& def = primitive_def(with_load);
    if (def.applies(w, object) && def.unmet_precondition(w, object).empty()) aims.push_back({with_load});
  }
  aims.push_back({PrimitiveType::place});
  return aims;
}

// Whether the arm, the base at p, reaches the object for each of `purposes`
// (the room checked by the caller).
bool reaches_for(const World& w, IkSolver& ik, ArmCollisionChecker& checker, int object, const Pose2& p,
                 const std::vector<PrimitiveType>& purposes, size_t starts) {
  return std::all_of(purposes.begin(), purposes.end(), [&](PrimitiveType purpose) {
    return reach(ik, checker, w, object, approaches(w, purpose, object, p), p, purpose, load_below_hand(w), starts)
        .has_value();
  });
}

bool reachable_here(const World& w, IkSolver& ik, ArmCollisionChecker& checker, int object,
                    const std::vector<PrimitiveType>& purposes, size_t starts = kReachStarts.size()) {
  const std::vector<Approach> a = approaches(w, purposes[0], object, w.base_pose());
  const Scene& scene = w.scene();
  return scene.room_at(w.base_pose().x, w.base_pose().y) == scene.room_at(a[0].point.x(), a[0].point.y()) &&
         reaches_for(w, ik, checker, object, w.base_pose(), purposes, starts);
}

bool applies(const World&, int) {
  return true;
}

std::string unmet_precondition(const World& w, int object) {
  return within_reach(w, object) ? "already within reach of '" + w.scene().objects().at(object).name + "'" : "";
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  PrimitiveResult& result = e.result();
  const int object = e.object();
  // Tucked (or carrying) if it can be; where furniture is in the way the
  // footprint measures the arm as it is.
  if (!e.at(w.carried_object() >= 0 ? kCarryConfiguration : kTuckedConfiguration) && !e.tuck_where_possible()) {
    return false;
  }
  const Clock::time_point t = Clock::now();
  const std::vector<std::vector<PrimitiveType>> aims = aims_of_navigation(w, object);
  ArmCollisionChecker checker(w);
  if (reachable_here(w, m.ik(), checker, object, aims[0])) {
    result.planning_seconds += since(t);
    return e.fail(PrimitiveStatus::precondition_failure, "already within reach of '" + e.name() + "'");
  }
  const Footprint footprint(w);
  BasePoseTally tally;
  int path_failures = 0;
  bool arrived = false;
  Clock::time_point planning = t;
  for (const std::vector<PrimitiveType>& aim : aims) {
    // One purpose alone that the hand serves from here already is not where
    // to go: the other is (a door just opened, the robot swung round with
    // it, reaches its handle but not the toggle point; back at a pose for the
    // handle alone the plan would never toggle).
    if (aim != aims[0] && reachable_here(w, m.ik(), checker, object, aim)) continue;
    const std::vector<Approach> here = approaches(w, aim[0], object, w.base_pose());
    const auto targets = [&](const Pose2& p) { return approaches(w, aim[0], object, p); };
    const std::vector<PrimitiveType> others(aim.begin() + 1, aim.end());
    path_failures = 0;
    sample_base_poses(w, m.ik(), checker, footprint, aim[0], object, here, targets, m.next_seed(), load_below_hand(w),
                      e.options().base_pose_samples, tally, [&](const Pose2& p, size_t starts) {
                        if (!reaches_for(w, m.ik(), checker, object, p, others, starts))
                          return ++tally.unreachable, false;
                        // Reachable with the arm; now the base must get there.
                        result.planning_seconds += since(planning);
                        // Where the base stops (physically, millimetres off p)
                        // the arm must still reach, as it did there: at the
                        // edge of its reach it may not, and the next candidate
                        // is tried.
                        arrived = m.base_to(p, footprint) && reachable_here(w, m.ik(), checker, object, aim, starts);
                        planning = Clock::now();
                        if (arrived || result.diverged || ++path_failures == 3) return true;
                        result.status = PrimitiveStatus::success;  // try the next candidate
                        result.reason.clear();
                        return false;
                      });
    result.planning_seconds += since(planning);
    planning = Clock::now();
    // A failed base path says why itself; out of reach where the base stopped
    // falls to the tally below.
    if (arrived || result.diverged || (path_failures == 3 && !result.ok())) return arrived;
  }
  // What for, and with what in hand: a load hanging low keeps the base off
  // what stands as high (its disk in the footprint). The counts are the last
  // aim's.
  std::string aim;
  for (size_t k = aims.size() > 1 && aims[0].size() > 1 ? 1 : 0; k < aims.size(); ++k) {
    aim += (aim.empty() ? "" : " or ") + std::string(to_string(aims[k][0]));
  }
  if (w.carried_object() >= 0) {
    char hangs[32];
    std::snprintf(hangs, sizeof hangs, "%.2f", load_below_hand(w));
    aim +=
        ", holding '" + w.scene().objects()[w.carried_object()].name + "', which hangs " + hangs + " m below the hand";
  }
  return e.fail(PrimitiveStatus::motion_planning_failure,
                "no collision-free base pose within reach of '" + e.name() + "' (to " + aim + ") in its room (" +
                    std::to_string(tally.blocked) + " samples in collision, then of " +
                    std::to_string(tally.elsewhere + tally.unreachable + path_failures) +
                    " free ones: " + std::to_string(tally.elsewhere) + " in another room, " +
                    std::to_string(tally.unreachable) + " out of the arm's reach, " + std::to_string(path_failures) +
                    " without a path or out of reach where the base stopped)");
}

// Symbolically: the object comes within reach, and what was goes out of it.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const SymbolicObject::Kind kind = objects[a.target].kind;
  if (kind != SymbolicObject::Kind::object && kind != SymbolicObject::Kind::floor) return {};
  SymbolicStep s;
  s.needs_not = {literal(kWithinReach, {a.target})};
  for (int o = 0; o < static_cast<int>(objects.size()); ++o) {
    if (o != a.target) s.deletes.push_back(literal(kWithinReach, {o}));
  }
  s.adds = {literal(kWithinReach, {a.target})};
  // To what lies in a closed fridge or oven the base-pose search finds no
  // pose (the door is in the arm's way): the plan opens it first.
  return only_while_open(objects, a.target, s);
}

}  // namespace

bool within_reach(const World& world, int object) {
  IkSolver ik(world);
  ArmCollisionChecker checker(world);
  return reachable_here(world, ik, checker, object, aims_of_navigation(world, object)[0]);
}

const PrimitiveDef& navigate_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .touches = false,
                                .drives = true};
  return def;
}

}  // namespace chore
