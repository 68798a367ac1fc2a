#include "world/model_cache.hpp"

#include <mujoco/mujoco.h>

#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <vector>

#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/temp_file.hpp"
#include "world/mujoco_errors.hpp"

namespace fs = std::filesystem;

namespace chore {
namespace {

// The file: this header, then the MJB bytes.
struct Header {
  char magic[8] = {'c', 'h', 'o', 'r', 'e', 'm', 'j', 'b'};
  uint32_t format = 2;  // 2: scenes' objects settled where they were placed (Scene)
  int32_t mujoco = 0;  // mj_version()
  uint64_t xml_hash = 0, xml_size = 0;
  uint64_t mjb_size = 0, mjb_hash = 0;
};

constexpr uint64_t kMaxMjb = uint64_t{1} << 30;  // MuJoCo's VFS takes an int size

Header expected_header(const std::string& xml) {
  Header h;
  h.mujoco = mj_version();
  h.xml_hash = fnv1a(xml);
  h.xml_size = xml.size();
  return h;
}

bool same_key(const Header& a, const Header& b) {
  return std::memcmp(a.magic, b.magic, sizeof a.magic) == 0 && a.format == b.format && a.mujoco == b.mujoco &&
         a.xml_hash == b.xml_hash && a.xml_size == b.xml_size;
}

// The model in `path` when the file is whole and for this document; else nullptr.
mjModel* read_cached(const fs::path& path, const Header& want) {
  std::error_code ec;
  const uintmax_t size = fs::file_size(path, ec);
  if (ec || size < sizeof(Header) || size - sizeof(Header) > kMaxMjb) return nullptr;
  std::ifstream in(path, std::ios::binary);
  Header h;
  if (!in.read(reinterpret_cast<char*>(&h), sizeof h) || !same_key(h, want)) return nullptr;
  if (h.mjb_size != size - sizeof(Header)) return nullptr;
  std::string mjb(h.mjb_size, '\0');
  if (!in.read(mjb.data(), static_cast<std::streamsize>(mjb.size())) || fnv1a(mjb) != h.mjb_hash) return nullptr;
  mjVFS vfs;
  mj_defaultVFS(&vfs);
  const char* file = "chore.mjb";
  if (mj_addBufferVFS(&vfs, file, mjb.data(), static_cast<int>(mjb.size())) != 0) {
    mj_deleteVFS(&vfs);
    return nullptr;
  }
  mjModel* model = nullptr;
  try {
    model = mj_loadModel(file, &vfs);
  } catch (const Error&) {  // MuJoCo's complaint about a file of another build
  }
  mj_deleteVFS(&vfs);
  return model;
}

// The name of a file this cache writes: HASH.mjb.
bool is_cache_name(const fs::path& name) {
  const std::string stem = name.stem().string();
  return name.extension() == ".mjb" && !stem.empty() && stem.size() <= 20 &&
         std::all_of(stem.begin(), stem.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// A file this cache wrote: named HASH.mjb and starting with its magic.
bool is_cache_file(const fs::path& path) {
  if (!is_cache_name(path.filename())) return false;
  std::ifstream in(path, std::ios::binary);
  Header h;
  return in.read(reinterpret_cast<char*>(&h), sizeof h) && std::memcmp(h.magic, Header().magic, sizeof h.magic) == 0;
}

// Writes beside, then renames: a reader never sees half a file. Failures
// leave the model uncached.
void write_cached(const fs::path& dir, const fs::path& path, Header h, const mjModel* model) {
  const int size = mj_sizeModel(model);
  if (size <= 0 || static_cast<uint64_t>(size) > kMaxMjb) return;
  std::string mjb(static_cast<size_t>(size), '\0');
  mj_saveModel(model, nullptr, mjb.data(), size);
  h.mjb_size = mjb.size();
  h.mjb_hash = fnv1a(mjb);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) return;
  const fs::path temp = temp_path_for(path);
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(&h), sizeof h);
    out.write(mjb.data(), static_cast<std::streamsize>(mjb.size()));
    if (!out.flush()) {
      out.close();
      fs::remove(temp, ec);
      return;
    }
  }
  fs::rename(temp, path, ec);
  if (ec) fs::remove(temp, ec);
  // The most recently used of chore's files stay; other files (a user's own
  // .mjb) are not the cache's to remove. Temporary files of writers that
  // died mid-write go.
  std::vector<std::pair<fs::file_time_type, fs::path>> files;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (is_cache_file(it->path())) files.push_back({it->last_write_time(ec), it->path()});
  }
  remove_dead_writers_temps(dir, [](const std::string& name) { return is_cache_name(name); });
  if (files.size() <= static_cast<size_t>(kModelCacheFiles)) return;
  std::sort(files.begin(), files.end());
  for (size_t i = 0; i + kModelCacheFiles < files.size(); ++i) fs::remove(files[i].second, ec);
}

}  // namespace

mjModel_* load_mjcf_cached(const std::string& xml, const std::string& what, const std::string& dir, bool* from_cache,
                           const std::function<void(mjModel_*)>& prepare) {
  if (from_cache) *from_cache = false;
  const auto compile = [&] {
    mjModel* model = load_mjcf(xml, what);
    if (prepare) {
      try {
        prepare(model);
      } catch (...) {
        mj_deleteModel(model);
        throw;
      }
    }
    return model;
  };
  if (dir.empty()) return compile();
  install_mujoco_handlers();
  const Header want = expected_header(xml);
  const fs::path path = fs::path(dir) / (std::to_string(want.xml_hash) + ".mjb");
  if (mjModel* cached = read_cached(path, want)) {
    if (from_cache) *from_cache = true;
    std::error_code ec;
    fs::last_write_time(path, fs::file_time_type::clock::now(), ec);  // recently used: kept
    return cached;
  }
  mjModel* model = compile();
  write_cached(dir, path, want, model);
  return model;
}

std::string default_model_cache_dir() {
  for (const auto& [variable, below] :
       {std::pair{"CHORE_CACHE", ""}, std::pair{"XDG_CACHE_HOME", "/chore"}, std::pair{"HOME", "/.cache/chore"}}) {
    const char* value = std::getenv(variable);
    if (value && *value) return std::string(value) + below + "/models";
  }
  return "";
}

}  // namespace chore
