#include "training/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/error.hpp"
#include "base/hash.hpp"
#include "base/json_file.hpp"
#include "base/temp_file.hpp"

namespace chore {
namespace {

constexpr char kMagic[8] = {'C', 'H', 'O', 'R', 'E', 'C', 'K', 'P'};

template <class T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

// Reads a T at `offset`, or throws "truncated".
template <class T>
T take(const std::string& bytes, size_t& offset, const std::string& path) {
  if (bytes.size() - offset < sizeof(T)) throw Error("checkpoint " + path + ": truncated");
  T value;
  std::memcpy(&value, bytes.data() + offset, sizeof value);
  offset += sizeof value;
  return value;
}

std::string take_block(const std::string& bytes, size_t& offset, const std::string& path, uint64_t length) {
  if (bytes.size() - offset < length) throw Error("checkpoint " + path + ": truncated");
  std::string block = bytes.substr(offset, length);
  offset += length;
  return block;
}

std::string take_block(const std::string& bytes, size_t& offset, const std::string& path) {
  return take_block(bytes, offset, path, take<uint64_t>(bytes, offset, path));
}

constexpr uint64_t kMaxTensors = 100000;
constexpr uint32_t kMaxTensorName = 1024;

void put_tensors(std::string& out, const TensorRecords& tensors) {
  put(out, static_cast<uint64_t>(tensors.size()));
  for (const auto& [name, t] : tensors) {
    put(out, static_cast<uint32_t>(name.size()));
    out += name;
    put(out, static_cast<uint8_t>(t.type));
    put(out, static_cast<uint8_t>(t.shape.size()));
    for (int64_t d : t.shape) put(out, d);
    put(out, static_cast<uint64_t>(t.bytes.size()));
    out += t.bytes;
  }
}

// The tensors block, each record checked: a name, a known type, a shape whose
// elements are exactly the bytes that follow.
TensorRecords take_tensors(const std::string& bytes, size_t& offset, const std::string& path) {
  const std::string what = "checkpoint " + path + ": ";
  const uint64_t count = take<uint64_t>(bytes, offset, path);
  if (count > kMaxTensors)
    throw Error(what + std::to_string(count) + " tensors, more than " + std::to_string(kMaxTensors));
  TensorRecords tensors;
  for (uint64_t i = 0; i < count; ++i) {
    const uint32_t name_length = take<uint32_t>(bytes, offset, path);
    if (name_length == 0 || name_length > kMaxTensorName) {
      throw Error(what + "tensor " + std::to_string(i) + ": a name of " + std::to_string(name_length) + " bytes");
    }
    const std::string name = take_block(bytes, offset, path, name_length);
    const std::string where = what + "tensor '" + name + "': ";
    TensorRecord t;
    const uint8_t type = take<uint8_t>(bytes, offset, path);
    if (type > static_cast<uint8_t>(ElementType::float64))
      throw Error(where + "unknown element type " + std::to_string(type));
    t.type = static_cast<ElementType>(type);
    const uint8_t rank = take<uint8_t>(bytes, offset, path);
    if (rank > kMaxTensorRank)
      throw Error(where + "rank " + std::to_string(rank) + " is over " + std::to_string(kMaxTensorRank));
    // Elements counted against the bytes left, so that no product overflows.
    uint64_t elements = 1;
    const uint64_t left = bytes.size() - offset;
    for (int d = 0; d < rank; ++d) {
      const int64_t size = take<int64_t>(bytes, offset, path);
      if (size < 0 || static_cast<uint64_t>(size) > left) throw Error(where + "dimension " + std::to_string(size));
      t.shape.push_back(size);
      elements = size == 0 || elements == 0 ? 0 : elements * static_cast<uint64_t>(size);
      if (elements > left) throw Error(where + "more elements than the file holds");
    }
    const uint64_t length = take<uint64_t>(bytes, offset, path);
    if (length != elements * element_size(t.type)) {
      throw Error(where + std::to_string(length) + " bytes for " + std::to_string(elements) + " elements");
    }
    t.bytes = take_block(bytes, offset, path, length);
    if (!tensors.emplace(name, std::move(t)).second) throw Error(where + "twice");
  }
  return tensors;
}

void write_all(int fd, const std::string& bytes, const std::string& path) {
  for (size_t done = 0; done < bytes.size();) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw Error("checkpoint " + path + ": write failed: " + std::strerror(errno));
    done += static_cast<size_t>(n);
  }
}

}  // namespace

size_t element_size(ElementType type) {
  switch (type) {
    case ElementType::uint8:
      return 1;
    case ElementType::float32:
      return 4;
    case ElementType::int64:
    case ElementType::float64:
      return 8;
  }
  return 0;
}

