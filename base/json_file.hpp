// Reading JSON files with errors that say which file, where, and which field.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace chore {

// Parses a JSON file; a missing file or a syntax error throws chore::Error
// naming the path and line:column.
nlohmann::json read_json_file(const std::string& path);

// Typed field access for validated configs: `where` names the object in
// messages, e.g. "apartment.json: objects[3]".
class JsonReader {
 public:
  JsonReader(const nlohmann::json& value, std::string where);

  bool has(const char* key) const;
  JsonReader at(const char* key) const;  // required object/array field
  JsonReader at(size_t index) const;     // array element
  size_t size() const;                   // array length (throws if not an array)

  std::string string(const char* key) const;
  std::string string(const char* key, const std::string& fallback) const;
  double number(const char* key) const;
  double number(const char* key, double fallback) const;
  bool boolean(const char* key, bool fallback) const;
  std::vector<double> numbers(const char* key, size_t count) const;  // exact length
  std::vector<double> numbers(const char* key, size_t count, std::vector<double> fallback) const;
  std::vector<double> as_numbers(size_t count) const;  // this value itself

  const std::string& where() const { return where_; }
  [[noreturn]] void fail(const std::string& message) const;

 private:
  const nlohmann::json& value_;
  std::string where_;
};

}  // namespace chore
