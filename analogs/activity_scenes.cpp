#include "analogs/activity_scenes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <set>

#include "base/error.hpp"
#include "base/json_file.hpp"
#include "tasks/initial_states.hpp"
#include "tasks/knowledge_base.hpp"
#include "tasks/vocabulary.hpp"

namespace chore {
namespace {

// What an activity asks of a scene: the scene objects its inroom literals
// name, by room, and the synsets of its other objects; those the category
// models lack, modelled as their nearest ancestor that has one.
struct Needs {
  std::map<std::string, std::vector<std::string>> in_room;  // BDDL room -> synsets
  std::vector<std::string> loose;
  std::vector<std::string> future;  // objects transitions make (hidden until then)
  std::set<std::string> rooms;
  std::map<std::string, std::string> modelled_as;
  std::set<std::string> floors;  // BDDL rooms whose floor a state is asked of (dirt)
};

// `synset` if the models' knowledge base has it as an object, else its
// nearest ancestor in the activity's own that it has ("" for none).
std::string model_synset(const std::string& synset, const KnowledgeBase& models, const KnowledgeBase& dialect) {
  const auto modelled = [&](const std::string& s) { return models.contains(s) && !models.is_substance(s); };
  if (modelled(synset)) return synset;
  if (!dialect.contains(synset)) return "";
  std::vector<std::string> level = {synset};
  for (size_t depth = 0; depth < 64 && !level.empty(); ++depth) {  // breadth first: nearest first
    std::vector<std::string> next;
    for (const std::string& s : level) {
      for (const std::string& p : dialect.parents(s)) {
        if (modelled(p)) return p;
        next.push_back(p);
      }
    }
    level = std::move(next);
  }
  return "";
}

// The synset an instance is made as: its own, or, for an abstract synset
// whose states :init sets, the first of its kinds that keeps them (a
// saturated fiber.n.01 is made as cotton.n.01: fiber itself soaks nothing).
std::string made_as(const Problem& problem, const ObjectDecl& d, const KnowledgeBase& dialect) {
  if (!dialect.contains(d.type)) return d.type;
  const std::vector<std::string> states = states_set_on(problem, d.name);
  const std::string kind = states.empty() ? "" : kind_keeping(dialect, d.type, states);
  return kind.empty() ? d.type : kind;
}

// The synset a needed object is modelled as.
const std::string& needs_model(const Needs& needs, const std::string& synset) {
  const auto as = needs.modelled_as.find(synset);
  return as == needs.modelled_as.end() ? synset : as->second;
}

// The predicates a placement names its support with: a floor there is the room's.
bool places(const std::string& predicate) {
  return predicate == "ontop" || predicate == "inside" || predicate == "onfloor" || predicate == "under" ||
         predicate == "nextto";
}

// Calls `f` with every literal of `formula` and the variables in scope.
template <typename F>
void each_literal(const Formula& formula, std::vector<Variable>& scope, const F& f) {
  if (formula.op == Op::literal) {
    f(formula.literal, scope);
    return;
  }
  scope.insert(scope.end(), formula.variables.begin(), formula.variables.end());
  for (const Formula& child : formula.children) each_literal(child, scope, f);
  scope.resize(scope.size() - formula.variables.size());
}

Needs needs_of(const Problem& problem, const KnowledgeBase& kb) {
  const KnowledgeBase& dialect = *dialect_knowledge_base(problem.domain);
  std::map<std::string, std::string> room_of;
  std::set<std::string> future, substances, placed;
  for (const Literal& l : problem.init) {
    if (l.negated) continue;
    if (l.predicate == "inroom" && l.args.size() == 2) room_of[l.args[0]] = l.args[1];
    if (l.predicate == "future" && l.args.size() == 1) future.insert(l.args[0]);
    if (l.args.size() == 2 && places(l.predicate)) placed.insert(l.args[0]);
    if (l.args.size() == 2 && (l.predicate == "covered" || l.predicate == "filled" || l.predicate == "contains" ||
                               l.predicate == "saturated" || l.predicate == "insource"))
      substances.insert(l.args[1]);
  }
  Needs needs;
  for (const auto& [instance, room] : room_of) needs.rooms.insert(room);
  std::map<std::string, std::string> type_of;
  for (const ObjectDecl& d : problem.objects) type_of[d.name] = d.type;
  // Floor `a` (an instance, or a variable in `scope`, which stands for every
  // floor) is an object in its room.
  const auto floor_object = [&](const std::string& a, const std::vector<Variable>& scope) {
    const auto var = std::find_if(scope.rbegin(), scope.rend(), [&](const Variable& v) { return v.name == a; });
    const std::string type = var != scope.rend() ? var->type : type_of.contains(a) ? type_of[a] : "";
    if (type != "floor.n.01") return;
    for (const auto& [instance, room] : room_of) {
      if (var != scope.rend() ? type_of[instance] == "floor.n.01" : instance == a) needs.floors.insert(room);
    }
  };
  // A floor a state or relation is asked of ((covered floor dust), (touching
  // shoe floor); in :init or the goal) is an object, and so is one the goal
  // puts things on (place sets them down onto it).
  const auto floor_state = [&](const Literal& l, const std::vector<Variable>& scope) {
    if (l.predicate == "inroom" || places(l.predicate)) return;
    for (const std::string& a : l.args) floor_object(a, scope);
  };
  std::vector<Variable> scope;
  for (const Literal& l : problem.init) floor_state(l, scope);
  each_literal(problem.goal, scope, floor_state);
  each_literal(problem.goal, scope, [&](const Literal& l, const std::vector<Variable>& scope) {
    if ((l.predicate == "ontop" || l.predicate == "onfloor") && l.args.size() == 2) floor_object(l.args[1], scope);
  });
  for (const ObjectDecl& d : problem.objects) {
    if (d.type == "agent.n.01" || d.type == "floor.n.01") continue;
    const bool substance = dialect.contains(d.type) && dialect.is_substance(d.type) && !placed.contains(d.name);
    if (substances.contains(d.name) || substance) continue;
    const std::string synset = made_as(problem, d, dialect);
    const std::string model = model_synset(synset, kb, dialect);
    if (model.empty()) continue;
    if (model != synset) needs.modelled_as[synset] = model;
    const auto room = room_of.find(d.name);
    if (future.contains(d.name)) {
      needs.future.push_back(synset);  // a free object, hidden until a transition makes it
    } else if (room != room_of.end()) {
      needs.in_room[room->second].push_back(synset);
    } else {
      needs.loose.push_back(synset);
    }
  }
  return needs;
}

bool matches(const RoomInventory& room, const std::string& bddl_room) {
  return room.type == bddl_room || room.name == bddl_room;
}

// The BDDL rooms no room of `inventory` matches.
std::vector<std::string> missing_rooms(const SceneInventory& inventory, const std::set<std::string>& rooms) {
  std::vector<std::string> missing;
  for (const std::string& r : rooms) {
    if (std::none_of(inventory.rooms.begin(), inventory.rooms.end(), [&](const auto& i) { return matches(i, r); })) {
      missing.push_back(r);
    }
  }
  return missing;
}

// BEHAVIOR's preselected scenes per activity, read once.
const std::map<std::string, std::vector<std::string>>& preselected_scenes() {
  static std::once_flag once;
  static std::map<std::string, std::vector<std::string>> scenes;
  std::call_once(once, [] {
    const std::string path = default_tasks_dir() + "/kb/behavior-1k/activity_to_preselected_scenes.json";
    const nlohmann::json file = read_json_file(path);
    if (!file.is_object()) throw Error(path + ": expected an object of activities");
    for (const auto& [activity, list] : file.items()) {
      if (!list.is_array()) JsonReader(file, path).at(activity.c_str()).fail("expected a list of scenes");
      for (const nlohmann::json& scene : list) {
        if (!scene.is_string()) JsonReader(file, path).at(activity.c_str()).fail("expected scene names");
        scenes[activity].push_back(scene.get<std::string>());
      }
    }
  });
  return scenes;
}

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& n : names) text += (text.empty() ? "" : ", ") + n;
  return text;
}

