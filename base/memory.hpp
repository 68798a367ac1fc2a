// Buffers whose size an input sets (a replay buffer of --set sac.buffer
// transitions, a rollout of ppo.buffer images): checked against the machine's
// memory before they are allocated, so that an absurd size is an error naming
// the setting, not an allocator's failure deep inside a dependency.
#pragma once

#include <cstdint>
#include <string>

namespace chore {

// This machine's physical memory, bytes.
uint64_t physical_memory_bytes();

// chore::Error "WHAT needs X GB, more than this machine's Y GB of memory"
// when `bytes` exceed physical memory.
void check_fits_in_memory(double bytes, const std::string& what);

}  // namespace chore
