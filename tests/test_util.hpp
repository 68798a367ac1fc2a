// Shared helpers for the test suites: test data paths and scratch directories.
#pragma once

#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "base/error.hpp"
#include "env/env.hpp"

namespace chore::test {

inline std::string data_path(const std::string& relative) {
  return std::string(CHORE_TEST_DATA) + "/" + relative;
}

// A TCP port free on loopback now (the kernel's choice for port 0).
inline int free_port() {
  const int s = socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = 0;
  socklen_t n = sizeof a;
  const bool ok = bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0 &&
                  getsockname(s, reinterpret_cast<sockaddr*>(&a), &n) == 0;
  close(s);
  return ok ? ntohs(a.sin_port) : 29500;
}

inline std::string box_room() {
  return data_path("scenes/box_room.json");
}

// The box room with the robot exactly at its start pose (no seeded jitter).
inline EnvConfig box_room_config() {
  EnvConfig c;
  c.scene = box_room();
  c.start_jitter = 0;
  return c;
}

// An activity in the primitive action space, observing only is_grasping.
inline EnvConfig primitives_config(const std::string& activity) {
  EnvConfig c;
  c.activity = activity;
  c.action_space = "primitives";
  c.observations = {"is_grasping"};
  return c;
}

// A fresh directory under the build tree for files a test writes and a person
// may want to look at (pictures).
inline std::filesystem::path output_dir() {
  std::filesystem::path dir(CHORE_TEST_OUTPUT);
  std::filesystem::create_directories(dir);
  return dir;
}

// A scratch directory, emptied on creation.
inline std::filesystem::path scratch_dir(const std::string& name) {
  std::filesystem::path dir = output_dir() / ("scratch_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The message of the chore::Error that f throws, or "(no error)".
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

inline void write_file(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

}  // namespace chore::test
