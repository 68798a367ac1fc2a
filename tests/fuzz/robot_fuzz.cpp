// libFuzzer target: robot MJCF text -> MuJoCo's reader and chore's check of
// what it drives (world/robot.hpp). Bad input must end in chore::Error;
// anything else is a finding (scripts/fuzz).
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "world/robot.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    chore::robot_mjcf_children(std::string(reinterpret_cast<const char*>(data), size), "fuzz/tiago.xml");
  } catch (const chore::Error&) {
  }
  return 0;
}
