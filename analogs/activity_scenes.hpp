// The analog an activity is instantiated in: BEHAVIOR's preselected scenes
// for it (tasks/kb/behavior-1k/activity_to_preselected_scenes.json) where one
// has every room its (inroom ...) literals name, else the inventory with the
// fewest objects that has them (or lacks fewest); plus the objects the activity needs, as
// BEHAVIOR's sampler imports task objects: a scene object an inroom literal
// names that the room lacks is added to the room, and each object without an
// inroom literal gets a free instance of its synset, which the activity's
// sampler then places by its initial conditions.
#pragma once

#include <cstdint>
#include <string>

#include "analogs/scene_analogs.hpp"
#include "tasks/bddl.hpp"

namespace chore {

// The inventory scene for `problem`: `scene` when given (it must have the
// rooms: else a chore::Error naming those it lacks), else as above; where no
// inventory has every room, the one that lacks fewest, with the rooms it
// lacks added empty (the activity's objects furnish them).
SceneInventory activity_inventory(const Problem& problem, const std::string& scene = "");

// The analog of `inventory` (layout seed 0) with what `problem` needs added.
SceneAnalog activity_scene_analog(const Problem& problem, const SceneInventory& inventory,
                                  const CategoryModels& models);

}  // namespace chore
