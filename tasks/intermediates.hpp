// What the knowledge base's rules make on the way to an activity's future
// objects without the activity declaring it: chop_an_onion declares the onion
// and its diced pieces, and the halves that slicing makes of the onion
// (dicing's input) come in between, as OmniGibson creates them. Each such
// synset, a rule's input that the activity has nothing of (no object whose
// type is-a it) and some rule makes, up to kIntermediateDepth rules back from
// a future object, is declared as one more object, SYNSET_made, future at
// :init: the scene has it hidden until a transition makes it (analogs/), the
// world's transitions bind it like a declared one (tasks/activity.hpp), and
// the primitive action space and the planner act on it.
#pragma once

#include "tasks/bddl.hpp"
#include "tasks/knowledge_base.hpp"
#include "tasks/transition_rules.hpp"

namespace chore {

inline constexpr int kIntermediateDepth = 3;
inline constexpr const char* kIntermediateSuffix = "_made";

// BEHAVIOR-1K's dialect only (BEHAVIOR-100 has no transition rules); `kb` is
// the problem's. Declared once: objects already named SYNSET_made are kept.
void declare_intermediates(Problem& problem, const KnowledgeBase& kb, const TransitionRules& rules);

}  // namespace chore
