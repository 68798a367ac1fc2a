// Reading JSON files with errors that say which file, where, and which field.
#pragma once

#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

namespace chore {

// Bounds on what a JSON input may make us do: files larger than
// kMaxJsonBytes and values nested deeper than kMaxJsonDepth are errors (the
// readers recurse along the nesting).
inline constexpr size_t kMaxJsonBytes = 256u << 20;
inline constexpr int kMaxJsonDepth = 64;

// A text file's bytes; a missing file, or one larger than max_bytes, throws
// chore::Error naming the path (`what` names the kind: "a BDDL file").
std::string read_text_file(const std::string& path, size_t max_bytes, const std::string& what);

// Parses JSON text; a syntax error, nesting past kMaxJsonDepth or a number
// out of double's range throws chore::Error naming `where` and line:column.
nlohmann::json parse_json(const std::string& text, const std::string& where);
// The same for a file, which must exist and be at most kMaxJsonBytes.
nlohmann::json read_json_file(const std::string& path);

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
