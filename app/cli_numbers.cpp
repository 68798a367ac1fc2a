#include "app/cli_numbers.hpp"

#include <charconv>
#include <cmath>
#include <sstream>

#include "base/random.hpp"

namespace chore {

CLI::Validator integer_in(int64_t low, int64_t high) {
  const std::string range = "[" + std::to_string(low) + ", " + std::to_string(high) + "]";
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        int64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (text.empty() || error != std::errc() || stop != end || value < low || value > high) {
          return "'" + text + "' is not an integer in " + range;
        }
        return "";
      },
      "INT in " + range);
}

CLI::Validator seed_number() {
  return integer_in(0, static_cast<int64_t>(kMaxSeed));
}

CLI::Validator real_in(double low, double high) {
  std::ostringstream range;
  range << "[" << low << ", " << high << "]";
  return CLI::Validator(
      [=, range = range.str()](std::string& text) -> std::string {
        double value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        if (text.empty() || error != std::errc() || stop != end || !std::isfinite(value) || value < low ||
            value > high) {
          return "'" + text + "' is not a number in " + range;
        }
        return "";
      },
      "NUMBER in " + range.str());
}

}  // namespace chore
