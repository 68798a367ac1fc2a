// Reading JSON files with errors that say which file, where, and which field.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "base/input_file.hpp"

namespace chore {

// Bounds on what a JSON input may make us do: files larger than
// kMaxJsonBytes and values nested deeper than kMaxJsonDepth are errors (the
// readers recurse along the nesting).
inline constexpr size_t kMaxJsonBytes = 256u << 20;
inline constexpr int kMaxJsonDepth = 64;

// Parses JSON text; a syntax error, nesting past kMaxJsonDepth or a number
// out of double's range throws chore::Error naming `where` and line:column.
nlohmann::json parse_json(const std::string& text, const std::string& where);
// The same for a file, which must exist and be at most kMaxJsonBytes.
nlohmann::json read_json_file(const std::string& path);
// `value` as JSON text (indent as nlohmann's dump), strings that are not
// valid UTF-8 escaped as base/utf8.hpp does: what chore writes and prints.
std::string json_text(const nlohmann::json& value, int indent = -1);

// read() over fields of a JSON file chore wrote (an evaluation, a table),
// read without JsonReader: a field missing or of the wrong type (nlohmann's
// json::exception) is chore::Error "PATH: not as chore writes it (...)".
template <class Read>
auto reading_json(const std::string& path, Read read) -> decltype(read()) {
  try {
    return read();
  } catch (const nlohmann::json::exception& e) {
    throw Error(path + ": not as chore writes it (" + e.what() + ")");
  }
}

// The closed range a number read must lie in: input outside it is an error
// naming the field (a position of 1e308 m would reach the physics).
struct Bounds {
  double low, high;
};
inline constexpr Bounds kAnyNumber{-1.7976931348623157e308, 1.7976931348623157e308};

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
  double number(const char* key, Bounds bounds = kAnyNumber) const;
  double number(const char* key, double fallback, Bounds bounds = kAnyNumber) const;
  bool boolean(const char* key, bool fallback) const;
  std::vector<double> numbers(const char* key, size_t count, Bounds bounds = kAnyNumber) const;  // exact length
  std::vector<double> numbers(const char* key, size_t count, std::vector<double> fallback,
                              Bounds bounds = kAnyNumber) const;
  std::vector<double> as_numbers(size_t count, Bounds bounds = kAnyNumber) const;  // this value itself

  const std::string& where() const { return where_; }
  [[noreturn]] void fail(const std::string& message) const;

 private:
  const nlohmann::json& value_;
  std::string where_;
};

}  // namespace chore
