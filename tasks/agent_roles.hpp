// The roles the agent (synset agent.n.01) may play in an activity: what the
// samplers and predicate checkers handle, checked on the problem's text (at
// `activity check` time and before instantiation) rather than discovered
// inside the simulator. The agent is the robot, not an object: it stands on
// a floor or an object ((ontop agent.n.01_1 floor.n.01_1), BEHAVIOR-100's
// onfloor), is in a room (inroom), grasps ((grasped agent.n.01_1 x)) and holds
// ((attached x agent.n.01_1)). Nothing is on, in or under it, and it has no
// object states (open, cooked, covered, ...). The corpora use the first
// alone: 820 (ontop agent floor) and 101 (onfloor agent floor).
#pragma once

#include "tasks/bddl.hpp"
#include "tasks/goal.hpp"

namespace chore {

// chore::Error naming the file, the section (:init or :goal) and the literal
// where the agent plays another role.
void check_agent_roles(const Problem& problem, const GroundGoal& goal);

}  // namespace chore
