#include "tasks/activity.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "base/error.hpp"
#include "base/json_file.hpp"
#include "tasks/agent_roles.hpp"
#include "tasks/initial_states.hpp"
#include "tasks/intermediates.hpp"
#include "world/object_geometry.hpp"
#include "world/predicates.hpp"
#include "world/sampling.hpp"

namespace fs = std::filesystem;

namespace chore {
namespace {

// The binary predicates between two objects, by BDDL name.
const std::map<std::string, bool (*)(const World&, int, int), std::less<>> kObjectRelations = {
    {"ontop", ontop},       {"inside", inside},         {"under", under},       {"nextto", nextto},
    {"touching", touching}, {"insameroom", insameroom}, {"overlaid", overlaid}, {"draped", draped}};

constexpr int kInstantiationAttempts = 10;

// Predicates chore can check, by their BDDL names (both dialects).
const std::set<std::string> kKinematic = {"ontop",  "inside",   "under",    "onfloor",
                                          "nextto", "touching", "overlaid", "draped"};
const std::set<std::string> kUnaryStates = {"cooked", "burnt",      "frozen", "hot",   "on_fire",
                                            "soaked", "toggled_on", "sliced", "broken"};
const std::set<std::string> kOther = {"inroom",   "open",     "saturated", "covered", "filled",  "contains",   "dusty",
                                      "stained",  "grasped",  "inhand",    "infov",   "inreach", "insameroom", "folded",
                                      "unfolded", "attached", "insource",  "future",  "real"};
// Second arguments that name a substance rather than an object.
const std::set<std::string> kSubstanceArgument = {"covered", "filled", "contains", "saturated", "insource"};

bool room_matches(const Room& room, const std::string& bddl_room) {
  return room.type == bddl_room || room.name == bddl_room;
}

}  // namespace

std::string resolve_activity_path(const std::string& name) {
  if (name.ends_with(".bddl") || name.find('/') != std::string::npos) {
    if (!fs::exists(name)) throw Error("activity file '" + name + "' does not exist");
    return name;
  }
  const fs::path dir = fs::path(default_tasks_dir()) / "activities";
  const fs::path path = dir / (name + ".bddl");
  if (fs::exists(path)) return path.string();
  std::string known;
  if (fs::is_directory(dir)) {
    for (const auto& e : fs::directory_iterator(dir)) {
      if (e.path().extension() == ".bddl") known += (known.empty() ? "" : ", ") + e.path().stem().string();
    }
  }
  throw Error("unknown activity '" + name + "' (no " + path.string() +
              "); known activities: " + (known.empty() ? "none" : known));
}

namespace {

// tasks/activities/scenes.json: activity name -> scene name.
std::vector<std::pair<std::string, std::string>> activity_scenes() {
  const fs::path path = fs::path(default_tasks_dir()) / "activities" / "scenes.json";
  const nlohmann::json json = read_json_file(path.string());
  const JsonReader reader(json, path.string());
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [activity, _] : json.items()) out.emplace_back(activity, reader.string(activity.c_str()));
  return out;
}

}  // namespace

std::string activity_scene(const std::string& activity) {
  const std::string key = fs::path(activity).stem().string();
  for (const auto& [a, s] : activity_scenes()) {
    if (a == key) return s;
  }
  return "";
}

std::string scene_activity(const std::string& scene) {
  for (const auto& [a, s] : activity_scenes()) {
    if (s == scene) return a;
  }
  return "";
}

