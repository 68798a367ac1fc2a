// MuJoCo's default error handler calls exit(). chore installs handlers that turn
// errors into chore::Error (thrown through MuJoCo's frames, which carry unwind
// tables on x86-64) and keep the last warning per thread instead of printing it.
#pragma once

#include <string>

struct mjModel_;

namespace chore {

// Idempotent and thread-safe; every entry point that touches MuJoCo calls it.
void install_mujoco_handlers();

// Compiles an MJCF document held in memory (through MuJoCo's virtual file
// system); MuJoCo's complaint becomes a chore::Error after "WHAT: ".
mjModel_* load_mjcf(const std::string& xml, const std::string& what);

// The last MuJoCo warning raised on this thread ("" if none).
const std::string& last_mujoco_warning();

}  // namespace chore
