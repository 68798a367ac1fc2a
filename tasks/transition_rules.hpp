// The knowledge base's transition rules (BEHAVIOR-1K appendix B.3; OmniGibson's
// transition_rules.py): what slicing, dicing, melting, cooking, toggled
// machines, mixing tools and washers turn which synsets into. Read from
// <kb>/transition_map/*.json (StanfordVL/bddl data, MIT, see LICENSE-bddl),
// one file a family; never a hand-written recipe table. Loaded once and shared
// read-only, like the KnowledgeBase.
//
//   auto rules = TransitionRules::load();
//   for (const TransitionRule* r : rules->producing("half__apple.n.01")) ...
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tasks/knowledge_base.hpp"

namespace chore {

// The rule families, one transition_map file each, and how OmniGibson fires
// them (what must hold besides the inputs being real):
//   slicing, dicing     a slicer touches the (sliceable, diceable) input
//   melting             the input reaches its melting temperature
//   heat_cook           the inputs in a container on or in a heat source that heats
//   substance_cooking,  the input substance in a container that a heat source heats
//   substance_watercooking
//   single_toggleable_machine  the inputs inside the machine when it is toggled on
//   mixing_stick        a mixing tool touches the inputs in a container
//   washer_particleremover, washer_nonparticleremover
//                       the washed item inside a washer toggled on
// clang-format off
#define CHORE_TRANSITION_FAMILIES(X) \
  X(slicing) X(dicing) X(melting) X(heat_cook) X(substance_cooking) X(substance_watercooking) \
  X(single_toggleable_machine) X(mixing_stick) X(washer_particleremover) X(washer_nonparticleremover)
// clang-format on

#define CHORE_TRANSITION_FAMILY_ENUM(name) name,
enum class TransitionFamily { CHORE_TRANSITION_FAMILIES(CHORE_TRANSITION_FAMILY_ENUM) };
#undef CHORE_TRANSITION_FAMILY_ENUM
const char* to_string(TransitionFamily family);

// A synset and how many of it (an object count, or 1 for a substance).
struct SynsetCount {
  std::string synset;
  int count = 1;
};

// A state the rule asks of its inputs or gives its outputs: (cooked X) false,
// (covered X Y) true, (ontop X Y) true.
struct StateCondition {
  std::string predicate;
  std::vector<std::string> synsets;
  bool value = true;
};

struct TransitionRule {
  TransitionFamily family;
  std::string name;
  std::vector<SynsetCount> inputs, outputs;  // sorted by synset
  std::vector<StateCondition> input_states, output_states;
  std::vector<SynsetCount> containers, heat_sources, machines, washed_items;  // any of each list
  std::optional<int> timesteps;
};

// The machines of OmniGibson's WasherRule and DryerRule (its category
// filters "washer" and "clothes_dryer"): the washer rules name the washer as
// their machine; no file names the dryer.
inline constexpr const char* kWasher = "washer.n.03";
inline constexpr const char* kClothesDryer = "clothes_dryer.n.01";

class TransitionRules;
// BEHAVIOR-1K's rules (TransitionRules::load()), loaded on first use and kept.
const TransitionRules& behavior_transition_rules();

class TransitionRules {
 public:
  // Reads <dir>/transition_map/<family>.json for every family and
  // <dir>/transition_map/washer.json. Bad files throw chore::Error naming the
  // file, the rule and the field; with `kb`, a synset it does not know is one.
  static std::shared_ptr<const TransitionRules> load(const std::string& dir = default_tasks_dir() + "/kb/behavior-1k",
                                                     const KnowledgeBase* kb = nullptr);
  TransitionRules(const TransitionRules&) = delete;
  TransitionRules& operator=(const TransitionRules&) = delete;

  const std::vector<TransitionRule>& rules() const { return rules_; }
  // Rules with `synset` among their outputs, or among their inputs.
  std::vector<const TransitionRule*> producing(const std::string& synset) const;
  std::vector<const TransitionRule*> consuming(const std::string& synset) const;
  // washer.json (OmniGibson's WasherRule cleaning conditions): whether a
  // washer removes `substance` from what it washes: nullopt never
  // (rust.n.01); an empty list always (dust.n.01, and, as OmniGibson's
  // default, every substance the file does not name); else when one of the
  // listed solvents is in the washer too.
  std::optional<std::vector<std::string>> washer_solvents(const std::string& substance) const;

 private:
  TransitionRules() = default;
  std::vector<TransitionRule> rules_;
  std::multimap<std::string, size_t> producing_, consuming_;
  std::map<std::string, std::optional<std::vector<std::string>>> washer_solvents_;  // nullopt: never
};

}  // namespace chore
