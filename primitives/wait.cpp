// wait(object): holds still while the world changes the object's temperature
// (on a lit stove, in an oven or a freezer, back to the room's), until one of
// its temperature states (cooked, burnt, frozen, hot, on fire) turns or a
// transition takes it, at most kMaxWait. As OmniGibson's symbolic primitives
// wait for an object to cook (`_wait_for_cooked`: pass some time while it
// warms up, fail when it does not), and for what its primitives do not
// cover: an egg left on the stove as the last step of a plan cooks only while
// time passes, and in the primitive action space time passes only as the
// robot acts. Not a motion: the robot stands and holds what it holds.
#include <array>

#include "primitives/primitive_def.hpp"
#include "world/predicates.hpp"

namespace chore {
namespace {

constexpr double kLook = 1.0;       // s held still between looks at the object
constexpr double kMaxWait = 120.0;  // s: one wait ends here, however slowly it changes
constexpr double kStill = 0.01;     // degrees C over a look: not warming up or cooling down (OmniGibson's)

bool applies(const World& w, int object) {
  const ObjectAbilities* ab = w.states().abilities(object);
  return ab && ab->temperature;
}

// Whether it changes shows only over time: act() fails when it does not.
std::string unmet_precondition(const World&, int) {
  return "";
}

std::array<bool, 5> temperature_states(const World& w, int object) {
  return {cooked(w, object), burnt(w, object), frozen(w, object), hot(w, object), on_fire(w, object)};
}

bool act(Executor& e) {
  World& w = e.world();
  const int object = e.object();
  const std::array<bool, 5> before = temperature_states(w, object);
  for (double waited = 0; waited < kMaxWait; waited += kLook) {
    const double temperature = w.states().state(object).temperature;
    e.motion().wait(kLook);
    if (e.result().diverged) return false;
    if (!w.real(object) || temperature_states(w, object) != before) return true;
    if (std::abs(w.states().state(object).temperature - temperature) < kStill) {
      return e.fail(PrimitiveStatus::precondition_failure,
                    "'" + e.name() + "' is not warming up or cooling down" +
                        (waited > 0 ? " (any more, after " + std::to_string(std::lround(waited + kLook)) + " s)" : ""));
    }
  }
  return true;  // still changing: time passed, and the world went on
}

// Symbolically nothing: the planner's heating and cooling are the world's
// steps, which happen as time passes (the planned expert waits at a plan's
// end for what they still have to do).
std::vector<SymbolicStep> model(const std::vector<SymbolicObject>&, const SymbolicArgs&) {
  return {};
}

}  // namespace

const PrimitiveDef& wait_primitive() {
  static const PrimitiveDef def{
      .applies = applies, .unmet_precondition = unmet_precondition, .act = act, .model = model, .touches = false};
  return def;
}

}  // namespace chore
