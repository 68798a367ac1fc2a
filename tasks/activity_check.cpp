#include "tasks/activity_check.hpp"

#include "tasks/agent_roles.hpp"
#include "tasks/initial_states.hpp"
#include "tasks/intermediates.hpp"
#include "tasks/vocabulary.hpp"

namespace chore {

CheckedActivity check_activity(const std::string& file, const Vocabulary& vocabulary) {
  Problem p = load_bddl(file, {.vocabulary = &vocabulary});
  const auto kb = dialect_knowledge_base(p.domain);
  declare_intermediates(p, *kb, behavior_transition_rules());
  GroundGoal goal = ground_goal(p);
  check_agent_roles(p, goal);
  check_initial_states(p, *kb);
  return {std::move(p), std::move(goal)};
}

}  // namespace chore
