#include "planner/symbolic_problem.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "tasks/vocabulary.hpp"

namespace chore {
namespace {

using Kind = SymbolicObject::Kind;

constexpr const char* kStain = "stain.n.01";
constexpr const char* kDust = "dust.n.01";
constexpr const char* kWater = "water.n.06";

SymbolicObject describe(const std::string& name, const std::string& synset, const KnowledgeBase& kb, Domain domain) {
  SymbolicObject o{name, synset};
  if (synset == "agent.n.01") o.kind = Kind::agent;
  if (synset == "floor.n.01") o.kind = Kind::floor;
  if (synset == kStain || synset == kDust || synset == kWater) o.kind = Kind::substance;
  if (synset == kWater) o.properties["liquid"];
  if (!kb.contains(synset)) return o;
  for (const auto& [property, parameters] : kb.properties(synset)) o.properties[property] = parameters;
  if (o.kind == Kind::object && kb.is_substance(synset)) o.kind = Kind::substance;
  if (kb.is_liquid(synset)) o.properties["liquid"];
  if (domain == Domain::igibson) {
    if (kb.is_cleaning_tool(synset) || kb.has_property(synset, "soakable")) {
      // BEHAVIOR-100's cleaning tools, as chore's world treats them: dust as
      // they are, stains soaked with water; what soaks is a remover too (dip).
      o.properties["particleRemover"];
      if (kb.is_cleaning_tool(synset)) o.removes = {{kDust, {}}, {kStain, {kWater}}};
    }
    // BEHAVIOR-100's knowledge base names no container property; what
    // BEHAVIOR-1K's calls fillable (a cabinet, an ashcan) holds what is
    // placed in it in chore's world in either dialect.
    static const std::shared_ptr<const KnowledgeBase> b1k = dialect_knowledge_base(Domain::omnigibson);
    if (b1k->contains(synset) && b1k->has_property(synset, "fillable")) o.properties["fillable"];
  }
  return o;
}

// Builds the world's steps over the problem's objects.
class WorldSteps {
 public:
  WorldSteps(SymbolicProblem& p, const KnowledgeBase& kb) : p_(p), kb_(kb) {}

  // Objects whose synset is-a `synset` (the knowledge base's hierarchy).
  std::vector<int> matching(const std::string& synset, bool future_only = false) const {
    std::vector<int> out;
    for (int i = 0; i < static_cast<int>(p_.objects.size()); ++i) {
      const std::string& s = p_.objects[i].synset;
      const bool is = s == synset || (kb_.contains(s) && kb_.contains(synset) && kb_.is_a(s, synset));
      if (is && (!future_only || p_.init.count({"future", {i}}))) out.push_back(i);
    }
    return out;
  }
  std::vector<int> with(const char* property) const {
    std::vector<int> out;
    for (int i = 0; i < static_cast<int>(p_.objects.size()); ++i) {
      if (p_.objects[i].has(property)) out.push_back(i);
    }
    return out;
  }
  void add(SymbolicStep step) { p_.world_steps.push_back(std::move(step)); }

  // What a working heat (cold) source needs of itself: on, closed.
  void source_needs(int source, const char* property, SymbolicStep& s) const {
    const SymbolicObject& o = p_.objects[source];
    if (o.parameter(property, "requires_toggled_on", 0) > 0) s.needs.push_back(literal("toggled_on", {source}));
    if (o.parameter(property, "requires_closed", 0) > 0) s.needs_not.push_back(literal("open", {source}));
  }

