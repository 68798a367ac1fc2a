// chore::Error: the one exception type for bad input and failed set-up.
// Its message says what went wrong and where (file, line, name, index).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace chore {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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
