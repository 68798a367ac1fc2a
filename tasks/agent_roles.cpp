#include "tasks/agent_roles.hpp"

#include <set>
#include <string>

#include "base/error.hpp"

namespace chore {

namespace {

// The argument positions where a predicate takes the agent.
bool agent_may_be(const std::string& predicate, size_t position, size_t arity) {
  if (predicate == "ontop" || predicate == "onfloor") return position == 0 && arity == 2;
  if (predicate == "inroom" || predicate == "grasped") return position == 0 && arity == 2;
  if (predicate == "attached") return position == 1 && arity == 2;
  return false;
}

void check(const Literal& l, const std::set<std::string>& agents, const std::string& where) {
  for (size_t i = 0; i < l.args.size(); ++i) {
    if (!agents.count(l.args[i]) || agent_may_be(l.predicate, i, l.args.size())) continue;
    throw Error(where + ": " + to_bddl(l) + ": '" + l.args[i] +
                "' is the agent (the robot), not an object: it may stand on a floor or an object "
                "(ontop/onfloor AGENT X), be in a room (inroom), grasp (grasped AGENT X) and hold "
                "(attached X AGENT), nothing else");
  }
}

}  // namespace

void check_agent_roles(const Problem& problem, const GroundGoal& goal) {
  std::set<std::string> agents;
  for (const ObjectDecl& d : problem.objects) {
    if (d.type == "agent.n.01") agents.insert(d.name);
  }
  if (agents.empty()) return;
  for (const Literal& l : problem.init) check(l, agents, problem.file + ": :init");
  for (const GroundLiteral& l : goal.literals) check(l, agents, problem.file + ": :goal");
}

}  // namespace chore
