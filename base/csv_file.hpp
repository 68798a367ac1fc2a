// CSV tables (RFC 4180: quoted fields may hold commas, doubled quotes and line
// breaks) read by the names of their columns, with errors naming file:line.
#pragma once

#include <string>
#include <vector>

namespace chore {

struct CsvTable {
  std::string path;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // each as long as the header
  // The index of column `name`; chore::Error naming the file if absent.
  size_t column(const std::string& name) const;
  // "path:line" of row `r` (the header is line 1), for messages.
  std::string where(size_t r) const;
};

// A missing file, one larger than max_bytes, an unclosed quote or a row whose
// field count is not the header's is a chore::Error naming the file (and line).
CsvTable read_csv_file(const std::string& path, size_t max_bytes = 64u << 20);

}  // namespace chore
