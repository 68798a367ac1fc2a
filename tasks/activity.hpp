// An activity: a BDDL problem bound to a scene's objects. Loaded once and
// shared read-only by every environment; instantiate() samples a fresh
// instance of its :init in a world ("infinite activity initialisation") and
// score() evaluates its goal there (success, Q, BEHAVIOR's potential).
//
// Binding (deterministic, in :objects order):
//   agent.n.01       the robot
//   floor.n.01       the floor of the room its (inroom floor ROOM) names
//   a substance      (water.n.06, or the second argument of filled/covered):
//                    not an object, a kind of liquid or dirt
//   anything else    the first unbound scene object whose synset is-a the
//                    declared type (knowledge base), in the room its inroom
//                    names if it has one; objects without inroom must be free
//                    (they are placed by sampling).
// Rooms are named by type in BDDL (living_room) or by scene name (living_room_0).
#pragma once

#include <memory>
#include <set>
#include <string>
#include <vector>

#include "base/random.hpp"
#include "tasks/bddl.hpp"
#include "tasks/goal.hpp"
#include "tasks/knowledge_base.hpp"
#include "tasks/vocabulary.hpp"
#include "world/sampling.hpp"
#include "world/world.hpp"

namespace chore {

struct Binding {
  // future: an object a transition will create, (future X) in :init, for which
  // the scene has no free object of its type to hide until it is made: every
  // literal on it is false but (future X). Future objects the scene has one
  // for are bound as objects, hidden (World::hide) until made.
  enum class Kind { object, floor, agent, substance, future };
  Kind kind = Kind::object;
  int index = -1;  // object: index in scene().objects(); floor: index in scene().rooms()
  // floor: the scene object of synset floor.n.01 in that room, which keeps
  // the floor's states (dust on it), or -1 where the scene has none.
  int object = -1;
  // The scene object whose states it has: an object's own, a floor's object; -1 for none.
  int state_object() const { return kind == Kind::object ? index : kind == Kind::floor ? object : -1; }
};

// The scene an activity is set in (tasks/activities/scenes.json), or "" if
// it names none; and the first activity set in a scene, or "".
std::string activity_scene(const std::string& activity);
std::string scene_activity(const std::string& scene);
// The .bddl file of an activity name (<tasks>/activities/<name>.bddl) or path;
// chore::Error listing the known activities when there is none.
std::string resolve_activity_path(const std::string& name);

class Activity {
 public:
  // `name` is an activity in <tasks>/activities/<name>.bddl, or a path to a
  // .bddl file; without `kb`, its dialect's knowledge base (tasks/vocabulary.hpp).
  // Throws chore::Error naming what cannot be bound and why.
  static std::shared_ptr<const Activity> load(const std::string& name, const Scene& scene,
                                              std::shared_ptr<const KnowledgeBase> kb = nullptr);

  const std::string& name() const { return name_; }
  const Problem& problem() const { return problem_; }
  const GroundGoal& goal() const { return goal_; }
  const Binding& binding(const std::string& instance) const;
  // The scene object bound to a BDDL instance (e.g. "pumpkin.n.02_1").
  int object(const std::string& instance) const;

  // Configures the world's extended states for the bound objects (Table A.5,
  // from the knowledge base). Call once per world.
  void configure(World& world) const;
  // Samples :init in the world, which must be freshly reset, with the
  // samplers' `options` (where the robot reaches). Retries whole
  // instantiations; the last failure throws chore::Error naming the literal.
  void instantiate(World& world, Rng& rng, const SampleOptions& options = {}) const;

  bool holds(const World& world, const GroundLiteral& literal) const;
  // The goal against the world: success and Q, and BEHAVIOR's potential (the
  // fraction of the goal's first option that holds), each literal checked once.
  struct Evaluation {
    Score score;
    double potential = 0;
  };
  Evaluation evaluate(const World& world) const;
  Score score(const World& world) const { return evaluate(world).score; }
  double potential(const World& world) const { return evaluate(world).potential; }

 private:
  Activity() = default;
  bool sample_literal(World& world, const Literal& literal, Rng& rng, const SampleOptions& options) const;
  std::string type_of(const std::string& instance) const;
  std::string liquid_of(const Literal& literal) const;
  int agent_room(const World& world, const Binding& where) const;
  // The knowledge base's transition rules bound to this activity's objects,
  // given to the world (tasks/activity_transitions.cpp).
  void configure_transitions(World& world) const;
  // What knows a scene object's synset: the activity's knowledge base, else
  // BEHAVIOR-1K's, whose synsets scene analogs are built of (a BEHAVIOR-100
  // activity meets their openable_window.n.01).
  const KnowledgeBase& kb_of(const std::string& synset) const;

  std::string name_;
  Problem problem_;
  GroundGoal goal_;
  std::shared_ptr<const KnowledgeBase> kb_;
  std::vector<std::pair<std::string, Binding>> bindings_;  // in :objects order
  std::set<std::string> future_;                           // (future X) in :init
  std::set<std::string> unmade_;                           // of those, bound as Kind::future
  std::vector<Literal> init_order_;                        // :init without inroom, in sampling order
};

}  // namespace chore
