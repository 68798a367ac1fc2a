#include "base/temp_file.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>

namespace chore {
namespace {

constexpr std::string_view kTemp = ".tmp.";

bool all_digits(std::string_view s, size_t max_size) {
  if (s.empty() || s.size() > max_size) return false;
  for (const char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

}  // namespace

std::filesystem::path temp_path_for(const std::filesystem::path& final_path) {
  static std::atomic<unsigned long> count = 0;
  return final_path.string() + std::string(kTemp) + std::to_string(::getpid()) + "." + std::to_string(count++);
}

std::string dead_writers_final_name(const std::string& file_name) {
  const size_t tmp = file_name.rfind(kTemp);
  if (tmp == std::string::npos || tmp == 0) return "";
  const std::string_view rest = std::string_view(file_name).substr(tmp + kTemp.size());
  const size_t dot = rest.find('.');
  if (dot == std::string_view::npos) return "";
  const std::string_view pid = rest.substr(0, dot), n = rest.substr(dot + 1);
  // A PID is at most 2^22 on Linux: more than nine digits is not one of ours.
  if (!all_digits(pid, 9) || !all_digits(n, 20)) return "";
  if (::kill(static_cast<pid_t>(std::stol(std::string(pid))), 0) == 0 || errno != ESRCH) return "";
  return file_name.substr(0, tmp);
}

void remove_dead_writers_temps(const std::filesystem::path& dir,
                               const std::function<bool(const std::string& final_name)>& is_ours) {
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string final_name = dead_writers_final_name(it->path().filename().string());
    if (final_name.empty() || !is_ours(final_name)) continue;
    std::error_code ignored;
    const std::filesystem::file_status status = it->symlink_status(ignored);
    if (std::filesystem::is_regular_file(status)) std::filesystem::remove(it->path(), ignored);
    if (std::filesystem::is_directory(status)) std::filesystem::remove_all(it->path(), ignored);
  }
}

}  // namespace chore
