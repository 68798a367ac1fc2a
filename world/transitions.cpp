#include "world/transitions.hpp"

#include <algorithm>
#include <set>

#include "base/random.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/sampling.hpp"
#include "world/state_rules.hpp"
#include "world/world.hpp"

namespace chore {
namespace {

constexpr double kGap = 0.01;  // m between outputs revealed side by side, and above what they stand on

bool on_or_in(const World& w, int object, int place) {
  return ontop(w, object, place) || inside(w, object, place);
}

// Whether a source of `t` (any heat source, when it lists none) acts on
// `place` now. A source the rule lists may be a cold one: a freezer makes ice.
bool heated(const World& w, const Transition& t, int place) {
  for (const auto& [source, ab] : w.states().all_abilities()) {
    if (source == place) continue;
    const bool listed = std::find(t.heat_sources.begin(), t.heat_sources.end(), source) != t.heat_sources.end();
    if (!t.heat_sources.empty() && !listed) continue;
    const std::optional<ThermalSource>& acting = ab.heat_source || !listed ? ab.heat_source : ab.cold_source;
    if (acting && thermal_source_acts(w, source, *acting, place)) return true;
  }
  return false;
}

// Whether `place` holds every input (objects on or in it, substances in its
// contents), and, for an exact recipe, no other substance.
bool holds_inputs(const World& w, const Transition& t, int place) {
  for (const int in : t.input_objects) {
    if (!on_or_in(w, in, place)) return false;
  }
  const ObjectStates& states = w.states();
  if (t.input_substances.empty()) return true;
  if (!states.tracked(place)) return false;
  const ObjectState& s = states.state(place);
  for (const std::string& in : t.input_substances) {
    const auto it = s.contents.find(in);
    if (it == s.contents.end() || it->second <= 0) return false;
  }
  if (t.exact) {
    for (const auto& [name, level] : s.contents) {
      if (level > 0 &&
          std::find(t.input_substances.begin(), t.input_substances.end(), name) == t.input_substances.end())
        return false;
    }
  }
  return true;
}

// The place where the transition's condition holds now; -1 where it holds
// without a place (sliced, melted); -2 where it does not hold.
int condition(const World& w, const Transition& t) {
  constexpr int kNot = -2;
  for (const int in : t.input_objects) {
    if (!w.real(in)) return kNot;
  }
  for (const StateOf& s : t.input_states) {
    if (unary_state(w, s.predicate, s.object) != s.value) return kNot;
  }
  const ObjectStates& states = w.states();
  switch (t.trigger) {
    case TransitionTrigger::sliced:
    case TransitionTrigger::melted: {
      if (t.input_objects.empty() || !states.tracked(t.input_objects[0])) return kNot;
      const ObjectState& s = states.state(t.input_objects[0]);
      const bool done = t.trigger == TransitionTrigger::sliced ? s.sliced : s.max_temperature >= t.temperature;
      return done ? -1 : kNot;
    }
    case TransitionTrigger::heated:
      for (const int place : t.places) {
        if (w.real(place) && holds_inputs(w, t, place) && heated(w, t, place)) return place;
      }
      return kNot;
    case TransitionTrigger::machine:
      for (const int place : t.places) {
        if (!states.tracked(place)) continue;
        const ObjectState& s = states.state(place);
        if (s.toggled && !s.machine_ran && holds_inputs(w, t, place)) return place;
      }
      return kNot;
    case TransitionTrigger::stirred:
      for (const int place : t.places) {
        if (!w.real(place) || !holds_inputs(w, t, place)) continue;
        for (const int tool : t.tools) {
          if (w.real(tool) && (touching(w, tool, place) || inside(w, tool, place))) return place;
        }
      }
      return kNot;
  }
  return kNot;
}

void fire(World& w, const Transition& t, int place, uint64_t seed) {
  ObjectStates& states = w.states();
  // Where the first input was (its box's bottom centre), and what held it.
  Eigen::Vector3d at = place >= 0 ? object_aabb(w, place).center() : Eigen::Vector3d::Zero();
  int container = place, support = -1;
  if (!t.input_objects.empty()) {
    const int first = t.input_objects[0];
    const Aabb box = object_aabb(w, first);
    at = {box.center().x(), box.center().y(), box.lo.z()};
    for (const auto& [other, ab] : states.all_abilities()) {
      if (other == first || !w.real(other)) continue;
      if (container < 0 && ab.holds_liquid && inside(w, first, other)) container = other;
      if (support < 0 && ab.covered && ontop(w, first, other)) support = other;
    }
  }
  // The inputs go: substances out of the place (their levels are the
  // outputs'), objects out of the world.
  double level = 0;
  if (place >= 0 && states.tracked(place)) {
    ObjectState& s = states.state(place);
    for (const std::string& in : t.input_substances) {
      level += s.contents[in];
      s.contents.erase(in);
    }
  }
  for (const int in : t.input_objects) w.hide(in);
  // Object outputs side by side along x, centred where the first input was.
  double width = 0;
  std::vector<Aabb> boxes;
  for (const int out : t.output_objects) {
    boxes.push_back(object_aabb(w, out));
    width += boxes.back().extent().x() + kGap;
  }
  double x = at.x() - width / 2;
  for (size_t k = 0; k < t.output_objects.size(); ++k) {
    const Aabb& box = boxes[k];
    const Eigen::Vector3d root = object_frame(w, t.output_objects[k]).pos;
    // The root where the box's bottom centre lands at (x + half its width, at.y, at.z + kGap).
    const Eigen::Vector3d offset = root - Eigen::Vector3d(box.center().x(), box.center().y(), box.lo.z());
    const Eigen::Vector3d bottom(x + box.extent().x() / 2, at.y(), at.z() + kGap);
    w.reveal(t.output_objects[k], bottom + offset);
    x += box.extent().x() + kGap;
  }
  for (const StateOf& s : t.output_states) {
    if (states.tracked(s.object) && unary_state(w, s.predicate, s.object) != s.value)
      sample_state(w, s.predicate, s.object, s.value);
  }
  // Substance outputs: in the place, or where the input object was.
  if (level <= 0) level = ObjectStates::kFilledLevel;
  for (const std::string& out : t.output_substances) {
    if (container >= 0 && states.tracked(container) && states.abilities(container)->holds_liquid) {
      states.state(container).contents[out] += level / t.output_substances.size();
    } else if (support >= 0) {
      Rng rng(seed);
      sample_covered(w, support, out, true, rng);
    }
  }
}

// One step of a washer or dryer that is on and closed (Washer).
void wash(World& w, const Washer& m, uint64_t seed) {
  ObjectStates& states = w.states();
  if (!w.real(m.object) || !states.tracked(m.object)) return;
  ObjectState& machine = states.state(m.object);
  if (!machine.toggled || is_open(w, m.object)) return;
  std::vector<int> items;
  for (const auto& [item, ab] : states.all_abilities()) {
    if (item != m.object && w.real(item) && inside(w, item, m.object)) items.push_back(item);
  }
  if (m.dryer) {
    machine.contents.erase("water");
    for (const int item : items) states.state(item).soaked.erase("water");
    return;
  }
  // What it removes is decided by what it holds before any of it goes.
  const auto removes = [&](const std::string& substance) {
    const auto it = m.removes.find(substance);
    if (it == m.removes.end()) return false;
    if (it->second.empty()) return true;
    return std::any_of(it->second.begin(), it->second.end(), [&](const std::string& solvent) {
      const auto held = machine.contents.find(solvent);
      return held != machine.contents.end() && held->second > 0;
    });
  };
  std::set<std::string> removed;
  for (const auto& [name, level] : machine.contents) {
    if (removes(name)) removed.insert(name);
  }
  for (const int item : items) {
    for (const auto& [name, particles] : states.state(item).dirt) {
      if (removes(name)) removed.insert(name);
    }
  }
  for (const std::string& name : removed) machine.contents.erase(name);
  for (const int item : items) {
    ObjectState& s = states.state(item);
    for (const std::string& name : removed) s.dirt.erase(name);
    const ObjectAbilities& ab = *states.abilities(item);
    if (ab.soakable) {
      s.soaked["water"] = 1.0;
    } else if (ab.covered && states.substance("water") && !covered(w, item, "water")) {
      Rng rng(seed ^ static_cast<uint64_t>(item));
      sample_covered(w, item, "water", true, rng);
    }
  }
}

}  // namespace

const char* to_string(TransitionTrigger trigger) {
#define CHORE_TRANSITION_TRIGGER_NAME(name) #name,
  static const char* const kNames[] = {CHORE_TRANSITION_TRIGGERS(CHORE_TRANSITION_TRIGGER_NAME)};
#undef CHORE_TRANSITION_TRIGGER_NAME
  return kNames[static_cast<int>(trigger)];
}

bool unary_state(const World& w, const std::string& p, int object) {
  if (p == "cooked") return cooked(w, object);
  if (p == "burnt") return burnt(w, object);
  if (p == "frozen") return frozen(w, object);
  if (p == "hot") return hot(w, object);
  if (p == "on_fire") return on_fire(w, object);
  if (p == "sliced") return sliced(w, object);
  if (p == "toggled_on") return toggled_on(w, object);
  if (p == "broken") return broken(w, object);
  return false;
}

void make_transitions(World& w) {
  ObjectStates& states = w.states();
  const std::vector<Transition>& transitions = states.transitions();
  std::vector<int>& progress = states.transition_progress();
  std::set<int> fired_in;  // the machines a transition fired in this step
  for (size_t i = 0; i < transitions.size(); ++i) {
    const Transition& t = transitions[i];
    const int place = condition(w, t);
    progress[i] = place > -2 ? progress[i] + 1 : 0;
    if (progress[i] < t.steps) continue;
    progress[i] = 0;
    fire(w, t, place, i);
    if (t.trigger == TransitionTrigger::machine) fired_in.insert(place);
  }
  // A machine runs once each time it is turned on: what it holds that no
  // recipe took becomes sludge (OmniGibson's ToggleableMachineRule).
  for (const int machine : states.machines()) {
    if (!states.tracked(machine)) continue;
    ObjectState& s = states.state(machine);
    if (!s.toggled) {
      s.machine_ran = false;
      continue;
    }
    if (s.machine_ran) continue;
    s.machine_ran = true;
    if (fired_in.count(machine)) continue;
    const double level = s.level();
    if (level <= 0 || (s.contents.size() == 1 && s.contents.count(kSludge))) continue;
    s.contents.clear();
    s.contents[kSludge] = level;
  }
  for (const Washer& washer : states.washers()) wash(w, washer, washer.object);
}

}  // namespace chore