std::shared_ptr<const Activity> Activity::load(const std::string& name, const Scene& scene,
                                               std::shared_ptr<const KnowledgeBase> kb) {
  const std::string path = resolve_activity_path(name);
  std::shared_ptr<Activity> a(new Activity());
  const Vocabulary vocabulary = load_vocabulary(kb);
  a->problem_ = load_bddl(path, {.vocabulary = &vocabulary});
  // BEHAVIOR-1K keeps an activity's instances as NAME/problemN.bddl: its name is the folder's.
  const fs::path file(path);
  const std::string stem = file.stem().string();
  const bool instance = stem.size() > 7 && stem.starts_with("problem") &&
                        std::all_of(stem.begin() + 7, stem.end(), [](char c) { return c >= '0' && c <= '9'; });
  a->name_ = instance && file.has_parent_path() ? file.parent_path().filename().string() : file.stem().string();
  a->kb_ = kb ? std::move(kb) : dialect_knowledge_base(a->problem_.domain);
  declare_intermediates(a->problem_, *a->kb_, behavior_transition_rules());
  const std::string where = "activity '" + a->name_ + "' in scene '" + scene.name() + "'";

  std::map<std::string, std::string> rooms;  // instance -> BDDL room
  std::set<std::string> substances, placed;
  auto check_predicate = [&](const Literal& l) {
    if (!kKinematic.count(l.predicate) && !kUnaryStates.count(l.predicate) && !kOther.count(l.predicate)) {
      throw Error(path + ": unsupported predicate '" + l.predicate + "' in " + to_bddl(l));
    }
    if (kSubstanceArgument.count(l.predicate) && l.args.size() >= 2) substances.insert(l.args[1]);
  };
  for (const Literal& l : a->problem_.init) {
    check_predicate(l);
    if (l.predicate == "inroom" && l.args.size() == 2) rooms[l.args[0]] = l.args[1];
    if (kKinematic.count(l.predicate) && !l.args.empty()) placed.insert(l.args[0]);
  }
  a->goal_ = ground_goal(a->problem_);
  for (const GroundLiteral& l : a->goal_.literals) check_predicate(l);
  check_agent_roles(a->problem_, a->goal_);
  check_initial_states(a->problem_, *a->kb_);

  for (const Literal& l : a->problem_.init) {
    if (l.predicate == "future" && !l.negated && l.args.size() == 1) a->future_.insert(l.args[0]);
  }
  // The object bound to an instance keeps the states :init sets on it (of an
  // abstract synset's kinds, the analog models one that does), and has joints
  // if :init opens it: the samplers get only what they can set.
  std::set<std::string> opened;
  for (const Literal& l : a->problem_.init) {
    if (l.predicate == "open" && !l.negated && l.args.size() == 1) opened.insert(l.args[0]);
  }
  // `states`: what :init sets on the instance (states_set_on), found once per declaration.
  const auto lacks = [&](const SceneObject& o, const std::string& instance,
                         const std::vector<std::string>& states) -> std::string {
    const ObjectAbilities ab = synset_abilities(a->kb_of(o.synset), o.synset);
    for (const std::string& predicate : states) {
      if (std::string missing = missing_for_state(predicate, ab); !missing.empty()) return "keeps no " + missing;
    }
    return o.joints.empty() && opened.count(instance) ? "no joints to open" : "";
  };
  std::vector<bool> taken(scene.objects().size(), false);
  for (const ObjectDecl& decl : a->problem_.objects) {
    Binding b;
    const auto room = rooms.find(decl.name);
    const bool substance_type =
        !placed.count(decl.name) && a->kb_->contains(decl.type) && a->kb_->is_substance(decl.type);
    if (a->future_.count(decl.name) && !substances.count(decl.name) && !substance_type) {
      // An object a transition makes: a free scene object of its type, hidden
      // until then (the scene analogs make one); where the scene has none, no
      // transition can make it.
      b.kind = Binding::Kind::future;
      for (size_t i = 0; i < scene.objects().size() && b.index < 0; ++i) {
        const SceneObject& o = scene.objects()[i];
        const KnowledgeBase& kb = a->kb_of(o.synset);
        if (taken[i] || o.fixed || o.grasp_weld < 0 || !kb.contains(o.synset) || !kb.contains(decl.type) ||
            !kb.is_a(o.synset, decl.type))
          continue;
        b.kind = Binding::Kind::object;
        b.index = static_cast<int>(i);
        taken[i] = true;
      }
    } else if (decl.type == "agent.n.01") {
      if (!scene.has_robot()) throw Error(where + ": " + decl.name + " needs the robot");
      b.kind = Binding::Kind::agent;
    } else if (decl.type == "floor.n.01") {
      if (room == rooms.end()) throw Error(where + ": " + decl.name + " has no (inroom ...) literal");
      for (size_t r = 0; r < scene.rooms().size() && b.index < 0; ++r) {
        if (room_matches(scene.rooms()[r], room->second)) b.index = static_cast<int>(r);
      }
      if (b.index < 0) throw Error(where + ": no room '" + room->second + "' for " + decl.name);
      b.kind = Binding::Kind::floor;
      // Floors of one room (floor.n.01_1 and floor.n.01_* in a garden) share its object.
      for (size_t i = 0; i < scene.objects().size() && b.object < 0; ++i) {
        const SceneObject& o = scene.objects()[i];
        if (o.synset == "floor.n.01" && scene.room_at(o.pos[0], o.pos[1]) == &scene.rooms()[b.index])
          b.object = static_cast<int>(i);
      }
    } else if (substances.count(decl.name) ||
               // What :init places is an object, whatever the knowledge base
               // (BEHAVIOR-100's soap on a shelf; its knowledge base calls soap a liquid).
               substance_type) {
      b.kind = Binding::Kind::substance;
    } else {
      a->kb_->is_a(decl.type, decl.type);  // an unknown synset is an error here
      const std::vector<std::string> states = states_set_on(a->problem_, decl.name);
      std::string seen;
      for (size_t i = 0; i < scene.objects().size() && b.index < 0; ++i) {
        const SceneObject& o = scene.objects()[i];
        const KnowledgeBase& kb = a->kb_of(o.synset);
        if (taken[i] || !kb.contains(o.synset) || !kb.contains(decl.type) || !kb.is_a(o.synset, decl.type)) continue;
        if (room != rooms.end()) {
          const Room* r = scene.room_at(o.pos[0], o.pos[1]);
          if (!r || !room_matches(*r, room->second)) {
            seen += (seen.empty() ? "" : ", ") + o.name + " (in " + (r ? r->name : "no room") + ")";
            continue;
          }
        } else if (o.fixed) {
          seen += (seen.empty() ? "" : ", ") + o.name + " (fixed: cannot be placed)";
          continue;
        }
        if (const std::string why = lacks(o, decl.name, states); !why.empty()) {
          seen += (seen.empty() ? "" : ", ") + o.name + " (" + why + ")";
          continue;
        }
        b.index = static_cast<int>(i);
        taken[i] = true;
      }
      if (b.index < 0) {
        throw Error(where + ": no scene object for " + decl.name + " (" + decl.type + ")" +
                    (room != rooms.end() ? " in " + room->second : std::string(" that is free")) +
                    (seen.empty() ? "" : "; of that type: " + seen));
      }
    }
    if (b.kind == Binding::Kind::future) a->unmade_.insert(decl.name);
    a->bindings_.emplace_back(decl.name, b);
  }

  // Sampling order: joint states, then placements, then the other states
  // (objects must be where they end up before dirt is laid on them).
  // Placements go support first, as BEHAVIOR's sampler does: a plate onto
  // the table before the food onto the plate, which would otherwise stay
  // behind when the plate moves.
  std::map<std::string, std::string> support;  // object -> what a placement puts it on, in or by
  for (const Literal& l : a->problem_.init) {
    if (!l.negated && kKinematic.count(l.predicate) && l.args.size() == 2) support.emplace(l.args[0], l.args[1]);
  }
  auto depth = [&](std::string object) {  // supports below it; a cycle stops at their count
    size_t d = 0;
    for (auto it = support.find(object); it != support.end() && d <= support.size(); it = support.find(object)) {
      object = it->second;
      ++d;
    }
    return d;
  };
  // Future objects leave the world first: nothing is placed against them.
  auto rank = [](const Literal& l) {
    return l.predicate == "future" || l.predicate == "open" ? 0 : kKinematic.count(l.predicate) ? 1 : 2;
  };
  auto key = [&](const Literal& l) {
    const size_t below = rank(l) == 1 && l.args.size() == 2 ? depth(l.args[1]) : 0;
    return std::pair(rank(l), below);
  };
  for (const Literal& l : a->problem_.init) {
    if (l.predicate != "inroom") a->init_order_.push_back(l);
  }
  std::stable_sort(a->init_order_.begin(), a->init_order_.end(),
                   [&](const Literal& x, const Literal& y) { return key(x) < key(y); });
  return a;
}

