// libFuzzer target: the simulator's input (issue 54). The input's bytes
// choose a BEHAVIOR-1K activity over the knowledge base: objects (rigid
// bodies, cloths, substances), the floor of a room and the agent, kinematic
// relations between them, object states and substances in :init (the agent
// now and then in a role it may not play), a goal; its text is parsed,
// grounded, instantiated in its scene analog at a seed the bytes give, and
// stepped with low-level actions. What chore cannot do must be a
// chore::Error; a crash (inside MuJoCo too), a sanitizer report, another
// exception or a hang is a finding (scripts/fuzz).
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "analogs/category_models.hpp"
#include "analogs/scene_analogs.hpp"
#include "base/error.hpp"
#include "env/env.hpp"
#include "tasks/vocabulary.hpp"

namespace {

// The input read as choices; past its end every choice is 0.
class Choices {
 public:
  Choices(const uint8_t* data, size_t size) : data_(data), size_(size) {}
  size_t below(size_t n) {  // in [0, n)
    if (n <= 1) return 0;
    size_t v = 0;
    for (int k = 0; k < 2; ++k) v = v << 8 | (at_ < size_ ? data_[at_++] : 0);
    return v % n;
  }
  template <class T>
  const T& pick(const std::vector<T>& from) {
    return from[below(from.size())];
  }

 private:
  const uint8_t* data_;
  size_t size_, at_ = 0;
};

struct Pools {
  std::vector<std::string> objects, cloths, substances;
};

const Pools& pools() {
  static const Pools p = [] {
    Pools p;
    const auto kb = chore::dialect_knowledge_base(chore::Domain::omnigibson);
    for (const std::string& s : kb->synsets()) {
      if (!kb->is_leaf(s) || s == "agent.n.01" || s == "floor.n.01") continue;  // each has its own role
      if (kb->has_property(s, "substance")) {
        p.substances.push_back(s);
      } else if (kb->has_property(s, "deformable")) {
        p.cloths.push_back(s);
      } else if (kb->has_property(s, "rigidBody")) {
        p.objects.push_back(s);
      }
    }
    return p;
  }();
  return p;
}

const std::vector<std::string> kRooms = {"kitchen", "living_room", "bathroom", "bedroom", "dining_room", "garden"};
const std::vector<std::string> kRelations = {"ontop", "inside", "under", "nextto", "overlaid", "draped", "attached",
                                             "touching"};
const std::vector<std::string> kStates = {"cooked", "frozen", "open", "folded", "unfolded", "toggled_on", "hot",
                                          "on_fire", "broken"};
// The state an object of this synset keeps, most of the time (else any:
// what it does not keep must be a chore::Error).
std::string state_of(Choices& c, const std::string& synset) {
  const auto kb = chore::dialect_knowledge_base(chore::Domain::omnigibson);
  std::vector<std::string> kept;
  for (const auto& [state, property] : {std::pair{"cooked", "cookable"}, {"frozen", "freezable"}, {"hot", "heatable"},
                                        {"open", "openable"}, {"toggled_on", "toggleable"}, {"on_fire", "flammable"},
                                        {"broken", "breakable"}, {"folded", "foldable"}}) {
    if (kb->has_property(synset, property)) kept.push_back(state);
  }
  return kept.empty() || c.below(4) == 0 ? c.pick(kStates) : c.pick(kept);
}
const std::vector<std::string> kSubstanceRelations = {"covered", "filled", "saturated", "contains", "insource"};

std::string literal(const std::string& predicate, const std::vector<std::string>& args, bool negated) {
  std::string text = "(" + predicate;
  for (const std::string& a : args) text += " " + a;
  text += ")";
  return negated ? "(not " + text + ")" : text;
}

std::string activity_text(Choices& c) {
  const Pools& p = pools();
  std::vector<std::pair<std::string, std::string>> objects;  // instance, synset
  const size_t count = 1 + c.below(4);
  for (size_t i = 0; i < count; ++i) {
    const std::string& synset = c.below(5) == 0 && !p.cloths.empty() ? c.pick(p.cloths) : c.pick(p.objects);
    objects.push_back({synset + "_" + std::to_string(i + 1), synset});
  }
  const std::string substance = c.pick(p.substances);
  const std::string floor = "floor.n.01_1", agent = "agent.n.01_1", stuff = substance + "_1";
  std::vector<std::string> things = {floor, agent};
  for (const auto& o : objects) things.push_back(o.first);

  std::vector<std::string> init = {literal("inroom", {floor, c.pick(kRooms)}, false)};
  init.push_back(c.below(8) == 0 ? literal(c.pick(kRelations), {c.pick(things), c.pick(things)}, false)
                                 : literal("ontop", {agent, floor}, false));
  for (size_t i = 0; i < objects.size(); ++i) {
    const std::string& o = objects[i].first;
    const std::string& under = i == 0 || c.below(3) != 0 ? floor : objects[c.below(i)].first;
    init.push_back(literal(c.below(3) == 0 ? c.pick(kRelations) : "ontop", {o, under}, false));
    if (c.below(2) == 0) init.push_back(literal(state_of(c, objects[i].second), {o}, c.below(3) == 0));
    if (c.below(3) == 0) init.push_back(literal(c.pick(kSubstanceRelations), {o, stuff}, c.below(4) == 0));
  }
  std::vector<std::string> goal;
  for (size_t k = 0, n = 1 + c.below(3); k < n; ++k) {
    goal.push_back(c.below(2) == 0 ? literal(c.pick(kStates), {c.pick(things)}, c.below(2) == 0)
                                   : literal(c.pick(kRelations), {c.pick(things), c.pick(things)}, c.below(2) == 0));
  }

  std::string text = "(define (problem fuzzed-0)\n  (:domain omnigibson)\n  (:objects\n";
  for (const auto& [instance, synset] : objects) text += "    " + instance + " - " + synset + "\n";
  text += "    " + stuff + " - " + substance + "\n    " + floor + " - floor.n.01\n    " + agent + " - agent.n.01\n  )\n";
  text += "  (:init\n";
  for (const std::string& l : init) text += "    " + l + "\n";
  text += "  )\n  (:goal (and";
  for (const std::string& l : goal) text += " " + l;
  return text + "))\n)\n";
}

}  // namespace

// What every input shares, loaded before libFuzzer times the inputs (under
// the sanitizers on a busy machine, the knowledge base's load alone passed
// the 5 s an input has: the first input was reported as a timeout).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  pools();
  chore::CategoryModels::shipped();
  chore::shipped_scene_inventories();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  Choices c(data, size);
  const std::string text = activity_text(c);
  const uint64_t seed = c.below(1000);
  // The activity reaches the env by its path, as a user's file does.
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("chore_activity_fuzz_" + std::to_string(::getpid()) + ".bddl");
  std::ofstream(file, std::ios::trunc) << text;
  try {
    chore::EnvConfig config;
    config.activity = file.string();
    config.observations = {"proprio"};
    config.reachable_instances = false;
    chore::Env env(config);
    env.reset(seed);
    const size_t n = env.action_space().element_count();
    for (int step = 0; step < 5; ++step) {
      std::vector<float> action(n);
      for (float& a : action) a = static_cast<float>(c.below(201)) / 100.0f - 1.0f;
      const chore::Env::StepResult r = env.step(action);
      if (r.terminated || r.truncated) env.reset(seed + 1);
    }
  } catch (const chore::Error&) {
  }
  return 0;
}