  // Heat and cold: what lies on or in a working source is heated (chilled),
  // and so is what lies on or in something heated; a source that requires it
  // heats only what is inside. Heated objects become hot, cooked and on fire
  // as the knowledge base says they can; chilled ones frozen. Off the
  // sources, at room temperature, they cool and thaw.
  void temperature() {
    for (const auto& [property, state] : {std::pair{"heatSource", kHeated}, std::pair{"coldSource", kChilled}}) {
      for (const int source : with(property)) {
        const bool inside_only = p_.objects[source].parameter(property, "requires_inside", 0) > 0;
        for (int x = 0; x < static_cast<int>(p_.objects.size()); ++x) {
          if (x == source || p_.objects[x].kind != Kind::object) continue;
          for (const char* relation : {"inside", "ontop"}) {
            if (inside_only && std::string(relation) == "ontop") continue;
            SymbolicStep s{std::string(state) + "(" + p_.objects[x].name + ")"};
            s.needs = {literal(relation, {x, source})};
            source_needs(source, property, s);
            s.adds = {literal(state, {x})};
            add(s);
          }
        }
      }
    }
    const int n = static_cast<int>(p_.objects.size());
    for (int x = 0; x < n; ++x) {
      if (p_.objects[x].kind != Kind::object) continue;
      for (int under = 0; under < n; ++under) {
        if (under == x || p_.objects[under].kind != Kind::object) continue;
        for (const char* relation : {"inside", "ontop"}) {
          for (const char* state : {kHeated, kChilled}) {
            add({std::string(state) + "(" + p_.objects[x].name + ")",
                 {literal(relation, {x, under}), literal(state, {under})},
                 {},
                 {},
                 {literal(state, {x})}});
          }
        }
      }
      const SymbolicObject& o = p_.objects[x];
      SymbolicStep heat{"heat(" + o.name + ")", {literal(kHeated, {x})}};
      if (o.has("heatable")) heat.adds.push_back(literal("hot", {x}));
      if (o.has("cookable")) heat.adds.push_back(literal("cooked", {x}));
      if (o.has("flammable")) heat.adds.push_back(literal("on_fire", {x}));
      heat.deletes.push_back(literal("frozen", {x}));
      add(heat);
      if (o.has("freezable"))
        add({"freeze(" + o.name + ")", {literal(kChilled, {x})}, {}, {}, {literal("frozen", {x})}});
      // Off every heat and cold source (a fridge keeps what is inside it
      // frozen: thawing takes it out), however it stands (on, open).
      SymbolicStep room{"room_temperature(" + o.name + ")"};
      for (const char* property : {"heatSource", "coldSource"}) {
        for (const int source : with(property)) {
          if (source == x) continue;
          room.needs_not.push_back(literal("inside", {x, source}));
          if (p_.objects[source].parameter(property, "requires_inside", 0) <= 0)
            room.needs_not.push_back(literal("ontop", {x, source}));
        }
      }
      room.deletes = {literal("hot", {x}), literal("frozen", {x}), literal("on_fire", {x})};
      add(room);
    }
  }

  // Particle sources and appliers give what their conditions list, when the
  // conditions (toggled on) hold: the source then contains it.
  void sources() {
    for (int i = 0; i < static_cast<int>(p_.objects.size()); ++i) {
      const std::string& synset = p_.objects[i].synset;
      if (!kb_.contains(synset)) continue;
      for (const char* property : {"particleSource", "particleApplier"}) {
        const auto text = kb_.text_parameter(synset, property, "conditions");
        if (!text) continue;
        const nlohmann::json conditions = nlohmann::json::parse(*text, nullptr, false);
        if (!conditions.is_object()) continue;
        for (const auto& item : conditions.items()) {
          for (const int substance : matching(item.key())) {
            SymbolicStep s{std::string(property) + "(" + p_.objects[i].name + ")"};
            if (item.value().is_array()) {
              for (const nlohmann::json& c : item.value()) {
                if (c.is_array() && c.size() == 2 && c[0] == "toggled_on" && c[1].is_boolean()) {
                  (c[1].get<bool>() ? s.needs : s.needs_not).push_back(literal("toggled_on", {i}));
                }
              }
            }
            s.adds = {literal("contains", {i, substance}), literal("real", {substance})};
            add(s);
          }
        }
      }
    }
  }

