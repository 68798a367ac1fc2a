#include "base/json_file.hpp"

#include <fstream>
#include <sstream>

#include "base/error.hpp"

namespace chore {

nlohmann::json read_json_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    // Convert nlohmann's byte offset into line:column.
    size_t line = 1, column = 1;
    for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    std::string what = e.what();
    const auto pos = what.find("syntax error");
    throw Error(path + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " +
                (pos == std::string::npos ? what : what.substr(pos)));
  }
}

JsonReader::JsonReader(const nlohmann::json& value, std::string where) : value_(value), where_(std::move(where)) {}

void JsonReader::fail(const std::string& message) const {
  throw Error(where_ + ": " + message);
}

bool JsonReader::has(const char* key) const {
  return value_.is_object() && value_.contains(key);
}

JsonReader JsonReader::at(const char* key) const {
  if (!value_.is_object()) fail("expected an object");
  if (!value_.contains(key)) fail(std::string("missing field '") + key + "'");
  return JsonReader(value_.at(key), where_ + "." + key);
}

JsonReader JsonReader::at(size_t index) const {
  if (!value_.is_array() || index >= value_.size()) fail("no element " + std::to_string(index));
  return JsonReader(value_.at(index), where_ + "[" + std::to_string(index) + "]");
}

size_t JsonReader::size() const {
  if (!value_.is_array()) fail("expected an array");
  return value_.size();
}

std::string JsonReader::string(const char* key) const {
  const JsonReader field = at(key);
  if (!field.value_.is_string()) field.fail("expected a string");
  return field.value_.get<std::string>();
}

std::string JsonReader::string(const char* key, const std::string& fallback) const {
  return has(key) ? string(key) : fallback;
}

double JsonReader::number(const char* key) const {
  const JsonReader field = at(key);
  if (!field.value_.is_number()) field.fail("expected a number");
  return field.value_.get<double>();
}

double JsonReader::number(const char* key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

bool JsonReader::boolean(const char* key, bool fallback) const {
  if (!has(key)) return fallback;
  const JsonReader field = at(key);
  if (!field.value_.is_boolean()) field.fail("expected true or false");
  return field.value_.get<bool>();
}

std::vector<double> JsonReader::as_numbers(size_t count) const {
  if (!value_.is_array() || value_.size() != count) {
    fail("expected an array of " + std::to_string(count) + " numbers");
  }
  std::vector<double> out;
  for (const auto& v : value_) {
    if (!v.is_number()) fail("expected an array of " + std::to_string(count) + " numbers");
    out.push_back(v.get<double>());
  }
  return out;
}

std::vector<double> JsonReader::numbers(const char* key, size_t count) const {
  return at(key).as_numbers(count);
}

std::vector<double> JsonReader::numbers(const char* key, size_t count, std::vector<double> fallback) const {
  return has(key) ? numbers(key, count) : fallback;
}

}  // namespace chore