const KnowledgeBase& Activity::kb_of(const std::string& synset) const {
  return kb_->contains(synset) ? *kb_ : *dialect_knowledge_base(Domain::omnigibson);
}

const Binding& Activity::binding(const std::string& instance) const {
  for (const auto& [name, b] : bindings_) {
    if (name == instance) return b;
  }
  throw Error("activity '" + name_ + "': no object '" + instance + "'");
}

int Activity::object(const std::string& instance) const {
  const Binding& b = binding(instance);
  if (b.kind != Binding::Kind::object)
    throw Error("activity '" + name_ + "': '" + instance + "' is not a scene object");
  return b.index;
}

void Activity::configure(World& world) const {
  const Scene& scene = world.scene();
  std::set<int> liquid_holders;
  // What the activity fills, or asks to contain something, holds a liquid level.
  const auto holder = [&](const auto& l) {
    if ((l.predicate == "filled" || l.predicate == "contains") && binding(l.args.at(0)).kind == Binding::Kind::object)
      liquid_holders.insert(object(l.args[0]));
  };
  for (const Literal& l : problem_.init) {
    if (!l.negated) holder(l);
  }
  for (const GroundLiteral& l : goal_.literals) holder(l);
  // The activity's substances, for what BEHAVIOR-1K's removers do with them.
  std::set<std::string> substances;
  for (const ObjectDecl& d : problem_.objects) {
    if (kb_of(d.type).contains(d.type) && kb_of(d.type).is_substance(d.type)) substances.insert(d.type);
  }
  for (const auto& [instance, b] : bindings_) {
    const int index = b.state_object();
    if (index < 0) continue;
    const std::string& s = scene.objects()[index].synset;
    const KnowledgeBase& kb = kb_of(s);
    ObjectAbilities ab = synset_abilities(kb, s);
    ab.holds_liquid = ab.holds_liquid || liquid_holders.count(index);
    if (problem_.domain == Domain::omnigibson && kb.contains(s) && kb.has_property(s, "particleRemover")) {
      for (const std::string& substance : substances) {
        const auto solvents = kb.remover_solvents(s, substance);
        if (!solvents) continue;
        std::vector<std::string>& lemmas = ab.removes[synset_lemma(substance)];
        for (const std::string& solvent : *solvents) lemmas.push_back(synset_lemma(solvent));
      }
    }
    world.states().configure(index, ab);
  }
  // Stains need a soaked cleaning tool, dust any (iGibson's rules).
  world.states().add_substance({"stain", true});
  world.states().add_substance({"dust", false});
  configure_transitions(world);
}

