// dip(object): lowers what the hand holds (a rag) into the liquid the object
// holds until it soaks, and lifts it out.
#include <algorithm>

#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"

namespace chore {
namespace {

constexpr double kSoakDepth = 0.04;  // m under a liquid's surface that dip lowers the held object

bool applies(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  return ab && ab->holds_liquid;
}

std::string unmet_precondition(const World& w, int object) {
  if (w.carried_object() < 0) return "the hand holds nothing";
  return applies(w, object) ? "" : "'" + w.scene().objects().at(object).name + "' holds no liquid";
}

// Where the held object's bottom is kSoakDepth under the liquid's surface.
Eigen::Vector3d line_end(const World& w, int object, const Approach& a, const Pose2&, double load) {
  const Aabb box = object_aabb(w, object);
  const double surface = box.lo.z() + w.states().state(object).liquid_level * (box.hi.z() - box.lo.z());
  return {a.point.x(), a.point.y(), surface - kSoakDepth + load};
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  if (!e.go_to_pre_pose_with_load()) return false;
  // Down until the held object's bottom is under the liquid's surface.
  const double end = line_end(w, e.object(), e.approach(), w.base_pose(), load_below_hand(w)).z();
  const Eigen::Vector3d down = kDown * std::max(0.0, m.hand_position().z() - end);
  // Not stopping at contact: a rag's corners brush the rim on the way in.
  if (!m.line(down, false, kApproachSpeed)) return false;
  m.wait(0.6);  // long enough to soak through (ObjectStates: 0.5 s)
  m.line(-down, false, kRetreatSpeed, 0.0);
  if (!e.tuck_where_possible()) return false;
  const int held = w.grasped_object();
  if (held < 0) return e.fail(PrimitiveStatus::grasp_failure, "dropped what it held");
  const ObjectAbilities* ab = w.states().abilities(held);
  if (ab && ab->soakable) {
    const auto& soaked = w.states().state(held).soaked;
    const std::string& liquid = w.states().state(e.object()).liquid;
    if (!soaked.count(liquid) || soaked.at(liquid) < ObjectStates::kSoakedLevel) {
      return e.fail(PrimitiveStatus::motion_planning_failure, "the held object did not reach the liquid");
    }
  }
  return true;
}

// Symbolically: what the hand holds, if it absorbs (a particle remover),
// becomes saturated with the liquid the object contains.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  if (agent < 0 || a.held < 0 || a.substance < 0 || objects[a.target].kind != SymbolicObject::Kind::object ||
      !objects[a.held].has("particleRemover") || !objects[a.substance].has("liquid")) {
    return {};
  }
  SymbolicStep s;
  s.needs = {literal("grasped", {agent, a.held}), literal(kWithinReach, {a.target}),
             literal("contains", {a.target, a.substance})};
  s.adds = {literal("saturated", {a.held, a.substance})};
  return {s};
}

}  // namespace

const PrimitiveDef& dip_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .line_end = line_end,
                                .about_substance = true,
                                .with_tool = true};
  return def;
}

}  // namespace chore
