// place_next_to(object): the carried object set down beside the object, on
// what the object stands on (BDDL's nextto: a book next to the others on a
// shelf, firewood by the fireplace), released, and the hand back.
#include <algorithm>

#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

constexpr double kGap = 0.02;  // m between the two boxes

bool applies(const World&, int) {
  return true;  // which objects things go next to is the activity's to say
}

std::string unmet_precondition(const World& w, int object) {
  if (w.carried_object() < 0) return "the hand holds nothing";
  return w.grasped_object() == object ? "cannot place an object next to itself" : "";
}

// The spots beside each of the object's four sides, as far out as the load
// is wide, at the height the object stands at; the side facing the base first.
std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  const Aabb box = object_aabb(w, object);
  const int held = w.carried_object();
  const Eigen::Vector3d load = held >= 0 ? object_aabb(w, held).extent() : Eigen::Vector3d::Zero();
  const double reach_out = std::max(load.x(), load.y()) / 2 + kGap;
  std::vector<Approach> out;
  for (const auto& [sx, sy] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {0.0, 1.0}, {0.0, -1.0}}) {
    const Eigen::Vector3d side(sx, sy, 0);
    Eigen::Vector3d p = box.center() + side.cwiseProduct(box.extent() / 2 + Eigen::Vector3d::Constant(reach_out));
    p.z() = box.lo.z();
    out.push_back({p, kDown, std::nullopt});
  }
  const Eigen::Vector2d at(base.x, base.y);
  std::stable_sort(out.begin(), out.end(), [&](const Approach& a, const Approach& b) {
    return (a.point.head<2>() - at).norm() < (b.point.head<2>() - at).norm();
  });
  return out;
}

bool act(Executor& e) {
  World& w = e.world();
  const int held = w.grasped_object();
  if (!e.go_to_pre_pose_with_load() || !e.release()) return false;
  if (!nextto(w, held, e.object())) {
    return e.fail(PrimitiveStatus::place_failure,
                  "'" + w.scene().objects()[held].name + "' is not next to '" + e.name() + "'");
  }
  return true;
}

// Symbolically: what the hand holds ends next to the object (either way
// round), on what the object stands on: on the floor of its room where it is
// furniture, else on what it lies on (a step for each; one for nothing).
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  using Kind = SymbolicObject::Kind;
  const int agent = agent_index(objects);
  const SymbolicObject& target = objects[a.target];
  if (agent < 0 || a.held < 0 || a.held == a.target || target.kind != Kind::object) return {};
  SymbolicStep beside =
      setting_down(agent, a, {literal("nextto", {a.held, a.target}), literal("nextto", {a.target, a.held})});
  if (target.fixed) {
    for (int f = 0; f < static_cast<int>(objects.size()); ++f) {
      if (objects[f].kind == Kind::floor && !target.room.empty() && objects[f].room == target.room)
        beside.adds.push_back(literal("ontop", {a.held, f}));
    }
    return {beside};
  }
  std::vector<SymbolicStep> out;
  for (int s = 0; s < static_cast<int>(objects.size()); ++s) {
    if (s == a.target || s == a.held || (objects[s].kind != Kind::object && objects[s].kind != Kind::floor)) continue;
    SymbolicStep on = beside;
    on.needs.push_back(literal("ontop", {a.target, s}));
    on.adds.push_back(literal("ontop", {a.held, s}));
    out.push_back(std::move(on));
    beside.needs_not.push_back(literal("ontop", {a.target, s}));
  }
  out.push_back(std::move(beside));
  return out;
}

}  // namespace

const PrimitiveDef& place_next_to_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .approaches = approaches,
                                .touches = false};
  return def;
}

}  // namespace chore