  // Each rule grounded on the objects: each input synset bound to one object
  // that is-a it (relaxed: the counts are not enforced), outputs made real.
  // A rule of one input object (slicing, dicing, melting) as the world binds
  // it (Activity::configure_transitions): one step per input object, each
  // making the next of the outputs by instance name, as many as the rule
  // makes of each (the first log's slicing makes two half logs, not the
  // eight the activity names: the plan cut one log and ended short).
  void rule(const TransitionRule& r) {
    std::vector<std::vector<int>> inputs;
    for (const SynsetCount& in : r.inputs) {
      inputs.push_back(matching(in.synset));
      if (inputs.back().empty()) return;  // the activity has none of it: the rule cannot fire
    }
    const bool per_input =
        r.inputs.size() == 1 && (r.family == TransitionFamily::slicing || r.family == TransitionFamily::dicing ||
                                 r.family == TransitionFamily::melting);
    if (!per_input) {
      std::vector<int> outputs;
      for (const SynsetCount& out : r.outputs) {
        for (const int o : matching(out.synset)) outputs.push_back(o);
      }
      if (outputs.empty()) return;  // makes nothing the activity names
      // The input objects in one binding: the first of each (relaxed: any would do).
      std::vector<int> bound;
      for (const auto& candidates : inputs) bound.push_back(candidates.front());
      ground(r, bound, outputs);
      return;
    }
    for (const int in : by_name(inputs[0])) {
      if (p_.objects[in].kind != Kind::object) continue;
      std::vector<int> outputs;
      for (const SynsetCount& out : r.outputs) {
        int wanted = out.count;
        for (const int o : by_name(matching(out.synset))) {
          if (p_.objects[o].kind == Kind::substance) {
            outputs.push_back(o);
          } else if (p_.init.count({"future", {o}}) && wanted > 0 && made_.insert(o).second) {
            outputs.push_back(o);
            --wanted;
          }
        }
      }
      if (!outputs.empty()) ground(r, {in}, outputs);
    }
  }

