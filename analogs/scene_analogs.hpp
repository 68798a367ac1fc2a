// Analogs of BEHAVIOR-1K's scenes, generated from their furnishing
// inventories: tasks/kb/behavior-1k/combined_room_object_list.json says, per
// scene, its rooms and how many objects of each category each room holds
// (categories are synsets through category_mapping.csv). BEHAVIOR's scene
// meshes are not chore's to ship; what an activity needs of a scene is its
// rooms and what stands in them, which the inventory gives.
//
// The generation, seeded (the same seed gives the same scene):
//   rooms          each sized for its floor-standing furniture (3x their
//                  footprints and aisles plus 4 m2, at least 6 m2, 1:1 to
//                  1.5:1), laid out in rows of one width, so the house is a
//                  rectangle of rooms;
//                  a doorway between neighbours in a row and one from each row
//                  to the row before, so every room is reachable
//   doors          the doorways stay open; the inventory's doors stand closed
//                  against walls (openable, as BDDL may ask)
//   furniture      scene objects (fixed): against a wall facing into the room,
//                  else free-standing (tables first); never overlapping each
//                  other, the walls or the 1 m before a doorway; an aisle of
//                  0.7 m kept clear before the front (along both long sides
//                  of what stands free) for the robot to stand in
//   on the walls   windows, pictures, mirrors, switches: at their height,
//                  not over furniture reaching within 0.5 m of them; the wall
//                  either side kept for what an activity attaches to them
//   small objects  (free) on the part of a table's, counter's, cabinet's or
//                  shelf's top the arm reaches from an aisle, else on the
//                  floor out of the aisles
//   floors         the rooms' own; an object (a slab 2 mm high) where asked
//   the robot      starts in the first room with floor 0.5 m clear of everything
// What does not fit is left out and counted (SceneAnalog::left_out).
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "analogs/category_models.hpp"
#include "world/scene_file.hpp"

namespace chore {

struct RoomInventory {
  std::string name, type;                            // "kitchen_0", "kitchen"
  std::vector<std::pair<std::string, int>> objects;  // synset, count; sorted by synset
};

struct SceneInventory {
  std::string name;  // "Rs_int"
  std::vector<RoomInventory> rooms;
  int object_count() const;
};

// Every scene of the inventory file, sorted by name; a category the mapping
// lacks, a bad count or room name is a chore::Error naming the file and scene.
std::vector<SceneInventory> read_scene_inventories(const std::string& inventory_path, const std::string& category_path);
// The shipped inventories (tasks/kb/behavior-1k/), read once.
const std::vector<SceneInventory>& shipped_scene_inventories();
// The shipped inventory of `name`; chore::Error naming the known scenes.
const SceneInventory& find_scene_inventory(const std::string& name);

struct SceneAnalog {
  SceneFile file;
  int placed = 0;    // inventory objects in the scene
  int left_out = 0;  // inventory objects with no room left for them
};

// An object added beyond the inventory, in the first room whose name or type
// is `room` ("": the first room): fixed furniture when its synset is a scene
// object and it is not `loose` (a kitchen appliance lower than a counter, a
// microwave, fixed on a surface facing the way the furniture under it does),
// else free on a surface or the floor.
struct ExtraObject {
  std::string room, synset;
  bool loose = false;
  // Hidden until a transition makes it (World::hide): placed after all else,
  // by draws of its own, so that the rest of the scene is the one it would
  // be without it.
  bool future = false;
};

// What a caller adds to an inventory: objects, the synsets of furniture
// whose tops stay clear of the inventory's small objects (an activity samples
// its own objects onto them), and least sizes.
struct AnalogExtras {
  std::vector<ExtraObject> objects;
  std::vector<std::string> clear_tops;
  // Least outer sizes (x, y, z) of synsets' models: containers grown to hold
  // what the activity puts inside them. A synset keeps its own size where
  // that is larger.
  std::map<std::string, Eigen::Vector3d> least_sizes;
  // Least inner heights of drawers and basins: the tallest thing the activity
  // puts inside, with room above it (CategoryModels::model).
  std::map<std::string, double> least_inner_heights;
  // Greatest heights of furniture synsets whose top :init puts something on
  // (or attaches something to): that within an arm's reach from above. A
  // least size wins over it.
  std::map<std::string, double> greatest_heights;
  // Synsets the category models lack (BEHAVIOR-100's sunglass.n.01) built as
  // another's (an ancestor's): synset -> the synset whose model it takes.
  std::map<std::string, std::string> modelled_as;
  // Synsets (object, to) an activity attaches: every object of the first
  // with every object of the second may be (SceneFile::attachments).
  std::vector<std::pair<std::string, std::string>> attachments;
  // Synsets something hangs on from the start (a wind chimes' pole on its
  // nail): as wall items they keep a larger item's height, with room below.
  std::vector<std::string> holding_at_start;
  // Rooms (name or type, as ExtraObject::room) whose floor is an object: a
  // fixed slab of synset floor.n.01 over the room's floor, in its colour,
  // that keeps states as objects do (dust on the floor).
  std::vector<std::string> floors;
};

// chore::Error for an extra object's room the inventory lacks.
SceneAnalog generate_scene_analog(const SceneInventory& inventory, const CategoryModels& models, uint64_t seed,
                                  const AnalogExtras& extras = {});

}  // namespace chore
