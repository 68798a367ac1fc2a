// cut(object): OmniGibson's CUT. The held slicer (a knife) comes down onto
// the object's top and on through it: physically the arm's push is the force
// the world's slicing rule reads (world/state_rules.cpp: a slicer's contact
// over the object's slice_force, the seed's F_sliced); in symbolic mode the
// motion is planned and checked the same way and the state set at the cut.
#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

constexpr double kCutDepth = 0.03;  // m the blade is driven on past first contact
constexpr double kCutSpeed = 0.05;  // m/s through the object
// m the pre-pose keeps the blade above the object: a knife hanging under the
// hand over a fruit on a counter is near the top of the arm's reach.
constexpr double kCutClearance = 0.04;

bool applies(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  return ab && ab->sliceable;
}

std::string unmet_precondition(const World& w, int object) {
  const int held = w.carried_object();
  if (held < 0) return "the hand holds nothing";
  const ObjectAbilities* tool = w.states().abilities(held);
  const auto& objects = w.scene().objects();
  if (!tool || !tool->slicer) return "'" + objects.at(held).name + "' does not cut";
  if (!applies(w, object)) return "'" + objects.at(object).name + "' cannot be cut";
  return sliced(w, object) ? "'" + objects.at(object).name + "' is already cut" : "";
}

// Where the hand's centre ends: the held blade's lowest point kCutDepth under
// the object's top (the blade hangs `load` below the hand).
Eigen::Vector3d line_end(const World& w, int object, const Approach& a, const Pose2&, double load) {
  return {a.point.x(), a.point.y(), object_aabb(w, object).hi.z() - kCutDepth + load};
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  const int object = e.object();
  if (!e.go_to_pre_pose()) return false;
  if (!m.line(kDown * (kCutClearance + 0.06), true, kApproachSpeed)) return false;
  if (!m.touched())
    return e.fail(PrimitiveStatus::motion_planning_failure, "the blade did not reach '" + e.name() + "'");
  m.line(kDown * kCutDepth, false, kCutSpeed, 0.0);
  if (!m.physical()) w.states().state(object).sliced = true;
  m.wait(0.2);
  m.line(kUp * kLift, false, kRetreatSpeed, 0.0);
  if (!e.tuck_where_possible()) return false;
  if (w.grasped_object() < 0) return e.fail(PrimitiveStatus::grasp_failure, "dropped the slicer");
  if (!sliced(w, object)) {
    return e.fail(PrimitiveStatus::motion_planning_failure, "the blade did not cut into '" + e.name() + "'");
  }
  return true;
}

// Symbolically: a held slicer cuts a sliceable (or diceable) object; the
// knowledge base's slicing and dicing rules (planner/) then make its pieces.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  const SymbolicObject& target = objects[a.target];
  if (agent < 0 || a.held < 0 || a.held == a.target || !objects[a.held].has("slicer") ||
      !(target.has("sliceable") || target.has("diceable"))) {
    return {};
  }
  SymbolicStep s;
  s.needs = {literal("grasped", {agent, a.held}), literal(kWithinReach, {a.target}), literal("real", {a.target})};
  s.adds = {literal("sliced", {a.target})};
  return {s};
}

}  // namespace

const PrimitiveDef& cut_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .line_end = line_end,
                                .with_tool = true,
                                .clearance = kCutClearance};
  return def;
}

}  // namespace chore