  // The rule's steps with its inputs bound to `bound`, making `outputs` real.
  void ground(const TransitionRule& r, const std::vector<int>& bound, const std::vector<int>& outputs) {
    SymbolicStep s{std::string(to_string(r.family)) + ":" + r.name};
    s.at_once = true;  // the world fires a transition as soon as its trigger holds
    for (const int o : outputs) s.adds.push_back(literal("real", {o}));
    for (const StateCondition& c : r.output_states) {
      if (c.synsets.size() != 1 || !c.value) continue;
      for (const int o : matching(c.synsets[0])) s.adds.push_back(literal(c.predicate.c_str(), {o}));
    }
    for (const int in : bound) {
      if (p_.objects[in].kind == Kind::object) s.deletes.push_back(literal("real", {in}));
    }
    const auto states = [&](SymbolicStep& step) {
      for (const StateCondition& c : r.input_states) {
        std::vector<int> args;
        for (const std::string& synset : c.synsets) {
          // A bound input where it is one (the log this step slices), else the first.
          const auto m = matching(synset);
          const auto in = std::find_first_of(bound.begin(), bound.end(), m.begin(), m.end());
          if (m.empty()) return false;
          args.push_back(in != bound.end() ? *in : m.front());
        }
        (c.value ? step.needs : step.needs_not).push_back(literal(c.predicate.c_str(), args));
      }
      return true;
    };
    // Each input where the rule's place (container, machine) holds it.
    const auto held_in = [&](int place, SymbolicStep& step) {
      for (const int in : bound) {
        const bool substance = p_.objects[in].kind == Kind::substance;
        step.needs.push_back(
            literal(substance ? "contains" : "inside", {substance ? place : in, substance ? in : place}));
        if (substance) {
          step.deletes.push_back(literal("contains", {place, in}));
          step.deletes.push_back(literal("filled", {place, in}));
        }
      }
    };
    // The outputs into the place, and the step added. The world gives one
    // substance made there the inputs' level (transitions.cpp): made of
    // objects alone it fills the place; made of substances, it does where
    // one of them filled it (a variant of the step each).
    const auto into = [&](int place, SymbolicStep& step) {
      std::vector<int> made;
      for (const int o : outputs) {
        const bool substance = p_.objects[o].kind == Kind::substance;
        step.adds.push_back(literal(substance ? "contains" : "inside", {substance ? place : o, substance ? o : place}));
        if (substance) made.push_back(o);
      }
      std::vector<int> liquids;
      for (const int in : bound) {
        if (p_.objects[in].kind == Kind::substance) liquids.push_back(in);
      }
      if (made.size() == 1 && liquids.empty()) step.adds.push_back(literal("filled", {place, made[0]}));
      add(step);
      if (made.size() != 1) return;
      for (const int in : liquids) {
        SymbolicStep filling = step;
        filling.needs.push_back(literal("filled", {place, in}));
        filling.adds.push_back(literal("filled", {place, made[0]}));
        add(filling);
      }
    };
    // A substance one object becomes (diced pieces, melted butter) stays
    // where the object was: in the container it was in, or on what it lay
    // on (a chopping board, covered with it). The step as it is, then one
    // for each container or support.
    const auto where_it_was = [&](const SymbolicStep& step) {
      add(step);
      for (int at = 0; at < static_cast<int>(p_.objects.size()); ++at) {
        if (at == bound[0] || p_.objects[at].kind != Kind::object) continue;
        for (const char* relation : {"inside", "ontop"}) {
          const bool in = std::string(relation) == "inside";
          if (in && !p_.objects[at].has("fillable")) continue;
          SymbolicStep placed = step;
          placed.needs.push_back(literal(relation, {bound[0], at}));
          bool substance = false;
          for (const int o : outputs) {
            if (p_.objects[o].kind != Kind::substance) continue;
            substance = true;
            placed.adds.push_back(literal(in ? "contains" : "covered", {at, o}));
          }
          if (substance) add(placed);
        }
      }
    };
    switch (r.family) {
      case TransitionFamily::slicing:
      case TransitionFamily::dicing: {
        // The input cut by a slicer (the cut primitive; the world's slicing
        // rule reads a slicer pressed in with the seed's F_sliced, not a touch).
        SymbolicStep step = s;
        step.needs = {literal("real", {bound[0]}), literal("sliced", {bound[0]})};
        if (states(step)) where_it_was(step);
        break;
      }
      case TransitionFamily::melting: {
        SymbolicStep step = s;
        step.needs = {literal("real", {bound[0]}), literal(kHeated, {bound[0]})};
        if (states(step)) where_it_was(step);
        break;
      }
      case TransitionFamily::heat_cook: {
        // The inputs on (or in) a container of the rule's that is heated, or
        // chilled where its sources are all cold ones (a freezer makes ice).
        const bool cold =
            !r.heat_sources.empty() && std::all_of(r.heat_sources.begin(), r.heat_sources.end(), [&](const auto& h) {
              return kb_.contains(h.synset) && kb_.has_property(h.synset, "coldSource") &&
                     !kb_.has_property(h.synset, "heatSource");
            });
        for (const SynsetCount& c : r.containers) {
          for (const int container : matching(c.synset)) {
            for (const char* relation : {"ontop", "inside"}) {
              SymbolicStep step = s;
              step.needs = {literal(cold ? kChilled : kHeated, {container})};
              for (const int in : bound) {
                const bool substance = p_.objects[in].kind == Kind::substance;
                step.needs.push_back(substance ? literal("contains", {container, in})
                                               : literal(relation, {in, container}));
              }
              if (states(step)) add(step);
            }
          }
        }
        break;
      }
      case TransitionFamily::substance_cooking:
      case TransitionFamily::substance_watercooking:
        // The substances in a heated container (any that holds them).
        for (const int container : with("fillable")) {
          SymbolicStep step = s;
          step.needs = {literal(kHeated, {container})};
          held_in(container, step);
          if (states(step)) into(container, step);
        }
        break;
      case TransitionFamily::single_toggleable_machine:
        for (const SynsetCount& m : r.machines) {
          for (const int machine : matching(m.synset)) {
            SymbolicStep step = s;
            step.needs = {literal("toggled_on", {machine})};
            held_in(machine, step);
            if (states(step)) into(machine, step);
          }
        }
        break;
      case TransitionFamily::mixing_stick:
        // A mixing tool touching a container that holds the inputs.
        for (const int tool : with("mixingTool")) {
          for (const int container : with("fillable")) {
            SymbolicStep step = s;
            step.needs = {literal("touching", {tool, container})};
            held_in(container, step);
            if (states(step)) into(container, step);
          }
        }
        break;
      case TransitionFamily::washer_particleremover:
      case TransitionFamily::washer_nonparticleremover:
        break;  // washers clean: washing(), not an output to make real
    }
  }

