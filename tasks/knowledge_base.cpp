#include "tasks/knowledge_base.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <set>

#include "base/error.hpp"
#include "base/json_file.hpp"

namespace chore {

std::string default_tasks_dir() {
  const char* env = std::getenv("CHORE_TASKS");
  return (env && *env) ? env : CHORE_TASKS_DIR;
}

const char* to_string(ExtendedState state) {
  switch (state) {
    case ExtendedState::temperature:
      return "temperature";
    case ExtendedState::max_temperature:
      return "max_temperature";
    case ExtendedState::soaked_level:
      return "soaked_level";
    case ExtendedState::covered_level:
      return "covered_level";
    case ExtendedState::toggled_state:
      return "toggled_state";
    case ExtendedState::sliced_state:
      return "sliced_state";
    case ExtendedState::broken_state:
      return "broken_state";
  }
  return "?";
}

namespace {

// The releases' file names: BEHAVIOR-100's, then BEHAVIOR-1K's. The rules are
// the same: the 1K properties file lists every synset, its non-leaf entries
// already the intersection of their leaves' (checked over all 927 of them).
struct Release {
  const char* hierarchy;
  const char* properties;
};
constexpr Release kReleases[] = {{"hierarchy_owned.json", "synsets_to_filtered_properties.json"},
                                 {"output_hierarchy.json", "propagated_annots_params.json"}};
constexpr int kStateCount = static_cast<int>(ExtendedState::broken_state) + 1;

constexpr unsigned bit(ExtendedState state) {
  return 1u << static_cast<unsigned>(state);
}
constexpr unsigned kTemperatures = bit(ExtendedState::temperature) | bit(ExtendedState::max_temperature);

// Table A.5 under both the table's property names (BEHAVIOR-1K) and the
// shipped bddl data's older ones. The data's "burnable" carries the burn
// temperature that Burnt compares with the maximum temperature (Table A.8), so
// it keeps what overcookable keeps; "dustyable"/"stainable" objects carry dust
// and stain particles, which Table A.7 tracks as the covered level.
struct StateRule {
  const char* property;
  unsigned states;
};
constexpr StateRule kStateRules[] = {
    {"cookable", kTemperatures},
    {"overcookable", kTemperatures},
    {"burnable", kTemperatures},
    {"freezable", bit(ExtendedState::temperature)},
    {"flammable", bit(ExtendedState::temperature)},
    {"heatable", bit(ExtendedState::temperature)},
    {"meltable", bit(ExtendedState::temperature)},  // the table misspells it "metable"
    {"soakable", bit(ExtendedState::soaked_level)},
    {"particleRemover", bit(ExtendedState::soaked_level)},  // BEHAVIOR-1K: what wipes up absorbs (a rag)
    {"dustyable", bit(ExtendedState::covered_level)},
    {"stainable", bit(ExtendedState::covered_level)},
    {"toggleable", bit(ExtendedState::toggled_state)},
    {"heatSource", bit(ExtendedState::toggled_state)},
    {"fireSource", bit(ExtendedState::toggled_state)},
    {"coldSource", bit(ExtendedState::toggled_state)},
    {"waterSource", bit(ExtendedState::toggled_state)},
    {"sliceable", bit(ExtendedState::sliced_state)},
    {"breakable", bit(ExtendedState::broken_state)},
};

void sort_unique(std::vector<std::string>& names) {
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
}

using Tree = std::map<std::string, std::vector<std::string>>;  // synset -> children

// Adds `node` and its subtree. A synset repeated under several parents is one
// entry whose children are those of all its repeats (duplicates removed later).
void read_hierarchy_node(const JsonReader& node, Tree& tree) {
  std::vector<std::string>& children = tree[node.string("name")];
  if (!node.has("children")) return;
  const JsonReader list = node.at("children");
  for (size_t i = 0; i < list.size(); ++i) {
    children.push_back(list.at(i).string("name"));
    read_hierarchy_node(list.at(i), tree);
  }
}

struct Annotations {
  Properties properties;
  TextParameters texts;
};

// BEHAVIOR-1K's parameters that are not numbers (kb/prop_param_description.md
// of its release): derivative synsets (*_synset), a particle method, and
// particle conditions (conditions, default_*_conditions), kept as JSON text.
bool is_text_parameter(const std::string& name) {
  return name.ends_with("_synset") || name == "method" || name.ends_with("conditions");
}

// Numbers and true/false are parameters; the text ones above text parameters;
// anything else an error.
std::map<std::string, Annotations> read_properties(const std::string& path) {
  const nlohmann::json json = read_json_file(path);
  if (!json.is_object()) throw Error(path + ": expected an object of synsets");
  std::map<std::string, Annotations> out;
  for (const auto& synset : json.items()) {
    const std::string where = path + ": " + synset.key();
    if (!synset.value().is_object()) throw Error(where + ": expected an object of properties");
    Annotations& annotations = out[synset.key()];
    for (const auto& property : synset.value().items()) {
      const std::string property_where = where + "." + property.key();
      if (!property.value().is_object()) throw Error(property_where + ": expected an object of parameters");
      auto& parameters = annotations.properties[property.key()];
      for (const auto& parameter : property.value().items()) {
        const nlohmann::json& value = parameter.value();
        if (value.is_boolean()) {
          parameters[parameter.key()] = value.get<bool>() ? 1.0 : 0.0;
        } else if (value.is_number()) {
          parameters[parameter.key()] = value.get<double>();
        } else if (is_text_parameter(parameter.key())) {
          annotations.texts[property.key()][parameter.key()] =
              value.is_string() ? value.get<std::string>() : json_text(value);
        } else {
          throw Error(property_where + "." + parameter.key() + ": expected a number or true/false");
        }
      }
    }
  }
  return out;
}

// The tree's synsets with every parent before its children; a cycle (possible
// once repeated synsets are merged) is an error.
std::vector<std::string> parents_first(const Tree& tree, const std::string& hierarchy_path) {
  std::map<std::string, size_t> waiting;  // parents not yet placed
  for (const auto& [name, children] : tree) {
    waiting[name];
    for (const std::string& child : children) ++waiting[child];
  }
  std::vector<std::string> order;
  for (const auto& [name, count] : waiting) {
    if (count == 0) order.push_back(name);
  }
  for (size_t i = 0; i < order.size(); ++i) {
    for (const std::string& child : tree.at(order[i])) {
      if (--waiting[child] == 0) order.push_back(child);
    }
  }
  for (const auto& [name, count] : waiting) {
    if (count > 0) throw Error(hierarchy_path + ": the hierarchy has a cycle through '" + name + "'");
  }
  return order;
}

// Keeps the properties both have, and of their parameters those with equal values.
template <class Map>
void intersect(Map& into, const Map& other) {
  for (auto it = into.begin(); it != into.end();) {
    const auto found = other.find(it->first);
    if (found == other.end()) {
      it = into.erase(it);
      continue;
    }
    std::erase_if(it->second, [&](const auto& parameter) {
      const auto value = found->second.find(parameter.first);
      return value == found->second.end() || value->second != parameter.second;
    });
    ++it;
  }
}

}  // namespace

std::shared_ptr<const KnowledgeBase> KnowledgeBase::load(const std::string& dir) {
  const auto release = std::find_if(std::begin(kReleases), std::end(kReleases),
                                    [&](const Release& r) { return std::filesystem::exists(dir + "/" + r.hierarchy); });
  if (release == std::end(kReleases)) {
    throw Error(dir + ": no knowledge base (expected " + kReleases[0].hierarchy + " or " + kReleases[1].hierarchy +
                ")");
  }
  const std::string hierarchy_path = dir + "/" + release->hierarchy;
  const std::string properties_path = dir + "/" + release->properties;
  Tree tree;
  const nlohmann::json hierarchy = read_json_file(hierarchy_path);
  read_hierarchy_node(JsonReader(hierarchy, hierarchy_path), tree);
  std::map<std::string, Annotations> annotations = read_properties(properties_path);

  std::map<std::string, Synset> synsets;
  for (auto& [name, children] : tree) {
    sort_unique(children);
    if (children.empty() && !annotations.contains(name)) {
      throw Error(hierarchy_path + ": leaf '" + name + "' has no entry in " + properties_path);
    }
    // The tree iterates in name order, so parents arrive sorted.
    for (const std::string& child : children) synsets[child].parents.push_back(name);
    synsets[name].children = children;
  }
  for (auto& [name, a] : annotations) {
    synsets[name].properties = std::move(a.properties);
    synsets[name].texts = std::move(a.texts);
  }

  // Synsets outside the tree have no parents and no children: nothing to derive.
  const std::vector<std::string> order = parents_first(tree, hierarchy_path);
  for (const std::string& name : order) {
    Synset& synset = synsets.at(name);
    for (const std::string& parent : synset.parents) {
      const std::vector<std::string>& above = synsets.at(parent).ancestors;
      synset.ancestors.push_back(parent);
      synset.ancestors.insert(synset.ancestors.end(), above.begin(), above.end());
    }
    sort_unique(synset.ancestors);
  }
  // Children before parents, so each child's properties are final when used.
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    Synset& synset = synsets.at(*it);
    if (synset.children.empty()) continue;
    synset.properties = synsets.at(synset.children.front()).properties;
    synset.texts = synsets.at(synset.children.front()).texts;
    for (const std::string& child : synset.children) {
      intersect(synset.properties, synsets.at(child).properties);
      intersect(synset.texts, synsets.at(child).texts);
    }
  }
  for (auto& [name, synset] : synsets) {
    for (const StateRule& rule : kStateRules) {
      if (synset.properties.contains(rule.property)) synset.states |= rule.states;
    }
  }