// Containers and surfaces large enough for what :init puts inside or on
// them, as BEHAVIOR's scenes have them: room for 2.5x the footprints of the
// contents (each turned any way: its diagonal squared), no side shorter than
// the largest diagonal (furniture keeps its depth), and, inside, the tallest
// under the lid; walls, doors and the sampler's margins beside. A container
// grows along both sides, a surface along its width. Nested ones (a
// tupperware in the fridge) are sized inside out; a like thing on its like
// (stacked plates) is no load. The least inner heights (AnalogExtras::least_inner_heights)
// beside: the tallest content and the margins above it. And furniture that
// :init puts something on (or attaches something to, which hangs from its
// top) no taller than keeps that within an arm's reach from above
// (AnalogExtras::greatest_heights): BDDL's ontop is the top, and a bottle on
// a 1.8 m shelf's top is out of reach; what must go inside keeps its room.
void support_sizes(const Problem& problem, const CategoryModels& models, AnalogExtras& extras) {
  constexpr double kWalls = 0.1, kSpace = 2.5;
  // m: the highest top of a load the samplers prefer (arm_reach_preference),
  // and the lowest a support is made for a tall load.
  constexpr double kReachedTop = 1.15, kLowestTop = 0.4;
  const KnowledgeBase& kb = models.knowledge_base();
  std::map<std::string, std::string> synset_of;
  const KnowledgeBase& dialect = *dialect_knowledge_base(problem.domain);
  for (const ObjectDecl& d : problem.objects) synset_of[d.name] = made_as(problem, d, dialect);
  const auto object_synset = [&](const std::string& instance) -> std::string {
    const auto it = synset_of.find(instance);
    return it != synset_of.end() && kb.contains(it->second) && !kb.is_substance(it->second) &&
                   it->second != "agent.n.01" && it->second != "floor.n.01"
               ? it->second
               : "";
  };
  std::map<std::string, Eigen::Vector3d>& least = extras.least_sizes;
  const auto size = [&](const std::string& synset) {
    const auto it = least.find(synset);
    return it == least.end() ? models.size(synset) : models.size(synset).cwiseMax(it->second);
  };
  struct Load {
    bool inside = false;
    double area = 0, diagonal = 0, narrow = 0, height = 0;  // narrow: the widest content's narrow side
  };
  for (int depth = 0; depth < 3; ++depth) {  // BEHAVIOR nests two deep at most
    std::map<std::string, Load> loads;       // support instance -> what goes on or in it
    for (const Literal& l : problem.init) {
      if (l.negated || l.args.size() != 2) continue;
      const std::string what = object_synset(l.args[0]), support = object_synset(l.args[1]);
      // A like thing on its like (a plate stacked on a plate, french toast
      // on french toast) is no load: sizes are the synset's, and grown for
      // its own kind a synset grew 2.5x at every pass (french toast 3 m
      // long on plates 2.5 m across on a breakfast table 8.5 m long).
      if (what.empty() || support.empty() || what == support) continue;
      const Eigen::Vector3d s = size(what);
      if ((l.predicate == "ontop" || l.predicate == "attached") && kb.has_property(support, "sceneObject")) {
        const double highest = std::max(kLowestTop, kReachedTop - s.z());
        const auto [it, fresh] = extras.greatest_heights.try_emplace(support, highest);
        if (!fresh) it->second = std::min(it->second, highest);
      }
      if (l.predicate != "inside" && l.predicate != "ontop") continue;
      Load& load = loads[l.args[1]];
      const double diagonal = s.head<2>().norm() + 0.02;
      // On a bowl is in it (pea pods on a mixing bowl): a container grows
      // both ways for what it holds either way. Grown along its width
      // alone, a bowl for five pea pods was 0.94 m across, and the counter
      // under it as deep, its middle out of the arm's reach. (Not a basin:
      // a sink grown deeper for the plates on it put its tap out of reach.)
      const Archetype held_by = models.archetype(support);
      load.inside |=
          l.predicate == "inside" || held_by == Archetype::open_container || held_by == Archetype::lidded_container;
      load.area += diagonal * diagonal;
      load.diagonal = std::max(load.diagonal, diagonal);
      load.narrow = std::max(load.narrow, s.head<2>().minCoeff() + 0.02);
      if (l.predicate == "inside") load.height = std::max(load.height, s.z());
    }
    for (const auto& [instance, load] : loads) {
      const std::string synset = object_synset(instance);
      const Eigen::Vector3d own = size(synset);
      Eigen::Vector3d need;
      if (load.inside) {
        const double side = std::max(load.diagonal, std::sqrt(kSpace * load.area)) + kWalls;
        need = {side, side, load.height + kWalls};
        // Reached into through its door, it keeps its depth and grows wider
        // (a fridge grown deeper held a bowl at its back beyond the arm).
        if (models.archetype(synset) == Archetype::cabinet) {
          need.x() = std::max(load.diagonal, kSpace * load.area / std::max(own.y(), load.diagonal)) + kWalls;
          need.y() = load.diagonal + kWalls;
        }
        double& inner = extras.least_inner_heights[synset];
        inner = std::max(inner, load.height + kWalls);
      } else {
        // A surface grows along its width, and no shallower than what lies
        // on it is across; furniture no shallower than that is narrow, for
        // what lies on it squared to its sides (world/sampling.cpp's
        // try_place). Grown as deep as a board grown for a fish was long,
        // a counter against its wall was 1.36 m deep, the board at its back
        // beyond every base pose (clean_a_fish).
        const bool furniture = kb.has_property(synset, "sceneObject");
        need = {std::max(load.diagonal, kSpace * load.area / std::max(own.y(), load.diagonal)),
                furniture ? load.narrow : load.diagonal, 0};
      }
      const auto [it, fresh] = least.try_emplace(synset, need);
      if (!fresh) it->second = it->second.cwiseMax(need);
    }
  }
}

}  // namespace

