#include "tasks/initial_states.hpp"

#include <algorithm>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

#include "base/error.hpp"

namespace chore {
namespace {

// OmniGibson's OnFire default (object_states/on_fire.py), for a flammable
// synset whose knowledge base entry gives none.
constexpr double kDefaultIgnition = 250;  // degrees C

// `synset` and its leaf descendants: the kinds a binding may choose for it.
std::vector<std::string> kinds_of(const KnowledgeBase& kb, const std::string& synset) {
  std::vector<std::string> kinds = {synset}, frontier = {synset};
  while (!frontier.empty()) {
    const std::string s = frontier.back();
    frontier.pop_back();
    for (const std::string& c : kb.children(s)) {
      if (kb.is_leaf(c))
        kinds.push_back(c);
      else
        frontier.push_back(c);
    }
  }
  std::sort(kinds.begin() + 1, kinds.end());
  kinds.erase(std::unique(kinds.begin() + 1, kinds.end()), kinds.end());
  return kinds;
}

}  // namespace

ObjectAbilities synset_abilities(const KnowledgeBase& kb, const std::string& s) {
  ObjectAbilities ab;
  const auto states = kb.extended_states(s);
  auto keeps = [&](ExtendedState e) { return std::find(states.begin(), states.end(), e) != states.end(); };
  ab.temperature = keeps(ExtendedState::temperature);
  ab.cook_temperature = kb.parameter(s, "cookable", "cook_temperature").value_or(ab.cook_temperature);
  ab.burn_temperature = kb.parameter(s, "burnable", "burn_temperature").value_or(ab.burn_temperature);
  if (kb.has_property(s, "flammable")) {
    ab.ignition_temperature = kb.parameter(s, "flammable", "ignition_temperature").value_or(kDefaultIgnition);
  }
  ab.soakable = keeps(ExtendedState::soaked_level);
  ab.covered = keeps(ExtendedState::covered_level);
  ab.toggleable = kb.has_property(s, "toggleable");
  ab.sliceable = keeps(ExtendedState::sliced_state) || kb.has_property(s, "diceable");
  ab.breakable = keeps(ExtendedState::broken_state);
  ab.cleaning_tool = kb.is_cleaning_tool(s);
  ab.slicer = kb.is_slicer(s);
  // Containers (BEHAVIOR-1K's fillable) and BEHAVIOR-100's water sources
  // keep a liquid level.
  ab.holds_liquid = kb.has_property(s, "waterSource") || kb.has_property(s, "fillable");
  // A source toggled on gives its substance: BEHAVIOR-1K's particleSource
  // conditions (a sink: water while toggled_on), BEHAVIOR-100's waterSource.
  // So do appliers (a shaker, a sprayer), which give theirs as they are held.
  if (ab.toggleable) {
    for (const char* property : {"particleSource", "particleApplier"}) {
      const auto conditions = kb.text_parameter(s, property, "conditions");
      if (!conditions) continue;
      const nlohmann::json systems = nlohmann::json::parse(*conditions, nullptr, false);
      if (systems.is_object() && !systems.empty()) ab.source = synset_lemma(systems.begin().key());
    }
    if (ab.source.empty() && kb.has_property(s, "waterSource")) ab.source = "water";
    if (!ab.source.empty()) ab.holds_liquid = true;
  }
  for (const auto& [property, source] :
       {std::pair{"heatSource", &ab.heat_source}, std::pair{"coldSource", &ab.cold_source}}) {
    if (!kb.has_property(s, property)) continue;
    ThermalSource t;
    if (std::string(property) == "coldSource") t.temperature = -18;
    auto flag = [&, property = property](const char* name, bool fallback) {
      return kb.parameter(s, property, name).value_or(fallback) != 0;
    };
    t.temperature = kb.parameter(s, property, "temperature").value_or(t.temperature);
    t.rate = kb.parameter(s, property, "heating_rate").value_or(t.rate);
    t.requires_toggled_on = flag("requires_toggled_on", false);
    t.requires_closed = flag("requires_closed", false);
    t.requires_inside = flag("requires_inside", false);
    *source = t;
  }
  return ab;
}

std::vector<std::string> states_set_on(const Problem& problem, const std::string& instance) {
  std::vector<std::string> predicates;
  for (const Literal& l : problem.init) {
    if (l.negated || l.args.empty() || l.args[0] != instance || l.predicate == "filled" || l.predicate == "contains")
      continue;
    if (missing_for_state(l.predicate, ObjectAbilities{}).empty()) continue;  // sets no state (a placement)
    predicates.push_back(l.predicate);
  }
  return predicates;
}

std::string kind_keeping(const KnowledgeBase& kb, const std::string& synset,
                         const std::vector<std::string>& predicates) {
  const auto keeps_all = [&](const std::string& kind) {
    const ObjectAbilities ab = synset_abilities(kb, kind);
    return std::all_of(predicates.begin(), predicates.end(),
                       [&](const std::string& p) { return missing_for_state(p, ab).empty(); });
  };
  for (const std::string& kind : kinds_of(kb, synset)) {
    if (keeps_all(kind)) return kind;
  }
  return "";
}

void check_initial_states(const Problem& problem, const KnowledgeBase& kb) {
  for (const ObjectDecl& d : problem.objects) {
    if (!kb.contains(d.type) || kb.is_substance(d.type)) continue;
    for (const Literal& l : problem.init) {
      if (l.predicate != "open" || l.negated || l.args.size() != 1 || l.args[0] != d.name) continue;
      const std::vector<std::string> kinds = kinds_of(kb, d.type);
      if (std::none_of(kinds.begin(), kinds.end(), [&](const std::string& k) { return kb.is_openable(k); })) {
        throw Error(problem.file + ": :init: " + to_bddl(l) + ": no kind of " + d.type +
                    " is openable (the knowledge base's properties, Table A.5)");
      }
    }
    const std::vector<std::string> predicates = states_set_on(problem, d.name);
    if (predicates.empty() || !kind_keeping(kb, d.type, predicates).empty()) continue;
    for (const Literal& l : problem.init) {
      if (l.negated || l.args.empty() || l.args[0] != d.name) continue;
      const std::string missing = missing_for_state(l.predicate, synset_abilities(kb, d.type));
      if (missing.empty() || !kind_keeping(kb, d.type, {l.predicate}).empty()) continue;
      throw Error(problem.file + ": :init: " + to_bddl(l) + ": no kind of " + d.type + " keeps " + missing +
                  ", which '" + l.predicate + "' sets (the knowledge base's properties, Table A.5)");
    }
    std::string all;
    for (const std::string& p : predicates) all += (all.empty() ? "" : ", ") + p;
    throw Error(problem.file + ": :init: " + d.name + ": no kind of " + d.type + " keeps the states of all of " + all +
                " at once (the knowledge base's properties, Table A.5)");
  }
}

}  // namespace chore