  std::shared_ptr<KnowledgeBase> kb(new KnowledgeBase());
  kb->synsets_ = std::move(synsets);
  return kb;
}

const KnowledgeBase::Synset& KnowledgeBase::find(const std::string& synset) const {
  const auto found = synsets_.find(synset);
  if (found == synsets_.end()) throw Error(unknown(synset));
  return found->second;
}

std::string KnowledgeBase::unknown(const std::string& synset) const {
  if (synsets_.contains(synset)) return "";
  // Other senses of the same lemma sort together, right after "<lemma>.".
  std::string message = "unknown synset '" + synset + "'";
  const std::string lemma = synset.substr(0, synset.find('.')) + ".";
  std::string senses;
  for (auto it = synsets_.lower_bound(lemma); it != synsets_.end() && it->first.starts_with(lemma); ++it) {
    senses += (senses.empty() ? "" : ", ") + it->first;
  }
  if (!senses.empty()) message += "; did you mean " + senses + "?";
  return message;
}

bool KnowledgeBase::contains(const std::string& synset) const {
  return synsets_.contains(synset);
}

std::vector<std::string> KnowledgeBase::synsets() const {
  std::vector<std::string> names;
  for (const auto& entry : synsets_) names.push_back(entry.first);
  return names;
}

const std::vector<std::string>& KnowledgeBase::parents(const std::string& synset) const {
  return find(synset).parents;
}

