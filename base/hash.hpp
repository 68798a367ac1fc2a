// FNV-1a, 64-bit: a stable hash of bytes (checkpoint checksums, colours per
// name), the same on every platform and run, unlike std::hash.
#pragma once

#include <cstdint>
#include <string_view>

namespace chore {

inline uint64_t fnv1a(std::string_view bytes) {
  uint64_t hash = 14695981039346656037ull;
  for (unsigned char c : bytes) hash = (hash ^ c) * 1099511628211ull;
  return hash;
}

}  // namespace chore
