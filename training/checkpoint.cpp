#include "training/checkpoint.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "base/error.hpp"
#include "base/json_file.hpp"

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

std::string take_block(const std::string& bytes, size_t& offset, const std::string& path) {
  const uint64_t length = take<uint64_t>(bytes, offset, path);
  if (bytes.size() - offset < length) throw Error("checkpoint " + path + ": truncated");
  std::string block = bytes.substr(offset, length);
  offset += length;
  return block;
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

uint64_t checkpoint_checksum(std::string_view bytes) {
  uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

void write_checkpoint(const std::string& path, const CheckpointFile& checkpoint) {
  std::string bytes(kMagic, sizeof kMagic);
  put(bytes, kCheckpointVersion);
  const std::string meta = checkpoint.meta.dump();
  put(bytes, static_cast<uint64_t>(meta.size()));
  bytes += meta;
  put(bytes, static_cast<uint64_t>(checkpoint.tensors.size()));
  bytes += checkpoint.tensors;
  put(bytes, checkpoint_checksum(bytes));

  // Write beside the target, flush to disk, then rename over it: the old file
  // stays whole until the new one is.
  const std::string temp = path + ".tmp" + std::to_string(::getpid());
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

CheckpointFile read_checkpoint(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("checkpoint " + path + ": cannot open");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  return parse_checkpoint(buffer.str(), path);
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
  checkpoint.tensors = take_block(bytes, offset, path);
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
