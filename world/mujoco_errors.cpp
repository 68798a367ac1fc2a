#include "world/mujoco_errors.hpp"

#include <mujoco/mujoco.h>

#include <mutex>

#include "base/error.hpp"

namespace chore {
namespace {

thread_local std::string last_warning;

void on_error(const char* message) {
  throw Error(std::string("MuJoCo error: ") + message);
}

void on_warning(const char* message) {
  last_warning = message;
}

}  // namespace

void install_mujoco_handlers() {
  static std::once_flag once;
  std::call_once(once, [] {
    mju_user_error = on_error;
    mju_user_warning = on_warning;
  });
}

const std::string& last_mujoco_warning() {
  return last_warning;
}

}  // namespace chore