  // A washer toggled on and closed cleans what is inside it of each
  // substance the washer removes, with one of its solvents inside where it
  // needs one, and wets it; a clothes dryer dries it (OmniGibson's WasherRule
  // and DryerRule).
  void washing(const TransitionRules& rules) {
    const std::vector<int> water = matching(kWater);
    for (int item = 0; item < static_cast<int>(p_.objects.size()); ++item) {
      if (!p_.objects[item].movable()) continue;
      const bool soaks = p_.objects[item].has("soakable") || p_.objects[item].has("particleRemover");
      for (const int washer : matching(kWasher)) {
        SymbolicStep base{"washer(" + p_.objects[item].name + ")",
                          {literal("toggled_on", {washer}), literal("inside", {item, washer})},
                          {literal("open", {washer})},
                          {},
                          {},
                          true};
        for (const int w : water) {
          SymbolicStep wet = base;
          wet.adds = {literal(soaks ? "saturated" : "covered", {item, w})};
          add(wet);
        }
        for (int d = 0; d < static_cast<int>(p_.objects.size()); ++d) {
          if (p_.objects[d].kind != Kind::substance) continue;
          const std::optional<std::vector<std::string>> solvents = rules.washer_solvents(p_.objects[d].synset);
          if (!solvents) continue;
          base.deletes = {literal("covered", {item, d})};
          if (solvents->empty()) add(base);
          for (const std::string& solvent : *solvents) {
            for (const int s : matching(solvent)) {
              SymbolicStep step = base;
              step.needs.push_back(literal("contains", {washer, s}));
              add(step);
            }
          }
        }
      }
      for (const int dryer : matching(kClothesDryer)) {
        for (const int w : water) {
          add({"dryer(" + p_.objects[item].name + ")",
               {literal("toggled_on", {dryer}), literal("inside", {item, dryer})},
               {literal("open", {dryer})},
               {literal("saturated", {item, w})},
               {},
               true});
        }
      }
    }
  }

 private:
  // The objects in the order of their instance names (the world's bindings).
  std::vector<int> by_name(std::vector<int> objects) const {
    std::sort(objects.begin(), objects.end(), [&](int a, int b) { return p_.objects[a].name < p_.objects[b].name; });
    return objects;
  }

