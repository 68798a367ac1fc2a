#include "base/memory.hpp"

#include <unistd.h>

#include <cstdio>

#include "base/error.hpp"

namespace chore {

uint64_t physical_memory_bytes() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  return pages > 0 && page_size > 0 ? static_cast<uint64_t>(pages) * static_cast<uint64_t>(page_size) : 0;
}

void check_fits_in_memory(double bytes, const std::string& what) {
  const double memory = static_cast<double>(physical_memory_bytes());
  if (memory > 0 && bytes > memory) {
    char text[96];
    std::snprintf(text, sizeof text, " needs %.1f GB, more than this machine's %.1f GB of memory", bytes / 1e9,
                  memory / 1e9);
    throw Error(what + text);
  }
}

}  // namespace chore
