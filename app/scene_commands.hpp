// `chore scene list` and `chore scene build`: BEHAVIOR-1K's scenes as analogs
// generated from their furnishing inventories (analogs/scene_analogs.hpp).
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <ostream>
#include <string>

namespace chore {

// Each scene of the inventories: its rooms and objects.
void list_scenes(std::ostream& out);

struct SceneBuildOptions {
  std::string name;
  uint64_t seed = 0;
  std::string out;          // top-down picture (.png); empty: none
  std::string model_cache;  // compiled models kept here (world/model_cache.hpp); empty: none
};
// Generates the analog, compiles it (or loads it from the model cache) and,
// with `out`, draws it from above. Returns what it measured: rooms, size,
// objects placed and left out, bodies and geoms of the model, seconds to
// generate and to compile or load, and whether it came from the cache.
nlohmann::json build_scene(const SceneBuildOptions& options);
std::string format_scene_build(const nlohmann::json& result);

}  // namespace chore
