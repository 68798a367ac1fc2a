// What an activity's :init asks the state samplers to set, checked against
// what the knowledge base says its objects keep (Table A.5's properties ->
// Table A.7's states), on the problem's text at `activity check` time and
// before instantiation, rather than found by the sampler: (saturated
// aluminum_foil.n.01_1 water.n.06_1) names a foil, and no foil soaks.
#pragma once

#include <string>
#include <vector>

#include "tasks/bddl.hpp"
#include "tasks/knowledge_base.hpp"
#include "world/object_states.hpp"

namespace chore {

// What the world keeps for an object of `synset` (world/object_states.hpp),
// from `kb`; a container the activity fills is made a holder by the activity.
ObjectAbilities synset_abilities(const KnowledgeBase& kb, const std::string& synset);

// The state predicates :init makes true of `instance`: those whose states the
// object must keep (filled and contains are not among them: what :init fills
// holds a liquid; nor are negations: a state not kept reads false, so its
// negation holds).
std::vector<std::string> states_set_on(const Problem& problem, const std::string& instance);

// `synset` when it keeps every state `predicates` set (missing_for_state);
// else the first of its leaf descendants, by name, that does (the kind a scene
// analog models an abstract synset as); "" when none does.
std::string kind_keeping(const KnowledgeBase& kb, const std::string& synset,
                         const std::vector<std::string>& predicates);

// chore::Error naming the file, :init and the literal when no kind of an
// object keeps what :init sets on it (kind_keeping is ""), or :init opens an
// object of which no kind is openable. Synsets `kb` does not know and
// substances are left to the checks that report them.
void check_initial_states(const Problem& problem, const KnowledgeBase& kb);

}  // namespace chore