SceneInventory activity_inventory(const Problem& problem, const std::string& scene) {
  const Needs needs = needs_of(problem, CategoryModels::shipped()->knowledge_base());
  if (!scene.empty()) {
    const SceneInventory& inventory = find_scene_inventory(scene);
    const std::vector<std::string> missing = missing_rooms(inventory, needs.rooms);
    if (!missing.empty()) throw Error("scene " + scene + " has no room " + joined(missing) + " for " + problem.name);
    return inventory;
  }
  // "assembling_gift_baskets-0": the activity is the name before the instance number.
  const std::string activity = problem.name.substr(0, problem.name.rfind('-'));
  if (const auto it = preselected_scenes().find(activity); it != preselected_scenes().end()) {
    for (const std::string& name : it->second) {
      for (const SceneInventory& inventory : shipped_scene_inventories()) {
        if (inventory.name == name && missing_rooms(inventory, needs.rooms).empty()) return inventory;
      }
    }
  }
  // The fewest rooms missing, then the fewest objects; a room no inventory
  // has (BEHAVIOR-100's home_office) is added empty, and the activity's
  // objects furnish it.
  const SceneInventory* best = nullptr;
  size_t best_missing = 0;
  for (const SceneInventory& inventory : shipped_scene_inventories()) {
    const size_t missing = missing_rooms(inventory, needs.rooms).size();
    if (!best || std::pair(missing, inventory.object_count()) < std::pair(best_missing, best->object_count())) {
      best = &inventory;
      best_missing = missing;
    }
  }
  if (!best) throw Error(problem.name + ": no BEHAVIOR-1K scene inventories");
  SceneInventory chosen = *best;
  for (const std::string& room : missing_rooms(*best, needs.rooms)) {
    // A room named TYPE_N keeps its name; a type names its first room.
    const size_t cut = room.rfind('_');
    const bool named = cut != std::string::npos && cut + 1 < room.size() &&
                       room.find_first_not_of("0123456789", cut + 1) == std::string::npos;
    chosen.rooms.push_back({named ? room : room + "_0", named ? room.substr(0, cut) : room, {}});
  }
  return chosen;
}