const std::vector<std::string>& KnowledgeBase::children(const std::string& synset) const {
  return find(synset).children;
}

const std::vector<std::string>& KnowledgeBase::ancestors(const std::string& synset) const {
  return find(synset).ancestors;
}

bool KnowledgeBase::is_leaf(const std::string& synset) const {
  return find(synset).children.empty();
}

bool KnowledgeBase::is_a(const std::string& synset, const std::string& ancestor) const {
  const std::vector<std::string>& above = find(synset).ancestors;
  find(ancestor);  // a misspelt ancestor is an error, not a quiet false
  return synset == ancestor || std::binary_search(above.begin(), above.end(), ancestor);
}

const Properties& KnowledgeBase::properties(const std::string& synset) const {
  return find(synset).properties;
}

bool KnowledgeBase::has_property(const std::string& synset, const std::string& property) const {
  return properties(synset).contains(property);
}

std::optional<double> KnowledgeBase::parameter(const std::string& synset, const std::string& property,
                                               const std::string& name) const {
  const Properties& all = properties(synset);
  const auto found = all.find(property);
  if (found == all.end()) return std::nullopt;
  const auto value = found->second.find(name);
  if (value == found->second.end()) return std::nullopt;
  return value->second;
}

std::optional<std::string> KnowledgeBase::text_parameter(const std::string& synset, const std::string& property,
                                                         const std::string& name) const {
  const TextParameters& all = find(synset).texts;
  const auto found = all.find(property);
  if (found == all.end()) return std::nullopt;
  const auto value = found->second.find(name);
  if (value == found->second.end()) return std::nullopt;
  return value->second;
}

