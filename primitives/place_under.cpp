// place_under(object): the carried object put on the floor (or whatever is
// there) beneath the object (BDDL's under: shoes under a table, a basket
// under the sink). Symbolic only: the hand is brought over the object as a
// place would bring it, then the load is set beneath it by the world's own
// `under` sampler (world/sampling.hpp), as OmniGibson's symbolic primitives
// set a post-condition. Not physical: the hand comes down from above, and
// above the spot beneath a table is its top; physically it fails its
// precondition saying so, and physical action spaces do not offer it.
#include "base/random.hpp"
#include "primitives/primitive_def.hpp"
#include "world/predicates.hpp"
#include "world/sampling.hpp"

namespace chore {
namespace {

bool applies(const World&, int) {
  return true;  // what things go under is the activity's to say
}

std::string unmet_precondition(const World& w, int object) {
  if (w.carried_object() < 0) return "the hand holds nothing";
  return w.grasped_object() == object ? "cannot place an object under itself" : "";
}

bool act(Executor& e) {
  World& w = e.world();
  Motion& m = e.motion();
  const int held = w.grasped_object(), object = e.object();
  if (m.physical()) {
    return e.fail(PrimitiveStatus::precondition_failure,
                  "placing under is symbolic only: the hand comes down from above, where the object's top is");
  }
  if (!e.go_to_pre_pose_with_load()) return false;
  w.release();
  m.gripper(true);
  Rng rng(m.next_seed());
  const bool placed = sample_under(w, held, object, rng);
  if (!e.tuck_where_possible()) return false;
  if (!placed || !under(w, held, object)) {
    return e.fail(PrimitiveStatus::place_failure,
                  "no room under '" + e.name() + "' for '" + w.scene().objects()[held].name + "'");
  }
  return true;
}

// Symbolically: what the hand holds ends under the object.
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>& objects, const SymbolicArgs& a) {
  const int agent = agent_index(objects);
  if (agent < 0 || a.held < 0 || a.held == a.target || objects[a.target].kind != SymbolicObject::Kind::object) {
    return {};
  }
  return {setting_down(agent, a, {literal("under", {a.held, a.target})})};
}

}  // namespace

const PrimitiveDef& place_under_primitive() {
  static const PrimitiveDef def{.applies = applies,
                                .unmet_precondition = unmet_precondition,
                                .act = act,
                                .model = model,
                                .touches = false,
                                .symbolic_only = true};
  return def;
}

}  // namespace chore
