// attach(object): the carried object set onto the object and attached to it
// (BDDL's attached: a lid on its jar, a hanger in the wardrobe, a wreath on
// its nail), OmniGibson's AttachedTo forming where two attachable objects
// meet. Placed as place places it (symbolically, dropped straight onto what
// is below); touching the object, the scene's attachment weld between the
// two (world/scene.hpp) holds them together.
#include "primitives/primitive_def.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

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

bool act(Executor& e) {
  World& w = e.world();
  const int held = w.grasped_object();
  if (!e.go_to_pre_pose_with_load() || !e.release()) return false;
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
  static const PrimitiveDef def{
      .applies = applies, .unmet_precondition = unmet_precondition, .act = act, .model = model, .touches = false};
  return def;
}

}  // namespace chore
