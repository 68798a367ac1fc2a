// libFuzzer target: a checkpoint file less its checksum, which the target
// appends -> the framing, the tensor records -> the metadata, every field
// checked. All of a checkpoint that chore reads but the copy of checked
// records into torch tensors (the checkpoint target's, replayed by the
// suite), and torch-free, so clang's campaign runs it. Bad input must end in
// chore::Error; anything else is a finding (scripts/fuzz).
#include <cstdint>
#include <string>

#include "base/error.hpp"
#include "training/checkpoint.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string bytes(reinterpret_cast<const char*>(data), size);
  const uint64_t checksum = chore::checkpoint_checksum(bytes);
  bytes.append(reinterpret_cast<const char*>(&checksum), sizeof checksum);
  try {
    chore::read_checkpoint_meta(chore::parse_checkpoint(bytes, "fuzz/checkpoint.pt"));
  } catch (const chore::Error&) {
  }
  return 0;
}