bool Activity::sample_literal(World& w, const Literal& l, Rng& rng, const SampleOptions& options) const {
  const Binding& first = binding(l.args.at(0));
  if (first.kind == Binding::Kind::future) return holds(w, l);
  if (l.predicate == "future" && !l.negated && first.kind == Binding::Kind::object) {
    w.hide(first.index);
    return true;
  }
  if (first.kind == Binding::Kind::agent) {
    // The start: (onfloor agent floor) in BEHAVIOR-100, (ontop agent floor) in
    // most BEHAVIOR-1K files, (ontop agent lawn) in some: the robot stands in
    // that room. Anything else about the agent must simply hold.
    if (l.args.size() != 2) return holds(w, l);  // a state of the agent: holds() names why it cannot
    const Binding& second = binding(l.args.at(1));
    if ((l.predicate != "onfloor" && l.predicate != "ontop") || second.kind == Binding::Kind::agent ||
        second.kind == Binding::Kind::substance || second.kind == Binding::Kind::future || l.negated) {
      return holds(w, l);
    }
    const int room = agent_room(w, second);
    if (room < 0) return false;
    const Pose2 base = w.base_pose();
    const Room* now = w.scene().room_at(base.x, base.y);
    return now == &w.scene().rooms()[room] || sample_robot_in_room(w, room, rng);
  }
  // A state of a floor is its object's (dust on it). What chore cannot
  // sample (a substance first, a floor without an object) must hold, and
  // holds() names why it cannot.
  const bool kinematic = kKinematic.count(l.predicate) > 0;
  const int a = first.kind == Binding::Kind::object || !kinematic ? first.state_object() : -1;
  if (a < 0) return holds(w, l);
  const bool value = !l.negated;
  if (kinematic) {
    // Negated placements are not sampled (as BEHAVIOR's sampler); fixed
    // objects stay where the scene has them. Both must simply hold.
    if (l.negated || w.scene().objects()[a].fixed || l.predicate == "nextto" || l.predicate == "touching") {
      return holds(w, l);
    }
    const Binding& second = binding(l.args.at(1));
    if (second.kind == Binding::Kind::floor) return sample_onfloor(w, a, second.index, rng, options);
    // On, in or under the agent or a substance: nothing to place it by; holds() names why.
    if (second.kind != Binding::Kind::object) return holds(w, l);
    // A cloth laid over b settles into overlaid or draped (the checks say which).
    if (l.predicate == "ontop" || l.predicate == "overlaid" || l.predicate == "draped")
      return sample_ontop(w, a, second.index, rng, options);
    if (l.predicate == "inside") return sample_inside(w, a, second.index, rng, options);
    return sample_under(w, a, second.index, rng, options);
  }
  if (l.predicate == "attached" && value && binding(l.args.at(1)).kind == Binding::Kind::object) {
    return sample_attached(w, a, binding(l.args[1]).index, rng);
  } else if (l.predicate == "open") {
    sample_open(w, a, value, rng);
  } else if (l.predicate == "dusty" || l.predicate == "stained") {
    return sample_covered(w, a, l.predicate == "dusty" ? "dust" : "stain", value, rng);
  } else if (l.predicate == "covered") {
    return sample_covered(w, a, synset_lemma(type_of(l.args.at(1))), value, rng);
  } else if (kUnaryStates.count(l.predicate) || l.predicate == "saturated" || l.predicate == "filled" ||
             l.predicate == "contains") {
    sample_state(w, l.predicate, a, value, liquid_of(l));
  } else {
    return holds(w, l);
  }
  return true;
}

