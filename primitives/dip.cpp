// dip(object): lowers what the hand holds into the liquid the object holds
// (a bucket's, a sink's running water) until it soaks (a rag) or fills (a
// container: OmniGibson's fill from a source), and lifts it out.
#include <algorithm>

#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

constexpr double kSoakDepth = 0.04;  // m under a liquid's surface that dip lowers the held object
// m above the rim the held object's bottom starts down from: close, as a
// person dips. (With place's 10 cm the hand, pointing down, would start
// above a pot on a counter higher than the arm reaches, 1.2 m.)
constexpr double kDipClearance = 0.03;

bool applies(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  return ab && ab->holds_liquid;
}

std::string unmet_precondition(const World& w, int object) {
  const int held = w.carried_object();
  if (held < 0) return "the hand holds nothing";
  const ObjectAbilities* ab = w.states().abilities(object);
  // A source (a sink) counts as it runs, whether or not it is on yet.
  if (!ab || !ab->holds_liquid || (w.states().state(object).level() <= 0 && ab->source.empty())) {
    return "'" + w.scene().objects().at(object).name + "' holds no liquid";
  }
  const ObjectAbilities* hab = w.states().abilities(held);
  if (!hab || !(hab->soakable || hab->holds_liquid)) {
    return "'" + w.scene().objects().at(held).name + "' neither soaks nor holds a liquid";
  }
  return "";
}

// Where the held object's bottom is kSoakDepth under the liquid's surface.
Eigen::Vector3d line_end(const World& w, int object, const Approach& a, const Pose2&, double load) {
  const Aabb box = object_aabb(w, object);
  // A source (a sink) is aimed at as it runs, whether or not it is on yet.
  const ObjectAbilities* ab = w.states().abilities(object);
  double level = w.states().state(object).level();
  if (ab && !ab->source.empty()) level = std::max(level, ObjectStates::kSourceLevel);
  const double surface = box.lo.z() + level * (box.hi.z() - box.lo.z());
  return {a.point.x(), a.point.y(), surface - kSoakDepth + load};
}

// From above; where that is too high (a bottle on a counter, its top at
// 1.16 m, the tool hanging below the hand: pointing down the hand reaches
// 1.2 m at most), the hand tilted 45 degrees towards it (Ik: up to 1.4 m).
std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  std::vector<Approach> out;
  const std::vector<Eigen::Vector3d> spots = top_spots(w, object, base);
  for (const Eigen::Vector3d& spot : spots) out.push_back({spot, kDown, std::nullopt});
  for (const Eigen::Vector3d& spot : spots) {
    const Eigen::Vector3d towards(spot.x() - base.x, spot.y() - base.y, 0);
    if (towards.norm() > 1e-6) out.push_back({spot, tilted_towards(towards), std::nullopt});
  }
  return out;
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  if (!e.go_to_pre_pose_with_load()) return false;
  // Down until the held object's bottom is under the liquid's surface.
  const double end = line_end(w, e.object(), e.approach(), w.base_pose(), load_below_hand(w)).z();
  const Eigen::Vector3d down = kDown * std::max(0.0, m.hand_position().z() - end);
  // Not stopping at contact: a rag's corners brush the rim on the way in.
  // As deep as the arm goes, the soak or fill below the judge: the reach
  // check's line and this one start from different arm configurations, and
  // a rag 1 cm short of the end (7.6 mm off after 100 IK iterations) was
  // still 3 cm under the water, its dip failed 57 times over (clean_table,
  // seed 97).
  if (!m.line(down, false, kApproachSpeed, 0.0)) return false;
  m.wait(0.6);  // long enough to soak through (ObjectStates: 0.5 s)
  m.line(-down, false, kRetreatSpeed, 0.0);
  if (!e.tuck_where_possible()) return false;
  const int held = w.grasped_object();
  if (held < 0) return e.fail(PrimitiveStatus::grasp_failure, "dropped what it held");
  const ObjectAbilities* ab = w.states().abilities(held);
  if (ab && ab->holds_liquid && !ab->soakable && !contains(w, held, w.states().state(e.object()).main_substance())) {
    return e.fail(PrimitiveStatus::motion_planning_failure, "the held container did not reach the liquid");
  }
  if (ab && ab->soakable) {
    const auto& soaked = w.states().state(held).soaked;
    const std::string liquid = w.states().state(e.object()).main_substance();
    if (!soaked.count(liquid) || soaked.at(liquid) < ObjectStates::kSoakedLevel) {
      return e.fail(PrimitiveStatus::motion_planning_failure, "the held object did not reach the liquid");
    }
  }
  return true;
}

// Symbolically: what the hand holds becomes saturated with the liquid the
// object contains, if it absorbs (a particle remover), or holds it, filled,
// if it is a container.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  if (agent < 0 || a.held < 0 || a.substance < 0 || objects[a.target].kind != SymbolicObject::Kind::object ||
      !objects[a.substance].has("liquid")) {
    return {};
  }
  const SymbolicObject& held = objects[a.held];
  if (!held.has("particleRemover") && !held.has("fillable")) return {};
  SymbolicStep s;
  s.needs = {literal("grasped", {agent, a.held}), literal(kWithinReach, {a.target}),
             literal("contains", {a.target, a.substance})};
  if (held.has("particleRemover")) s.adds.push_back(literal("saturated", {a.held, a.substance}));
  if (held.has("fillable")) {
    s.adds.push_back(literal("contains", {a.held, a.substance}));
    s.adds.push_back(literal("filled", {a.held, a.substance}));
  }
  return {s};
}

}  // namespace

const PrimitiveDef& dip_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .approaches = approaches,
                                .line_end = line_end,
                                .about_substance = true,
                                .with_tool = true,
                                .clearance = kDipClearance};
  return def;
}

}  // namespace chore
