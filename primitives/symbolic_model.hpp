// The primitives' symbolic model: what the task planner (planner/) reasons
// with. Each primitive states its model beside its execution, in its own file
// (primitives/<name>.cpp), so that the two cannot drift apart. The objects are
// an activity's, described by the knowledge base; a state is a set of ground
// literals of BDDL's predicates, plus the robot's own two (kHandEmpty,
// kWithinReach). A step is STRIPS: literals it needs to hold and not to hold,
// then those it deletes and adds.
#pragma once

#include <compare>
#include <map>
#include <string>
#include <vector>

namespace chore {

struct SymbolicObject {
  enum class Kind { object, substance, agent, floor };
  std::string name;    // the BDDL instance, e.g. apple.n.01_1
  std::string synset;  // apple.n.01
  // The knowledge base's properties (openable, toggleable, heatSource, ...)
  // and their numeric parameters (heatSource: requires_toggled_on 1).
  std::map<std::string, std::map<std::string, double>> properties;
  // particleRemover: each substance it removes, with the solvents it must be
  // saturated with to remove it (any one of them; none: as it is).
  std::map<std::string, std::vector<std::string>> removes;
  Kind kind = Kind::object;
  bool fixed = false;  // set in the scene by (inroom ...): furniture, appliances; never picked up
  std::string room;    // a fixed object's or a floor's (inroom ...): BDDL's room type
  bool has(const char* property) const { return properties.count(property) > 0; }
  bool movable() const { return kind == Kind::object && !fixed; }
  double parameter(const char* property, const char* name, double fallback) const;
};

// A ground literal: a predicate over objects (indices into the objects).
struct SymbolicLiteral {
  std::string predicate;
  std::vector<int> args;
  auto operator<=>(const SymbolicLiteral&) const = default;
};

// The robot's own predicates: its hand is empty (no argument); navigate has
// brought the object within the arm's reach (one).
inline constexpr const char* kHandEmpty = "handempty";
inline constexpr const char* kWithinReach = "withinreach";

// What a primitive acts on: its target, what the hand holds (-1: nothing),
// and for a primitive about a substance (dip, wipe) the substance (-1
// otherwise).
struct SymbolicArgs {
  int target = -1, held = -1, substance = -1;
};

struct SymbolicStep {
  std::string name;  // e.g. pick(apple.n.01_1)
  std::vector<SymbolicLiteral> needs, needs_not, deletes, adds;
  // A world step that happens as soon as its conditions hold (a transition
  // rule, a washer), as the world makes it, not when the planner chooses.
  bool at_once = false;
};

// Steps are built with these.
SymbolicLiteral literal(const char* predicate, std::vector<int> args);
// Deletes every relation that says where `object` is (kPlacements, either
// argument), as picking it up ends them.
void end_placements(const std::vector<SymbolicObject>& objects, int object, SymbolicStep& step);

// What the hand holds set down at the target (place, place_next_to,
// place_under, attach, drape): the object held by `agent`, the target within
// reach and real; then the hand empty, and `adds`.
SymbolicStep setting_down(int agent, const SymbolicArgs& args, std::vector<SymbolicLiteral> adds);

// `step` on `object` out of what opens (a cabinet, a fridge, a jar) only
// while that is open: shut, it is in the way of the hand. The step for an
// object in none of them, and one for each it may lie in.
std::vector<SymbolicStep> only_while_open(const std::vector<SymbolicObject>& objects, int object,
                                          const SymbolicStep& step);

// The first agent among the objects (the planner adds one where the activity
// declares none).
int agent_index(const std::vector<SymbolicObject>& objects);

// The relations that say where an object is; picking it up ends them all
// (an attached object comes off).
inline constexpr const char* kPlacements[] = {"ontop",    "inside", "nextto",  "under",   "touching",
                                              "overlaid", "draped", "onfloor", "attached"};

}  // namespace chore
