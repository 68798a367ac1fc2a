// An activity as the task planner sees it: its objects as the knowledge base
// describes them, its :init as a set of ground literals, and the steps the
// world takes by itself once their conditions hold (the knowledge base's
// transition rules, heat and cold, particle sources, cooling at room
// temperature). The primitives' own steps come from their symbolic models
// (primitives/symbolic_model.hpp).
//
// Literals are BEHAVIOR-1K's (the omnigibson dialect's). BEHAVIOR-100's
// dialect is read in those terms: (stained x) is (covered x stain.n.01),
// (dusty x) (covered x dust.n.01), (soaked x) (saturated x water.n.06),
// (onfloor x floor) (ontop x floor); its cleaning tools remove dust as they
// are and stains soaked with water, as chore's world does.
//
// The planner's own predicates, beside BDDL's and the robot's (kHandEmpty,
// kWithinReach): (heated x) x is where a heat source that works heats it,
// directly or through what it lies on or in; (chilled x) the same for a cold
// source.
#pragma once

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "primitives/symbolic_model.hpp"
#include "tasks/bddl.hpp"
#include "tasks/knowledge_base.hpp"
#include "tasks/transition_rules.hpp"

namespace chore {

inline constexpr const char* kHeated = "heated";
inline constexpr const char* kChilled = "chilled";

struct SymbolicProblem {
  // The :objects in order (the first `declared`); then, for BEHAVIOR-100's
  // dialect, the substances its predicates imply (stain.n.01, dust.n.01,
  // water.n.06) where not declared; then an agent where none is declared.
  // (What the rules make on the way to the activity's future objects, an
  // onion's halves before it is diced, the loaders declare:
  // tasks/intermediates.hpp.)
  std::vector<SymbolicObject> objects;
  int declared = 0;
  std::set<SymbolicLiteral> init;
  std::vector<SymbolicStep> world_steps;
  // Index of a BDDL instance (or a synthesised substance's synset), -1 if none.
  int index(const std::string& instance) const;
};

// `kb` is the problem's dialect's knowledge base; `rules` BEHAVIOR-1K's
// transition rules, applied to the omnigibson dialect (BEHAVIOR-100 has none).
SymbolicProblem symbolic_problem(const Problem& problem, const KnowledgeBase& kb, const TransitionRules& rules);

// A BDDL literal on the problem's instances in the planner's terms (the
// `negated` flag is left to the caller); nullopt when an argument is not one
// of the problem's objects (a room).
std::optional<SymbolicLiteral> symbolic_literal(const SymbolicProblem& problem, const Literal& literal);

}  // namespace chore
