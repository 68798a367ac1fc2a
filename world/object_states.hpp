// Extended object states (seed Table A.7): what the world keeps for the
// objects whose properties need them (Table A.5); the activity layer says
// which, from the synset knowledge base, through ObjectAbilities. Data only:
// the rules that update them and how they look are in state_rules.hpp.
#pragma once

#include <Eigen/Core>

#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "world/transitions.hpp"

namespace chore {

constexpr double kRoomTemperature = 23.0;  // degrees C

// A heat or cold source (stove, oven, fridge): it drives the temperature of
// objects near it (or inside it) towards its own, at `rate` per second.
struct ThermalSource {
  double temperature = 200;
  double rate = 0.04;     // fraction of the difference closed per second
  double distance = 0.2;  // m from the source's box; 0 with requires_inside
  bool requires_toggled_on = false;
  bool requires_closed = false;
  bool requires_inside = false;
};

// What the world tracks for one object. Thresholds default to BEHAVIOR's.
struct ObjectAbilities {
  bool temperature = false;  // cookable, freezable, burnable, ...
  double cook_temperature = 70, burn_temperature = 200, freeze_temperature = 0;
  double hot_temperature = 40, ignition_temperature = std::numeric_limits<double>::infinity();
  bool soakable = false;
  bool cleaning_tool = false;  // iGibson's: dust as it is, stains soaked in water
  // BEHAVIOR-1K's particle removers (a rag, a sponge): per substance of the
  // activity it removes, the solvents it must be saturated with one of (none:
  // as it is), KnowledgeBase::remover_solvents as the activity binds it.
  std::map<std::string, std::vector<std::string>> removes;
  bool covered = false;  // dirt (dustyable, stainable) can lie on it
  bool toggleable = false;
  bool sliceable = false, slicer = false;
  bool breakable = false;
  double break_force = 100;  // N of contact force (with one other object, over their contacts)
  double slice_force = 10;   // N (seed: F_sliced)
  std::optional<ThermalSource> heat_source, cold_source;
  bool holds_liquid = false;  // a container or source of water (sink, bucket)
  // A particle source (a sink's tap): the substance it gives while toggled
  // on, which it then holds (filled); "" for none.
  std::string source;
};

// A kind of dirt: stains need a soaked cleaning tool, dust any cleaning tool.
struct Substance {
  std::string name;
  bool needs_soaked_tool = false;
};

struct ObjectState {
  double temperature = kRoomTemperature, max_temperature = kRoomTemperature;
  std::map<std::string, double> soaked;                      // per liquid, 0 .. 1 absorbed (1 = saturated)
  // What a container (holds_liquid) holds: per substance, up to this
  // fraction of its inner height (several at once: a recipe's ingredients).
  std::map<std::string, double> contents;
  std::map<std::string, std::vector<Eigen::Vector3d>> dirt;  // particles in the object's frame
  std::map<std::string, int> dirt_sampled;                   // how many particles each substance was sampled with
  bool toggled = false;
  int toggle_steps = 0;  // consecutive env steps the hand is at the toggle point
  bool sliced = false, broken = false;
  // A machine (ObjectStates::machines()) has processed its contents since it
  // was turned on: it processes them once each time it is.
  bool machine_ran = false;

  // How high the contents reach, all together.
  double level() const;
  // What the container holds most of ("" for nothing): what a dip soaks in.
  std::string main_substance() const;
};

// What sampling the state `predicate` on an object needs of it: "" when
// `abilities` keep it, else what it lacks, as the samplers' errors name it
// ("SoakedLevel", "Temperature", "an ignition temperature (not flammable)").
// Predicates that set no state of the object (placements, inroom, open) need
// nothing here. The samplers refuse what this names; the activity layer
// checks it on the problem's text first.
std::string missing_for_state(const std::string& predicate, const ObjectAbilities& abilities);

class ObjectStates {
 public:
  // Thresholds of the predicates on these states.
  static constexpr int kCoveredParticles = 5;  // covered (OmniGibson) while at least this many remain
  static constexpr double kDirtyFraction =
      0.5;  // stained/dusty (iGibson) while more than this share of the sampled remain
  static constexpr double kSoakedLevel = 0.5;
  static constexpr double kSaturatedLevel = 1.0;
  // filled from a fifth of the inner height up (OmniGibson's VOLUME_FILL_PROPORTION);
  // contains from any amount.
  static constexpr double kFilledLevel = 0.2;
  // How full a particle source keeps itself while on (and a container dipped in fills).
  static constexpr double kSourceLevel = 0.8;
  static constexpr double kToggleDistance = 0.1;  // m from the toggle point
  static constexpr int kToggleSteps = 5;
  // m/s: a hand faster than this passes the toggle point, it does not press
  // it (a tuck sweeping back past a tap just turned on).
  static constexpr double kToggleSpeed = 0.05;
  static constexpr double kCleaningRadius = 0.06;  // m around a tool's contact

  void configure(int object, const ObjectAbilities& abilities);
  void add_substance(const Substance& substance);
  const ObjectAbilities* abilities(int object) const;  // nullptr: nothing tracked
  const Substance* substance(const std::string& name) const;

  ObjectState& state(int object) { return states_.at(object); }
  const ObjectState& state(int object) const { return states_.at(object); }
  bool tracked(int object) const { return states_.count(object) > 0; }

  // The transitions the world makes (world/transitions.hpp), and the machines
  // that make sludge of what no transition takes.
  void add_transition(Transition transition);
  const std::vector<Transition>& transitions() const { return transitions_; }
  void add_machine(int object) { machines_.insert(object); }
  const std::set<int>& machines() const { return machines_; }
  void add_washer(Washer washer) { washers_.push_back(std::move(washer)); }
  const std::vector<Washer>& washers() const { return washers_; }
  // Per transition, the env steps its condition has held in a row.
  std::vector<int>& transition_progress() { return progress_; }
  // Where the hand was at the last env step (none after a reset): how fast
  // it moves at a toggle point.
  std::optional<Eigen::Vector3d>& last_hand() { return last_hand_; }

  // Back to room temperature, dry, clean, off, whole; no transition under way.
  void reset();
  // Every tracked object's abilities and states, by object index.
  const std::map<int, ObjectAbilities>& all_abilities() const { return abilities_; }
  std::map<int, ObjectState>& all_states() { return states_; }
  const std::map<int, ObjectState>& all_states() const { return states_; }

 private:
  std::map<int, ObjectAbilities> abilities_;
  std::map<int, ObjectState> states_;
  std::map<std::string, Substance> substances_;
  std::vector<Transition> transitions_;
  std::vector<int> progress_;
  std::optional<Eigen::Vector3d> last_hand_;
  std::set<int> machines_;
  std::vector<Washer> washers_;
};

}  // namespace chore
