// chore::Error: the one exception type for bad input and failed set-up.
// Its message says what went wrong and where (file, line, name, index).
#pragma once

#include <stdexcept>
#include <string>

namespace chore {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace chore