// The room the agent stands in when on `where`: a floor's, or the room of
// the object it stands on (a lawn); -1 when that object is in no room.
int Activity::agent_room(const World& w, const Binding& where) const {
  if (where.kind == Binding::Kind::floor) return where.index;
  const Eigen::Vector3d c = object_aabb(w, where.index).center();
  const Room* r = w.scene().room_at(c.x(), c.y());
  return r ? static_cast<int>(r - w.scene().rooms().data()) : -1;
}

// The liquid a soaked/saturated/filled literal names: its second argument's
// synset lemma (B1K: water.n.06_1 -> "water"), or water (BEHAVIOR-100's unary soaked).
std::string Activity::liquid_of(const Literal& l) const {
  return l.args.size() >= 2 ? synset_lemma(type_of(l.args[1])) : "water";
}

std::string Activity::type_of(const std::string& instance) const {
  for (const ObjectDecl& d : problem_.objects) {
    if (d.name == instance) return d.type;
  }
  throw Error("activity '" + name_ + "': no object '" + instance + "'");
}

bool Activity::holds(const World& w, const GroundLiteral& l) const {
  const Scene& scene = w.scene();
  auto arg = [&](size_t i) -> const Binding& { return binding(l.args.at(i)); };
  auto object_arg = [&](size_t i) {
    const Binding& b = arg(i);
    const int object = b.state_object();  // a floor's states are its object's
    if (object < 0) {
      throw Error("activity '" + name_ + "': " + to_bddl(l) + ": '" + l.args.at(i) + "' is not an object");
    }
    return object;
  };
  const std::string& p = l.predicate;
  bool value = false;
  if (!unmade_.empty() &&
      std::any_of(l.args.begin(), l.args.end(), [&](const std::string& a) { return unmade_.count(a) > 0; })) {
    // No scene object stands for it: nothing makes it, only (future X) holds.
    value = p == "future";
  } else if (p == "future" || p == "real") {
    // Objects transitions make or use up are hidden until made; a substance
    // of the future is real once something holds it or is covered with it.
    const Binding& b = arg(0);
    bool real = true;
    if (b.kind == Binding::Kind::object) real = w.real(b.index);
    if (b.kind == Binding::Kind::substance && future_.count(l.args[0]))
      real = substance_exists(w, synset_lemma(type_of(l.args[0])));
    value = (p == "real") == real;
  } else if ((p == "onfloor" || p == "ontop") && arg(0).kind == Binding::Kind::agent) {
    const int room = agent_room(w, arg(1));
    const Pose2 base = w.base_pose();
    value = room >= 0 && scene.room_at(base.x, base.y) == &scene.rooms()[room];
  } else if (p == "onfloor" || ((p == "ontop") && arg(1).kind == Binding::Kind::floor)) {
    if (arg(1).kind != Binding::Kind::floor) {
      throw Error("activity '" + name_ + "': " + to_bddl(l) + ": '" + l.args.at(1) + "' is not a floor");
    }
    value = onfloor(w, object_arg(0), arg(1).index);
  } else if (p == "inroom") {
    const Room* r = nullptr;
    if (arg(0).kind == Binding::Kind::floor) {
      r = &scene.rooms()[arg(0).index];
    } else if (arg(0).kind == Binding::Kind::agent) {
      r = scene.room_at(w.base_pose().x, w.base_pose().y);
    } else {
      const Eigen::Vector3d c = object_aabb(w, object_arg(0)).center();
      r = scene.room_at(c.x(), c.y());
    }
    value = r && room_matches(*r, l.args.at(1));
  } else if (const auto relation = kObjectRelations.find(p); relation != kObjectRelations.end()) {
    value = relation->second(w, object_arg(0), object_arg(1));
  } else if (p == "grasped" || p == "inhand") {
    // B1K: (grasped agent obj); BEHAVIOR-100 style: (inhand obj).
    value = grasped(w, object_arg(l.args.size() - 1));
  } else if (p == "attached") {
    // (attached a b): b may be the agent (held in the gripper).
    value = attached(w, object_arg(0), arg(1).kind == Binding::Kind::agent ? -1 : object_arg(1));
  } else if (p == "covered") {
    value = covered(w, object_arg(0), synset_lemma(type_of(l.args.at(1))));
  } else if (p == "soaked" || p == "saturated" || p == "filled" || p == "contains") {
    const int a = object_arg(0);
    const std::string liquid = liquid_of(l);
    value = p == "soaked"      ? soaked(w, a, liquid)
            : p == "saturated" ? saturated(w, a, liquid)
            : p == "filled"    ? filled(w, a, liquid)
                               : contains(w, a, liquid);
  } else if (p == "dusty" || p == "stained") {
    value = dirty(w, object_arg(0), p == "dusty" ? "dust" : "stain");
  } else if (p == "insource") {
    // What the object is (a sink is a source of water), not a state: sampled by holding.
    const std::string& source = scene.objects()[object_arg(0)].synset;
    value = kb_of(source).is_source_of(source, type_of(l.args.at(1)));
  } else {
    static const std::map<std::string, bool (*)(const World&, int)> unary = {
        {"open", is_open},    {"cooked", cooked},         {"burnt", burnt},      {"frozen", frozen}, {"hot", hot},
        {"on_fire", on_fire}, {"toggled_on", toggled_on}, {"sliced", sliced},    {"broken", broken}, {"infov", infov},
        {"inreach", inreach}, {"folded", folded},         {"unfolded", unfolded}};
    value = unary.at(p)(w, object_arg(0));
  }
  return value != l.negated;
}

