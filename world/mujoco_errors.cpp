#include "world/mujoco_errors.hpp"

#include <mujoco/mujoco.h>

#include <cstring>
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

mjModel* load_mjcf(const std::string& xml, const std::string& what) {
  install_mujoco_handlers();
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  const char* file = "chore.xml";
  if (mj_addBufferVFS(&vfs, file, xml.data(), static_cast<int>(xml.size())) != 0) {
    mj_deleteVFS(&vfs);
    throw Error(what + ": cannot allocate the model in MuJoCo's VFS");
  }
  char error[2048] = "";
  mjModel* model = nullptr;
  try {
    model = mj_loadXML(file, &vfs, error, sizeof error);
  } catch (...) {
    mj_deleteVFS(&vfs);
    throw;
  }
  mj_deleteVFS(&vfs);
  if (!model) throw Error(what + ": " + error);
  return model;
}

const std::string& last_mujoco_warning() {
  return last_warning;
}

}  // namespace chore
