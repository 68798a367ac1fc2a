// What `chore activity check` checks of one BDDL file on its text, before any
// world: parsed against its dialect's vocabulary (predicates and arities, room
// types, synsets), its goal grounded with the knowledge base's type test, the
// agent's roles (tasks/agent_roles.hpp) and the states :init sets
// (tasks/initial_states.hpp). The command line and the Python package
// (chore.Goal) share it, so "checks" means one thing.
#pragma once

#include <string>

#include "tasks/bddl.hpp"
#include "tasks/goal.hpp"

namespace chore {

struct CheckedActivity {
  Problem problem;
  GroundGoal goal;
};

// chore::Error naming the file (with file:line:col where the text is at fault).
CheckedActivity check_activity(const std::string& file, const Vocabulary& vocabulary);

}  // namespace chore