Activity::Evaluation Activity::evaluate(const World& w) const {
  std::map<GroundLiteral, bool> known;
  const Truth truth = [&](const GroundLiteral& l) {
    const auto [it, fresh] = known.try_emplace(l, false);
    if (fresh) it->second = holds(w, l);
    return it->second;
  };
  Evaluation e;
  e.score = chore::score(goal_, truth);
  e.potential = goal_.options.empty() ? 0 : chore::potential(goal_, 0, truth);
  return e;
}

void Activity::instantiate(World& w, Rng& rng, const SampleOptions& options) const {
  const Pose2 start = w.base_pose();
  // The samplers' settling steps leave the states alone: what :init sets is
  // what the instance starts with (a stove :init turns on heats nothing yet),
  // and a scene of hundreds of objects does not run the state rules at every
  // physics step of every placement.
  struct StateUpdatesOff {
    World& w;
    const bool was = w.state_updates();
    explicit StateUpdatesOff(World& world) : w(world) { w.set_state_updates(false); }
    ~StateUpdatesOff() { w.set_state_updates(was); }
  } off(w);
  std::string failure;
  for (int attempt = 0; attempt < kInstantiationAttempts; ++attempt) {
    if (attempt > 0) w.reset(start);
    failure.clear();
    for (const Literal& l : init_order_) {
      if (!sample_literal(w, l, rng, options)) {
        failure = to_bddl(l) + " could not be sampled";
        break;
      }
    }
    // Later placements can disturb earlier ones: every literal must hold at the end.
    for (const Literal& l : init_order_) {
      if (failure.empty() && !holds(w, l)) failure = to_bddl(l) + " does not hold after sampling";
    }
    if (failure.empty()) return;
  }
  throw Error("activity '" + name_ + "': cannot instantiate: " + failure + " (" +
              std::to_string(kInstantiationAttempts) + " attempts)");
}

}  // namespace chore