SceneAnalog activity_scene_analog(const Problem& problem, const SceneInventory& inventory,
                                  const CategoryModels& models) {
  const KnowledgeBase& kb = models.knowledge_base();
  const Needs needs = needs_of(problem, kb);
  AnalogExtras extras;
  // Per BDDL room and synset: instances the room's inventory lacks; their
  // tops stay clear for what the activity puts there.
  for (const auto& [room, synsets] : needs.in_room) {
    extras.clear_tops.insert(extras.clear_tops.end(), synsets.begin(), synsets.end());
    std::map<std::string, int> wanted;
    for (const std::string& s : synsets) ++wanted[s];
    for (const auto& [synset, count] : wanted) {
      int have = 0;
      for (const RoomInventory& r : inventory.rooms) {
        if (!matches(r, room)) continue;
        for (const auto& [s, n] : r.objects) have += kb.contains(synset) && kb.is_a(s, synset) ? n : 0;
      }
      for (int i = have; i < count; ++i) extras.objects.push_back({room, synset, false});
    }
  }
  for (const std::string& synset : needs.loose) extras.objects.push_back({"", synset, true});
  for (const std::string& synset : needs.future) extras.objects.push_back({"", synset, true, true});
  support_sizes(problem, models, extras);
  extras.modelled_as = needs.modelled_as;
  extras.floors.assign(needs.floors.begin(), needs.floors.end());
  // A weld for each pair :init attaches or the goal would (a quantified pair:
  // every pair of those types).
  std::map<std::string, std::string> synset_of;
  for (const ObjectDecl& d : problem.objects) synset_of[d.name] = d.type;
  std::set<std::pair<std::string, std::string>> attachable;
  bool at_start = true;
  const auto attaches = [&](const Literal& l, const std::vector<Variable>& scope) {
    if (l.negated || l.predicate != "attached" || l.args.size() != 2) return;
    std::string types[2];
    for (int i = 0; i < 2; ++i) {
      const auto var =
          std::find_if(scope.rbegin(), scope.rend(), [&](const Variable& v) { return v.name == l.args[i]; });
      const auto declared = synset_of.find(l.args[i]);
      types[i] = var != scope.rend() ? var->type : declared != synset_of.end() ? declared->second : "";
    }
    if (types[0].empty() || types[1].empty() || types[1] == "agent.n.01") return;
    attachable.insert({needs_model(needs, types[0]), needs_model(needs, types[1])});
    if (at_start) extras.holding_at_start.push_back(needs_model(needs, types[1]));
  };
  std::vector<Variable> none;
  for (const Literal& l : problem.init) attaches(l, none);
  at_start = false;
  each_literal(problem.goal, none, attaches);
  for (const auto& [object, to] : attachable) extras.attachments.push_back({object, to});
  return generate_scene_analog(inventory, models, 0, extras);
}

}  // namespace chore
