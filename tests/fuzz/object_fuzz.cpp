// libFuzzer target: object model JSON text -> the model reader -> a scene of
// one room holding it, compiled by MuJoCo (no robot): what the reader lets
// through must compile or be a chore::Error. Anything else is a finding
// (scripts/fuzz).
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "world/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    chore::SceneFile file;
    file.name = "fuzz";
    file.path = "fuzz/object.json";
    file.rooms = {{"room_0", "room", {{{-2, -2, 2, 2}}}}};
    file.models["fuzzed"] =
        chore::parse_object_model(std::string(reinterpret_cast<const char*>(data), size), file.path);
    file.objects = {{.name = "fuzzed_1", .model = "fuzzed", .pos = {0, 0, 0.5}},
                    {.name = "fuzzed_2", .model = "fuzzed", .fixed = true, .pos = {1, 1, 0}}};
    if (file.models["fuzzed"].cloth) file.objects.pop_back();  // a cloth cannot be fixed
    chore::Scene::build(file, {.robot = false});
  } catch (const chore::Error&) {
  }
  return 0;
}
