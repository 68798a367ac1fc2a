// chore::Error: the one exception type for bad input and failed set-up.
// Its message says what went wrong and where (file, line, name, index).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

#include "base/utf8.hpp"

namespace chore {

// Its message is valid UTF-8 (what it quotes may not be: base/utf8.hpp).
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(valid_utf8(message)) {}
  explicit Error(const char* message) : Error(std::string(message)) {}
};

// `value`, checked to lie in [low, high]; else chore::Error
// "NAME = VALUE is outside [LOW, HIGH]". For settings read from files and
// command lines, where an absurd size would reach an allocation.
template <class T>
T within(const std::string& name, T value, T low, T high) {
  if (!(value >= low && value <= high)) {
    std::ostringstream s;
    s << name << " = " << value << " is outside [" << low << ", " << high << "]";
    throw Error(s.str());
  }
  return value;
}

}  // namespace chore
