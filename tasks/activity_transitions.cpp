// Activity::configure_transitions: the knowledge base's transition rules
// (tasks/transition_rules.hpp) bound to one activity's objects and
// substances, for the world to make (world/transitions.hpp).
//
// A rule is bound where the activity has each of its inputs and something it
// makes (a future object, or a substance it names), as the planner's
// SymbolicProblem binds it: an input synset matches the activity's objects
// and substances whose declared type is-a it. Each output object is made by
// one transition (two apples and two half apples: the first apple's
// slicing makes both halves). Counts: up to a rule's count of each input
// object are bound, and the rule fires with those (relaxed where the
// activity has fewer).
#include <map>
#include <optional>
#include <set>

#include "tasks/activity.hpp"
#include "tasks/transition_rules.hpp"
#include "world/transitions.hpp"

namespace chore {
namespace {

// OmniGibson's MeltingRule: a meltable object melts once its highest
// temperature reaches m.MELTING_TEMPERATURE.
constexpr double kMeltingTemperature = 100;

// What an input or output synset matches among the activity's things.
struct Thing {
  std::string instance, type;
  int object = -1;        // a scene object, or -1 for a substance
  std::string substance;  // the world's name of a substance (its lemma)
  bool future = false;
};

}  // namespace

void Activity::configure_transitions(World& w) const {
  const TransitionRules& rules = behavior_transition_rules();
  std::vector<Thing> things;
  for (const auto& [instance, b] : bindings_) {
    const std::string type = type_of(instance);
    if (!kb_->contains(type)) continue;
    const bool future = future_.count(instance) > 0;
    if (b.kind == Binding::Kind::object) things.push_back({instance, type, b.index, "", future});
    if (b.kind == Binding::Kind::substance) things.push_back({instance, type, -1, synset_lemma(type), future});
  }
  const auto type_of_object = [&](int object) {
    for (const Thing& t : things) {
      if (t.object == object) return t.type;
    }
    return std::string();
  };
  const auto matching = [&](const std::string& synset) {
    std::vector<const Thing*> out;
    if (!kb_->contains(synset)) return out;
    for (const Thing& t : things) {
      if (kb_->is_a(t.type, synset)) out.push_back(&t);
    }
    return out;
  };
  const auto objects_matching = [&](const std::string& synset) {
    std::vector<int> out;
    for (const Thing* t : matching(synset)) {
      if (t->object >= 0 && !t->future) out.push_back(t->object);
    }
    return out;
  };
  const auto holders = [&] {
    std::vector<int> out;
    for (const Thing& t : things) {
      const ObjectAbilities* ab = t.object >= 0 ? w.states().abilities(t.object) : nullptr;
      if (ab && ab->holds_liquid && !t.future) out.push_back(t.object);
    }
    return out;
  };
  // Machines make sludge of what no recipe takes, whether or not one of
  // their recipes is bound here.
  for (const TransitionRule& r : rules.rules()) {
    for (const SynsetCount& m : r.machines) {
      for (const int machine : objects_matching(m.synset)) w.states().add_machine(machine);
    }
  }

  std::set<int> made;  // output objects a transition already makes
  const auto add_outputs = [&](const TransitionRule& r, Transition& t) {
    for (const SynsetCount& out : r.outputs) {
      int wanted = out.count;
      std::set<std::string> substances;
      for (const Thing* thing : matching(out.synset)) {
        if (thing->object < 0 && substances.insert(thing->substance).second)
          t.output_substances.push_back(thing->substance);
        if (thing->object >= 0 && thing->future && wanted > 0 && made.insert(thing->object).second) {
          t.output_objects.push_back(thing->object);
          --wanted;
        }
      }
    }
    for (const StateCondition& c : r.output_states) {
      if (c.synsets.size() != 1) continue;
      for (const int out : t.output_objects) {
        if (kb_->contains(c.synsets[0]) && kb_->is_a(type_of_object(out), c.synsets[0]))
          t.output_states.push_back({out, c.predicate, c.value});
      }
    }
    return !t.output_objects.empty() || !t.output_substances.empty();
  };
  // The rule's input states, on the input objects bound to their synsets.
  const auto add_input_states = [&](const TransitionRule& r, Transition& t) {
    for (const StateCondition& c : r.input_states) {
      if (c.synsets.size() != 1) continue;
      for (const int in : t.input_objects) {
        if (kb_->contains(c.synsets[0]) && kb_->is_a(type_of_object(in), c.synsets[0]))
          t.input_states.push_back({in, c.predicate, c.value});
      }
    }
  };
  // Every input bound (objects up to their counts, substances by name); false
  // where the activity lacks one.
  const auto add_inputs = [&](const TransitionRule& r, Transition& t) {
    for (const SynsetCount& in : r.inputs) {
      const std::vector<const Thing*> found = matching(in.synset);
      if (found.empty()) return false;
      int wanted = in.count;
      std::set<std::string> substances;
      for (const Thing* thing : found) {
        if (thing->object < 0 && substances.insert(thing->substance).second)
          t.input_substances.push_back(thing->substance);
        if (thing->object >= 0 && wanted-- > 0) t.input_objects.push_back(thing->object);
      }
    }
    add_input_states(r, t);
    return true;
  };

  for (const TransitionRule& r : rules.rules()) {
    Transition t;
    t.name = r.name;
    t.steps = std::max(1, r.timesteps.value_or(1));
    switch (r.family) {
      case TransitionFamily::slicing:
      case TransitionFamily::dicing:
      case TransitionFamily::melting:
        // One transition per input object: each apple is sliced on its own.
        if (r.inputs.size() != 1) break;
        t.trigger = r.family == TransitionFamily::melting ? TransitionTrigger::melted : TransitionTrigger::sliced;
        t.temperature = kMeltingTemperature;
        for (const Thing* in : matching(r.inputs[0].synset)) {
          if (in->object < 0) continue;
          Transition one = t;
          one.input_objects = {in->object};
          add_input_states(r, one);
          if (add_outputs(r, one)) w.states().add_transition(std::move(one));
        }
        break;
      case TransitionFamily::heat_cook:
        t.trigger = TransitionTrigger::heated;
        for (const SynsetCount& c : r.containers) {
          for (const int place : objects_matching(c.synset)) t.places.push_back(place);
        }
        for (const SynsetCount& h : r.heat_sources) {
          for (const int source : objects_matching(h.synset)) t.heat_sources.push_back(source);
        }
        if (!r.heat_sources.empty() && t.heat_sources.empty()) break;
        if (!t.places.empty() && add_inputs(r, t) && add_outputs(r, t)) w.states().add_transition(std::move(t));
        break;
      case TransitionFamily::substance_cooking:
      case TransitionFamily::substance_watercooking:
        t.trigger = TransitionTrigger::heated;
        t.places = holders();
        if (!t.places.empty() && add_inputs(r, t) && add_outputs(r, t)) w.states().add_transition(std::move(t));
        break;
      case TransitionFamily::single_toggleable_machine:
        t.trigger = TransitionTrigger::machine;
        t.exact = true;
        for (const SynsetCount& m : r.machines) {
          for (const int place : objects_matching(m.synset)) t.places.push_back(place);
        }
        if (!t.places.empty() && add_inputs(r, t) && add_outputs(r, t)) w.states().add_transition(std::move(t));
        break;
      case TransitionFamily::mixing_stick:
        t.trigger = TransitionTrigger::stirred;
        t.exact = true;
        t.places = holders();
        for (const Thing& thing : things) {
          if (thing.object >= 0 && !thing.future && kb_->has_property(thing.type, "mixingTool"))
            t.tools.push_back(thing.object);
        }
        if (!t.places.empty() && !t.tools.empty() && add_inputs(r, t) && add_outputs(r, t))
          w.states().add_transition(std::move(t));
        break;
      case TransitionFamily::washer_particleremover:
      case TransitionFamily::washer_nonparticleremover:
        break;  // what any washer does to what it holds: below
    }
  }

  // Washers, with what they remove of the activity's substances, and dryers.
  std::map<std::string, std::vector<std::string>> removes;
  for (const Thing& t : things) {
    if (t.object >= 0) continue;
    const std::optional<std::vector<std::string>> solvents = rules.washer_solvents(t.type);
    if (!solvents) continue;
    std::vector<std::string> present;
    for (const std::string& solvent : *solvents) {
      for (const Thing* s : matching(solvent)) {
        if (s->object < 0) present.push_back(s->substance);
      }
    }
    // One that needs a solvent the activity lacks is never removed here.
    if (solvents->empty() || !present.empty()) removes[t.substance] = std::move(present);
  }
  const std::vector<int> washers = objects_matching(kWasher), dryers = objects_matching(kClothesDryer);
  for (const int washer : washers) w.states().add_washer({washer, false, removes});
  for (const int dryer : dryers) w.states().add_washer({dryer, true, {}});
  // What a washer wets and cannot soak it covers with water.
  if (!washers.empty() && !w.states().substance("water")) w.states().add_substance({"water", false});
}

}  // namespace chore