std::vector<ExtendedState> KnowledgeBase::extended_states(const std::string& synset) const {
  const unsigned states = find(synset).states;
  std::vector<ExtendedState> out;
  for (int i = 0; i < kStateCount; ++i) {
    if (states & bit(static_cast<ExtendedState>(i))) out.push_back(static_cast<ExtendedState>(i));
  }
  return out;
}

bool KnowledgeBase::has_any(const std::string& synset, std::initializer_list<const char*> names) const {
  const Properties& all = properties(synset);
  return std::any_of(names.begin(), names.end(), [&](const char* name) { return all.contains(name); });
}

// Table A.1 names beside the data's: "substance" covers liquids and physical
// and visual substances; the data says "slicer" where the table says "slicingTool".
bool KnowledgeBase::is_substance(const std::string& synset) const {
  return has_any(synset, {"substance", "liquid", "physicalSubstance", "visualSubstance"});
}
bool KnowledgeBase::is_liquid(const std::string& synset) const {
  return has_any(synset, {"liquid"});
}
bool KnowledgeBase::is_cleaning_tool(const std::string& synset) const {
  return has_any(synset, {"cleaningTool"});
}
bool KnowledgeBase::is_slicer(const std::string& synset) const {
  return has_any(synset, {"slicer", "slicingTool"});
}
bool KnowledgeBase::is_openable(const std::string& synset) const {
  return has_any(synset, {"openable"});
}

std::optional<std::vector<std::string>> KnowledgeBase::remover_solvents(const std::string& remover,
                                                                        const std::string& substance) const {
  // A condition list ([["saturated", solvent], ...], read as alternatives:
  // oil lists eleven, any one of them cleans it), or nothing where it is null
  // (rust: the remover cannot).
  const auto solvents_of = [](const nlohmann::json& conditions) -> std::optional<std::vector<std::string>> {
    if (!conditions.is_array()) return std::nullopt;
    std::vector<std::string> solvents;
    for (const nlohmann::json& c : conditions) {
      if (c.is_array() && c.size() == 2 && c[0] == "saturated" && c[1].is_string()) {
        solvents.push_back(c[1].get<std::string>());
      }
    }
    return solvents;
  };
  if (!contains(remover)) return std::nullopt;
  if (const auto text = text_parameter(remover, "particleRemover", "conditions")) {
    const nlohmann::json named = nlohmann::json::parse(*text, nullptr, false);
    if (named.is_object() && named.contains(substance)) return solvents_of(named[substance]);
  }
  const char* which = is_liquid(substance) ? "default_fluid_conditions"
                      : contains(substance) && has_property(substance, "visualSubstance")
                          ? "default_visual_conditions"
                          : "default_non_fluid_conditions";
  const auto text = text_parameter(remover, "particleRemover", which);
  if (!text) return std::nullopt;
  return solvents_of(nlohmann::json::parse(*text, nullptr, false));
}

bool KnowledgeBase::is_source_of(const std::string& synset, const std::string& substance) const {
  if (!contains(synset)) return false;
  // A source gives its substance out (a sink's water), an applier holds it to
  // spray (an atomizer's fertilizer): both have it "in source".
  bool annotated = false;
  for (const char* property : {"particleSource", "particleApplier"}) {
    if (const auto conditions = text_parameter(synset, property, "conditions")) {
      const nlohmann::json systems = nlohmann::json::parse(*conditions, nullptr, false);
      if (systems.is_object() && systems.contains(substance)) return true;
      annotated = true;
    }
  }
  return !annotated && substance.starts_with("water.") && has_property(synset, "waterSource");
}

}  // namespace chore
