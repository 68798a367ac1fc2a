// libFuzzer target: scene JSON text -> the scene reader (its object models
// from the asset library). Bad input must end in chore::Error; anything else
// is a finding (scripts/fuzz).
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "world/scene.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string assets = chore::default_assets_dir();
  try {
    chore::parse_scene_file(std::string(reinterpret_cast<const char*>(data), size), "fuzz/scene.json", assets);
  } catch (const chore::Error&) {
  }
  return 0;
}
