#include "base/input_file.hpp"

#include <filesystem>
#include <fstream>

#include "base/error.hpp"

namespace chore {

namespace fs = std::filesystem;

void check_regular_file(const std::string& path, const std::string& what) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  const char* kind = nullptr;
  switch (status.type()) {
    case fs::file_type::regular:
      return;
    case fs::file_type::not_found:
      throw Error(path + ": no such file; expected " + what);
    case fs::file_type::directory:
      kind = "a folder";
      break;
    case fs::file_type::character:
      kind = "a character device";
      break;
    case fs::file_type::block:
      kind = "a block device";
      break;
    case fs::file_type::fifo:
      kind = "a FIFO";
      break;
    case fs::file_type::socket:
      kind = "a socket";
      break;
    default:
      throw Error(path + ": cannot open file (" + (ec ? ec.message() : std::string("unknown type")) + "); expected " +
                  what);
  }
  throw Error(path + ": not a file (" + kind + "); expected " + what);
}

std::string read_text_file(const std::string& path, size_t max_bytes, const std::string& what) {
  check_regular_file(path, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::string bytes;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    const auto n = static_cast<size_t>(in.gcount());
    if (bytes.size() + n > max_bytes) {
      throw Error(path + ": larger than " + std::to_string(max_bytes >> 20) + " MB, the limit for " + what);
    }
    bytes.append(chunk, n);
  }
  if (in.bad()) throw Error(path + ": cannot read file");
  return bytes;
}

}  // namespace chore
