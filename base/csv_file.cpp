#include "base/csv_file.hpp"

#include <algorithm>

#include "base/error.hpp"
#include "base/json_file.hpp"

namespace chore {

size_t CsvTable::column(const std::string& name) const {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) throw Error(path + ": no column '" + name + "'");
  return static_cast<size_t>(it - header.begin());
}

std::string CsvTable::where(size_t r) const {
  return path + ":" + std::to_string(r + 2);
}

CsvTable read_csv_file(const std::string& path, size_t max_bytes) {
  const std::string text = read_text_file(path, max_bytes, "a CSV file");
  std::vector<std::vector<std::string>> rows(1, std::vector<std::string>(1));
  bool quoted = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    std::string& field = rows.back().back();
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      rows.back().emplace_back();
    } else if (c == '\n') {
      rows.emplace_back(1);
    } else if (c != '\r') {
      field += c;
    }
  }
  if (quoted) throw Error(path + ": a quoted field is not closed");
  if (rows.back().size() == 1 && rows.back()[0].empty()) rows.pop_back();
  if (rows.empty()) throw Error(path + ": empty, no header");
  CsvTable table{path, std::move(rows[0]), {}};
  for (size_t r = 1; r < rows.size(); ++r) {
    if (rows[r].size() != table.header.size()) {
      throw Error(path + ":" + std::to_string(r + 1) + ": " + std::to_string(rows[r].size()) +
                  " fields, the header has " + std::to_string(table.header.size()));
    }
    table.rows.push_back(std::move(rows[r]));
  }
  return table;
}

}  // namespace chore
