// MuJoCo's default error handler calls exit(). chore installs handlers that turn
// errors into chore::Error (thrown through MuJoCo's frames, which carry unwind
// tables on x86-64) and keep the last warning per thread instead of printing it.
#pragma once

#include <string>

namespace chore {

// Idempotent and thread-safe; every entry point that touches MuJoCo calls it.
void install_mujoco_handlers();

// The last MuJoCo warning raised on this thread ("" if none).
const std::string& last_mujoco_warning();

}  // namespace chore
