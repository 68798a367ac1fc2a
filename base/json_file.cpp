#include "base/json_file.hpp"

#include <fstream>
#include <sstream>

#include "base/error.hpp"
#include "base/utf8.hpp"

namespace chore {

namespace {

// "LINE:COLUMN" of byte `offset` of text.
std::string line_column(const std::string& text, size_t offset) {
  size_t line = 1, column = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return std::to_string(line) + ":" + std::to_string(column);
}

// The offset of the first '[' or '{' (outside strings) nested deeper than
// kMaxJsonDepth, or npos.
size_t too_deep(const std::string& text) {
  int depth = 0;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_string) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth) return i;
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
  return std::string::npos;
}

// The offset of number token `token` in text (where nlohmann says no more than its text).
size_t find_token(const std::string& text, const std::string& token) {
  for (size_t at = text.find(token); at != std::string::npos; at = text.find(token, at + 1)) {
    const bool starts = at == 0 || std::string_view(",:[ \t\r\n").find(text[at - 1]) != std::string_view::npos;
    if (starts) return at;
  }
  return std::string::npos;
}

}  // namespace

nlohmann::json parse_json(const std::string& text, const std::string& where) {
  if (const size_t at = too_deep(text); at != std::string::npos) {
    throw Error(where + ":" + line_column(text, at) + ": nested deeper than " + std::to_string(kMaxJsonDepth) +
                " levels, the limit");
  }
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    std::string what = e.what();
    const auto pos = what.find("syntax error");
    throw Error(where + ":" + line_column(text, e.byte == 0 ? 0 : e.byte - 1) + ": " +
                (pos == std::string::npos ? what : what.substr(pos)));
  } catch (const nlohmann::json::exception& e) {
    // A number out of double's range (1e400): nlohmann names its text only.
    std::string what = e.what();
    const size_t open = what.find('\''), close = what.rfind('\'');
    const std::string token = open < close ? what.substr(open + 1, close - open - 1) : "";
    const size_t at = token.empty() ? std::string::npos : find_token(text, token);
    const std::string message = token.empty() ? what : "the number " + token + " is out of range";
    throw Error(where + (at == std::string::npos ? "" : ":" + line_column(text, at)) + ": " + message);
  }
}

nlohmann::json read_json_file(const std::string& path) {
  return parse_json(read_text_file(path, kMaxJsonBytes, "a JSON file"), path);
}

namespace {

nlohmann::json with_valid_strings(const nlohmann::json& value) {
  switch (value.type()) {
    case nlohmann::json::value_t::string:
      return valid_utf8(value.get_ref<const std::string&>());
    case nlohmann::json::value_t::array: {
      nlohmann::json out = nlohmann::json::array();
      for (const auto& v : value) out.push_back(with_valid_strings(v));
      return out;
    }
    case nlohmann::json::value_t::object: {
      nlohmann::json out = nlohmann::json::object();
      for (const auto& [k, v] : value.items()) out[valid_utf8(k)] = with_valid_strings(v);
      return out;
    }
    default:
      return value;
  }
}

}  // namespace

std::string json_text(const nlohmann::json& value, int indent) {
  try {
    return value.dump(indent);
  } catch (const nlohmann::json::type_error&) {  // 316: a string that is not UTF-8
    return with_valid_strings(value).dump(indent);
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

namespace {

std::string fmt(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

double JsonReader::number(const char* key, Bounds bounds) const {
  const JsonReader field = at(key);
  if (!field.value_.is_number()) field.fail("expected a number");
  const double v = field.value_.get<double>();
  if (!(v >= bounds.low && v <= bounds.high)) {
    field.fail(fmt(v) + " is outside [" + fmt(bounds.low) + ", " + fmt(bounds.high) + "]");
  }
  return v;
}

double JsonReader::number(const char* key, double fallback, Bounds bounds) const {
  return has(key) ? number(key, bounds) : fallback;
}

bool JsonReader::boolean(const char* key, bool fallback) const {
  if (!has(key)) return fallback;
  const JsonReader field = at(key);
  if (!field.value_.is_boolean()) field.fail("expected true or false");
  return field.value_.get<bool>();
}

std::vector<double> JsonReader::as_numbers(size_t count, Bounds bounds) const {
  if (!value_.is_array() || value_.size() != count) {
    fail("expected an array of " + std::to_string(count) + " numbers");
  }
  std::vector<double> out;
  for (const auto& v : value_) {
    if (!v.is_number()) fail("expected an array of " + std::to_string(count) + " numbers");
    out.push_back(v.get<double>());
    if (!(out.back() >= bounds.low && out.back() <= bounds.high)) {
      fail("[" + std::to_string(out.size() - 1) + "] = " + fmt(out.back()) + " is outside [" + fmt(bounds.low) + ", " +
           fmt(bounds.high) + "]");
    }
  }
  return out;
}

std::vector<double> JsonReader::numbers(const char* key, size_t count, Bounds bounds) const {
  return at(key).as_numbers(count, bounds);
}

std::vector<double> JsonReader::numbers(const char* key, size_t count, std::vector<double> fallback,
                                        Bounds bounds) const {
  return has(key) ? numbers(key, count, bounds) : fallback;
}

}  // namespace chore
