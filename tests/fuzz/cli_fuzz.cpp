// libFuzzer target: a command line, one argument per line -> the parser of
// app/command_line.hpp, one parser for every input (as CommandLineParser
// allows; building CLI11's options would cost more than the parse). It must
// return a command or an exit status with a message, never throw; anything
// else is a finding (scripts/fuzz).
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "app/command_line.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::vector<std::string> args = {"chore"};
  std::istringstream lines(std::string(reinterpret_cast<const char*>(data), size));
  for (std::string line; std::getline(lines, line) && args.size() < 64;) args.push_back(line);
  std::vector<const char*> argv;
  for (const std::string& a : args) argv.push_back(a.c_str());
  static chore::CommandLineParser parser;
  std::ostringstream out, err;
  parser.parse(static_cast<int>(argv.size()), argv.data(), out, err);
  return 0;
}
