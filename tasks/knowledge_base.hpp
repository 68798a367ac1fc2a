// The synset knowledge base: the WordNet hierarchy of object categories and
// each category's properties (BEHAVIOR-1K appendix, section B), read from
// tasks/kb/behavior-100/ (the igibson dialect's) or tasks/kb/behavior-1k/ (the
// omnigibson dialect's); StanfordVL/bddl data, MIT, see each folder's
// LICENSE-bddl. Loaded once and shared read-only by every environment.
//
// Data rules:
// - The hierarchy file is a tree in which a synset with several parents is
//   repeated under each; parents() and children() merge the repeats.
// - A synset only in the properties file (e.g. wardrobe.n.01) is a root and a
//   leaf: no parents, no children.
// - A leaf's properties are its entry in the properties file (a hierarchy leaf
//   without an entry is an error). A non-leaf's properties are exactly the
//   intersection of its leaf descendants' (seed, section B), so its own entry,
//   if any, is ignored; a parameter survives the intersection only where all
//   those leaves give it the same value.
// - The hierarchy's own "abilities" and "igibson_categories" are not read.
#pragma once

#include <initializer_list>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace chore {

// Root of the task data (kb/, activities/): $CHORE_TASKS if set, else the
// source tree's tasks/.
std::string default_tasks_dir();

// A synset's lemma, the name the world knows a substance by (water.n.06 -> water).
inline std::string synset_lemma(const std::string& synset) {
  return synset.substr(0, synset.find('.'));
}

// Extended object states the simulation keeps for an object (Tables A.5, A.7).
enum class ExtendedState {
  temperature,
  max_temperature,
  soaked_level,
  covered_level,
  toggled_state,
  sliced_state,
  broken_state,
};
const char* to_string(ExtendedState state);

// property -> {parameter -> value}; true/false parameters read as 1/0.
using Properties = std::map<std::string, std::map<std::string, double>>;
// property -> {parameter -> text}: BEHAVIOR-1K's synset names (what slicing or
// cooking makes), methods, and particle conditions as JSON text.
using TextParameters = std::map<std::string, std::map<std::string, std::string>>;

class KnowledgeBase {
 public:
  // Reads <dir>/hierarchy_owned.json and <dir>/synsets_to_filtered_properties.json
  // (BEHAVIOR-100), or <dir>/output_hierarchy.json and
  // <dir>/propagated_annots_params.json (BEHAVIOR-1K).
  static std::shared_ptr<const KnowledgeBase> load(const std::string& dir = default_tasks_dir() + "/kb/behavior-100");
  KnowledgeBase(const KnowledgeBase&) = delete;
  KnowledgeBase& operator=(const KnowledgeBase&) = delete;

  bool contains(const std::string& synset) const;
  // Why `synset` is not in the hierarchy ("unknown synset 'x'; did you mean
  // x.n.01?"), or "" when it is.
  std::string unknown(const std::string& synset) const;
  std::vector<std::string> synsets() const;  // all, sorted

  // The queries below throw chore::Error "unknown synset '...'" (naming other
  // senses of the same lemma) for a name not in the knowledge base.

  // Hierarchy; lists are sorted by name.
  const std::vector<std::string>& parents(const std::string& synset) const;
  const std::vector<std::string>& children(const std::string& synset) const;
  const std::vector<std::string>& ancestors(const std::string& synset) const;  // transitive
  bool is_leaf(const std::string& synset) const;
  bool is_a(const std::string& synset, const std::string& ancestor) const;  // reflexive

  const Properties& properties(const std::string& synset) const;
  bool has_property(const std::string& synset, const std::string& property) const;
  std::optional<double> parameter(const std::string& synset, const std::string& property,
                                  const std::string& name) const;
  std::optional<std::string> text_parameter(const std::string& synset, const std::string& property,
                                            const std::string& name) const;

  // States the simulation keeps for an object of this synset, in enum order.
  std::vector<ExtendedState> extended_states(const std::string& synset) const;

  // Properties the predicate layer asks about, whichever spelling the data uses.
  bool is_substance(const std::string& synset) const;  // simulated as particles, not an object
  bool is_liquid(const std::string& synset) const;
  bool is_cleaning_tool(const std::string& synset) const;
  bool is_slicer(const std::string& synset) const;
  bool is_openable(const std::string& synset) const;
  // A particle source of `substance` (a synset): BEHAVIOR-1K's particleSource
  // or particleApplier with the substance among its conditions' systems, or BEHAVIOR-100's
  // waterSource for water. False for synsets it does not know.
  bool is_source_of(const std::string& synset, const std::string& substance) const;
  // What a particle remover (BEHAVIOR-1K's particleRemover: a rag, a sponge)
  // does with `substance` (synsets): nullopt where it cannot remove it (its
  // conditions name it with null, or name nothing for its kind); else the
  // solvents it must be saturated with one of (none: as it is). OmniGibson's
  // rule: the substance's own conditions, else the remover's default for the
  // substance's kind (default_fluid_conditions for a liquid,
  // default_visual_conditions for a visual substance, else
  // default_non_fluid_conditions). The planner's wipe and the world's
  // cleaning both read it.
  std::optional<std::vector<std::string>> remover_solvents(const std::string& remover,
                                                           const std::string& substance) const;

 private:
  struct Synset {
    std::vector<std::string> parents, children, ancestors;
    Properties properties;
    TextParameters texts;
    unsigned states = 0;  // bit i: ExtendedState i
  };
  KnowledgeBase() = default;
  const Synset& find(const std::string& synset) const;
  bool has_any(const std::string& synset, std::initializer_list<const char*> properties) const;

  std::map<std::string, Synset> synsets_;
};

}  // namespace chore