const TensorRecord& CheckpointFile::tensor(const std::string& name) const {
  const auto it = tensors.find(name);
  if (it == tensors.end()) throw Error("checkpoint " + path + ": no tensor '" + name + "'");
  return it->second;
}

uint64_t checkpoint_checksum(std::string_view bytes) {
  return fnv1a(bytes);
}

void write_checkpoint(const std::string& path, const CheckpointFile& checkpoint) {
  std::string bytes(kMagic, sizeof kMagic);
  put(bytes, kCheckpointVersion);
  const std::string meta = json_text(checkpoint.meta);
  put(bytes, static_cast<uint64_t>(meta.size()));
  bytes += meta;
  put_tensors(bytes, checkpoint.tensors);
  put(bytes, checkpoint_checksum(bytes));

  // Write beside the target, flush to disk, then rename over it: the old file
  // stays whole until the new one is.
  const std::string temp = temp_path_for(path).string();
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw Error("checkpoint " + temp + ": cannot create: " + std::strerror(errno));
  try {
    write_all(fd, bytes, temp);
    if (::fsync(fd) != 0) throw Error("checkpoint " + temp + ": fsync failed: " + std::strerror(errno));
  } catch (...) {
    ::close(fd);
    ::unlink(temp.c_str());
    throw;
  }
  ::close(fd);
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    ::unlink(temp.c_str());
    throw Error("checkpoint " + path + ": rename failed: " + std::strerror(errno));
  }
  const std::string dir = std::filesystem::absolute(path).parent_path().string();
  if (const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY); dfd >= 0) {
    ::fsync(dfd);  // makes the rename itself durable
    ::close(dfd);
  }
}

void remove_stale_checkpoint_temps(const std::string& dir) {
  remove_dead_writers_temps(
      dir, [](const std::string& name) { return name.starts_with("checkpoint") && name.ends_with(".pt"); });
}

CheckpointFile read_checkpoint(const std::string& path) {
  // A file of known size only: a device or a pipe (/dev/zero) would be read
  // without end, and a file beyond the bound is refused before it is read.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw Error("checkpoint " + path + (std::filesystem::exists(path, ec) ? ": not a regular file" : ": cannot open"));
  }
  const uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw Error("checkpoint " + path + ": cannot open");
  if (size > kMaxCheckpointBytes) {
    throw Error("checkpoint " + path + ": " + std::to_string(size) + " bytes, more than " +
                std::to_string(kMaxCheckpointBytes));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("checkpoint " + path + ": cannot open");
  std::string bytes(size, '\0');
  if (!in.read(bytes.data(), static_cast<std::streamsize>(size))) throw Error("checkpoint " + path + ": cannot read");
  return parse_checkpoint(bytes, path);
}

CheckpointFile parse_checkpoint(const std::string& bytes, const std::string& path) {
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
    throw Error("checkpoint " + path + ": not a chore checkpoint (bad magic)");
  }
  size_t offset = sizeof kMagic;
  const uint32_t version = take<uint32_t>(bytes, offset, path);
  if (version != kCheckpointVersion) {
    throw Error("checkpoint " + path + ": format version " + std::to_string(version) + ", this chore reads version " +
                std::to_string(kCheckpointVersion));
  }
  CheckpointFile checkpoint;
  checkpoint.path = path;
  const std::string meta = take_block(bytes, offset, path);
  checkpoint.tensors = take_tensors(bytes, offset, path);
  const size_t body = offset;
  const uint64_t checksum = take<uint64_t>(bytes, offset, path);
  if (offset != bytes.size()) throw Error("checkpoint " + path + ": trailing bytes after the checksum");
  if (checksum != checkpoint_checksum(std::string_view(bytes).substr(0, body))) {
    throw Error("checkpoint " + path + ": corrupt (checksum mismatch)");
  }
  checkpoint.meta = parse_json(meta, "checkpoint " + path + ": metadata");
  return checkpoint;
}

CheckpointMeta read_checkpoint_meta(const CheckpointFile& file) {
  const std::string what = "checkpoint " + file.path;
  try {
    CheckpointMeta meta{.config = train_config_from_json(file.meta.at("config")),
                        .network = network_spec_from_json(file.meta.at("network"))};
    EpisodeStats episodes(meta.config.num_envs);  // checked here; a resumed trainer reads its own
    meta.progress = load_run_meta(file.meta, episodes);
    within<int64_t>("steps", meta.progress.steps, 0, 10000000000);
    return meta;
  } catch (const nlohmann::json::exception& e) {
    throw Error(what + ": bad metadata: " + e.what());
  } catch (const Error& e) {
    throw Error(what + ": " + e.what());
  }
}

}  // namespace chore