  SymbolicProblem& p_;
  const KnowledgeBase& kb_;
  std::set<int> made_;  // future objects a one-input rule's step already makes
};

}  // namespace

int SymbolicProblem::index(const std::string& instance) const {
  for (size_t i = 0; i < objects.size(); ++i) {
    if (objects[i].name == instance) return static_cast<int>(i);
  }
  return -1;
}

std::optional<SymbolicLiteral> symbolic_literal(const SymbolicProblem& p, const Literal& l) {
  std::vector<int> args;
  for (const std::string& a : l.args) {
    const int i = p.index(a);
    if (i < 0) return std::nullopt;
    args.push_back(i);
  }
  const auto with = [&](const char* predicate, const char* substance) -> std::optional<SymbolicLiteral> {
    const int s = p.index(substance);
    if (s < 0 || args.size() != 1) return std::nullopt;
    return SymbolicLiteral{predicate, {args[0], s}};
  };
  if (l.predicate == "stained") return with("covered", kStain);
  if (l.predicate == "dusty") return with("covered", kDust);
  if (l.predicate == "soaked") return with("saturated", kWater);
  if (l.predicate == "onfloor") return SymbolicLiteral{"ontop", args};
  return SymbolicLiteral{l.predicate, args};
}

SymbolicProblem symbolic_problem(const Problem& problem, const KnowledgeBase& kb, const TransitionRules& rules) {
  SymbolicProblem p;
  for (const ObjectDecl& d : problem.objects) p.objects.push_back(describe(d.name, d.type, kb, problem.domain));
  p.declared = static_cast<int>(p.objects.size());
  if (problem.domain == Domain::igibson) {
    for (const char* substance : {kStain, kDust, kWater}) {
      if (p.index(substance) < 0) p.objects.push_back(describe(substance, substance, kb, problem.domain));
    }
  }
  if (agent_index(p.objects) < 0) p.objects.push_back(describe("agent.n.01", "agent.n.01", kb, problem.domain));
  // What each remover does with each substance of the activity
  // (KnowledgeBase::remover_solvents: its conditions, else its defaults;
  // sand is visual: a towel takes it off as it is).
  if (problem.domain == Domain::omnigibson) {
    for (SymbolicObject& remover : p.objects) {
      if (!remover.has("particleRemover")) continue;
      for (const SymbolicObject& substance : p.objects) {
        if (substance.kind != Kind::substance) continue;
        if (auto solvents = kb.remover_solvents(remover.synset, substance.synset))
          remover.removes[substance.synset] = std::move(*solvents);
      }
    }
  }

  bool holding = false;
  for (const Literal& l : problem.init) {
    if (l.predicate == "inroom") {
      if (const int i = p.index(l.args.at(0)); i >= 0) {
        p.objects[i].fixed = true;
        if (l.args.size() == 2) p.objects[i].room = l.args[1];
      }
      continue;
    }
    if (l.negated) continue;  // :init is closed-world: what it does not say is false
    const auto s = symbolic_literal(p, l);
    if (!s) continue;
    p.init.insert(*s);
    if (s->predicate == "filled") p.init.insert({"contains", s->args});
    // (insource is what the object is, not what it holds: a source contains
    // its substance once its conditions hold, by the world's step, sources().)
    if (s->predicate == "grasped") holding = true;
  }
  if (!holding) p.init.insert(literal(kHandEmpty, {}));
  // What lies in a container inside something that opens is inside that too,
  // as the world's inside() finds it: the primitives reach it only once that
  // is open (only_while_open). Said of the direct container alone, an ice
  // cube in a cup in a shut fridge was picked without opening the fridge,
  // and no base pose reached it through the door. (BEHAVIOR nests two deep.)
  std::vector<std::pair<int, int>> inside;  // (what, container) of each inside literal
  for (const SymbolicLiteral& l : p.init) {
    if (l.predicate == "inside" && l.args.size() == 2) inside.emplace_back(l.args[0], l.args[1]);
  }
  for (bool grew = true; grew;) {
    grew = false;
    for (size_t i = 0, n = inside.size(); i < n; ++i) {
      for (size_t j = 0; j < n; ++j) {
        const auto [what, container] = inside[i];
        const auto [held, outer] = inside[j];
        if (held != container || outer == what || !p.objects[outer].has("openable")) continue;
        if (p.init.insert(literal("inside", {what, outer})).second) {
          inside.emplace_back(what, outer);
          grew = true;
        }
      }
    }
  }
  for (int i = 0; i < static_cast<int>(p.objects.size()); ++i) {
    if (p.init.count({"future", {i}})) continue;
    if (p.objects[i].kind != Kind::substance) {
      p.init.insert({"real", {i}});
      continue;
    }
    // A substance is real where some object holds or carries it.
    for (const SymbolicLiteral& l : std::set<SymbolicLiteral>(p.init)) {
      if (l.args.size() == 2 && l.args[1] == i) p.init.insert({"real", {i}});
    }
  }

  WorldSteps steps(p, kb);
  steps.temperature();
  steps.sources();
  if (problem.domain == Domain::omnigibson) {
    for (const TransitionRule& r : rules.rules()) steps.rule(r);
    steps.washing(rules);
  }
  return p;
}

}  // namespace chore
