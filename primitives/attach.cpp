// attach(object): the carried object set onto the object and attached to it
// (BDDL's attached: a lid on its jar, a hanger in the wardrobe, a wreath on
// its nail), OmniGibson's AttachedTo forming where two attachable objects
// meet. Placed as place places it, or held against the object's side and
// let go; touching the object, the scene's attachment weld between the two
// (world/scene.hpp) holds them together. Symbolically, what did not come to
// touch it is attached where the world's sampler attaches it.
#include "primitives/primitive_def.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/sampling.hpp"

namespace chore {
namespace {

constexpr double kShortOfSide = 0.02;  // m the fingertips stop before a side the hand comes at

bool has_weld(const World& w, int object, int to) {
  for (const Scene::Attachment& a : w.scene().attachments()) {
    if (a.object == object && a.to == to && a.weld >= 0) return true;
  }
  return false;
}

bool applies(const World& w, int object) {
  for (const Scene::Attachment& a : w.scene().attachments()) {
    if (a.to == object && a.weld >= 0) return true;
  }
  return false;
}

std::string unmet_precondition(const World& w, int object) {
  const int held = w.carried_object();
  if (held < 0) return "the hand holds nothing";
  if (!has_weld(w, held, object)) {
    return "'" + w.scene().objects()[held].name + "' does not attach to '" + w.scene().objects()[object].name + "'";
  }
  return "";
}

// As place sets a load down onto the object; and against its side, in
// horizontally from where the base stands, the hand stopping with the
// fingertips 2 cm short of the side's middle: a nail on a wall, or a hook,
// has no top to set anything on.
std::vector<Approach> approaches(const World& w, int object, const Pose2& base) {
  std::vector<Approach> out = onto_top(w, object, base);
  const Aabb box = object_aabb(w, object);
  Eigen::Vector3d in(box.center().x() - base.x, box.center().y() - base.y, 0);
  if (in.norm() < 1e-6) return out;
  in.normalize();
  // Where the line from the base meets the box (on the hand's side of it).
  const Eigen::Vector3d half = box.extent() / 2;
  const double depth =
      std::min(half.x() / std::max(std::abs(in.x()), 1e-9), half.y() / std::max(std::abs(in.y()), 1e-9));
  const Eigen::Vector3d side = box.center() - in * depth;
  // The pre-pose, kClearance + kFingerReach short of the point, is where the hand stops.
  out.push_back({side + in * (kClearance - kShortOfSide), in, std::nullopt});
  return out;
}

bool act(Executor& e) {
  World& w = e.world();
  const int held = w.grasped_object();
  if (!e.go_to_pre_pose_with_load() || !e.release()) return false;
  // Symbolically, attached where the world's sampler attaches it, as
  // OmniGibson's symbolic attach sets AttachedTo: dropped against a wall's
  // nail, a load falls to the floor.
  if (!e.motion().physical() && !touching(w, held, e.object())) {
    Rng rng(e.motion().next_seed());
    if (sample_attached(w, held, e.object(), rng)) return true;
  }
  if (!touching(w, held, e.object())) {
    return e.fail(PrimitiveStatus::place_failure,
                  "'" + w.scene().objects()[held].name + "' does not touch '" + e.name() + "'");
  }
  w.attach_objects(held, e.object());
  return true;
}

// Symbolically: two attachable objects, the held one set onto the other,
// attached (and touching).
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  if (agent < 0 || a.held < 0 || a.held == a.target || objects[a.target].kind != SymbolicObject::Kind::object ||
      !objects[a.held].has("attachable") || !objects[a.target].has("attachable")) {
    return {};
  }
  return {setting_down(agent, a,
                       {literal("attached", {a.held, a.target}), literal("touching", {a.held, a.target}),
                        literal("touching", {a.target, a.held})})};
}

}  // namespace

const PrimitiveDef& attach_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .approaches = approaches,
                                .touches = false};
  return def;
}

}  // namespace chore
