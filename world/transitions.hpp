// Transitions: what the world makes of objects and substances by itself,
// OmniGibson's transition rules (slicing, dicing, melting, cooking, toggled
// machines, mixing tools, washers and dryers). The activity layer binds the knowledge base's
// rules to one activity's objects (tasks/activity_transitions.hpp); this
// layer knows only objects, substances and the conditions below.
//
// A transition fires when its trigger holds with its inputs where it needs
// them, for `steps` env steps in a row: its input objects become hidden
// (World::hide), its input substances leave the place, its output objects are
// revealed where the first input was (side by side), and its output
// substances go into the place, or where the input object was: into the
// container it was in, else onto what it lay on (covered).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace chore {

class World;

// clang-format off
#define CHORE_TRANSITION_TRIGGERS(X)                                                    \
  X(sliced)   /* the input object was cut (slicing, dicing) */                          \
  X(melted)   /* the input object's highest temperature reached `temperature` */       \
  X(heated)   /* the inputs on or in a place a heat source acts on (cooking) */         \
  X(machine)  /* the inputs in a place as it is toggled on (blender, coffee maker) */   \
  X(stirred)  /* a mixing tool touches or is in the place that holds the inputs */
// clang-format on

#define CHORE_TRANSITION_TRIGGER_ENUM(name) name,
enum class TransitionTrigger { CHORE_TRANSITION_TRIGGERS(CHORE_TRANSITION_TRIGGER_ENUM) };
#undef CHORE_TRANSITION_TRIGGER_ENUM
const char* to_string(TransitionTrigger trigger);

// A unary state an input must have (or lack), or an output is given:
// cooked, burnt, frozen, hot, on_fire, sliced, toggled_on, broken.
struct StateOf {
  int object;
  std::string predicate;
  bool value = true;
};

struct Transition {
  std::string name;  // the knowledge base's rule
  TransitionTrigger trigger = TransitionTrigger::sliced;
  std::vector<int> input_objects;             // each real (and, with places, on or in the place)
  std::vector<std::string> input_substances;  // each in the place's contents
  std::vector<StateOf> input_states;
  std::vector<int> places;        // where the inputs must be (containers, machines): any one; none for sliced, melted
  std::vector<int> heat_sources;  // heated: what may heat the place; empty: any heat source
  std::vector<int> tools;         // stirred: the mixing tools
  std::vector<int> output_objects;
  std::vector<std::string> output_substances;
  std::vector<StateOf> output_states;
  // Machines and stirring: the place holds no substance but the inputs
  // (OmniGibson's recipes; what else is there makes sludge).
  bool exact = false;
  double temperature = 0;  // melted: the melting temperature
  int steps = 1;           // consecutive env steps the condition must hold
};

// A washer or a clothes dryer (OmniGibson's WasherRule and DryerRule): while
// it is toggled on and not open it acts on what is inside it, every step. A
// washer takes each substance it removes out of its contents and off what
// is inside it (where the substance needs a solvent, with one of them in its
// contents), then wets what is inside: saturated with water where it soaks,
// else covered with it. A dryer dries what is inside it and lets its water
// out.
struct Washer {
  int object = -1;
  bool dryer = false;
  // The substances a washer removes, each with the solvents of which one
  // must be in its contents (none: always); one absent it never removes.
  std::map<std::string, std::vector<std::string>> removes;
};

// What a machine makes of contents no recipe takes (OmniGibson's sludge).
inline constexpr const char* kSludge = "sludge";

// Evaluates every transition of world.states() and fires those whose
// condition has held for their steps; after each env step (physical) and
// each primitive (symbolic). A machine turned on with contents that no
// transition takes turns its substances into sludge; washers and dryers
// that are on and closed act on what they hold.
void make_transitions(World& world);

// The unary state `predicate` of `object` ("cooked", "sliced", ...); false for
// a predicate that is not one.
bool unary_state(const World& world, const std::string& predicate, int object);

}  // namespace chore
