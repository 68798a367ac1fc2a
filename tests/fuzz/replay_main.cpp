// A main for the fuzz targets built without libFuzzer (tests/CMakeLists.txt):
// runs each file given, and each file under each folder given, through
// LLVMFuzzerTestOneInput once, so that the suite replays the seeds, the
// corpora and the reproducers (tests/fuzz/targets.txt). Exits 0 when all ran;
// a finding crashes it, as it would crash the campaign.
//
// With --mutate RUNS [--seed S] [--findings DIR], it is the campaign of the
// targets clang cannot build (they need LibTorch): RUNS inputs, each a given
// file with random byte edits, insertions, erasures and copied chunks (no
// coverage guidance), seeded by S. The input in flight is written to
// DIR/crash-SEED-RUN when the target aborts, crashes or runs past 5 s.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    std::cerr << path << ": cannot open" << std::endl;
    std::exit(2);
  }
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The mutation campaign's input in flight and where it goes on a crash
// (written from a signal handler: plain buffers and write(2) only).
std::string in_flight;
char crash_path[4096];

void save_in_flight(int signal) {
  const int fd = ::open(crash_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    for (size_t done = 0; done < in_flight.size();) {
      const ssize_t n = ::write(fd, in_flight.data() + done, in_flight.size() - done);
      if (n <= 0) break;
      done += static_cast<size_t>(n);
    }
    ::close(fd);
  }
  ::write(2, "replay: finding saved to ", 25);
  ::write(2, crash_path, std::strlen(crash_path));
  ::write(2, "\n", 1);
  std::signal(signal, SIG_DFL);
  std::raise(signal);
}

// One to eight edits of `input`: libFuzzer's simplest mutators, no coverage.
std::string mutate(std::string input, std::mt19937_64& random) {
  auto below = [&](size_t n) { return n == 0 ? size_t{0} : static_cast<size_t>(random() % n); };
  const int edits = 1 + static_cast<int>(random() % 8);
  for (int e = 0; e < edits; ++e) {
    switch (random() % 5) {
      case 0:  // a random byte
        if (!input.empty()) input[below(input.size())] = static_cast<char>(random());
        break;
      case 1:  // a flipped bit
        if (!input.empty()) input[below(input.size())] ^= static_cast<char>(1 << (random() % 8));
        break;
      case 2:  // inserted bytes
        input.insert(below(input.size() + 1), std::string(1 + below(16), static_cast<char>(random())));
        break;
      case 3:  // an erased span
        if (!input.empty()) {
          const size_t at = below(input.size());
          input.erase(at, 1 + below(std::min<size_t>(64, input.size() - at)));
        }
        break;
      default:  // a chunk copied over another place
        if (input.size() > 2) {
          const size_t from = below(input.size()), to = below(input.size());
          const size_t length = 1 + below(std::min({input.size() - from, input.size() - to, size_t{256}}));
          std::copy_n(input.data() + from, length, input.data() + to);
        }
    }
  }
  return input;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::filesystem::path> files;
  long long mutate_runs = 0;
  uint64_t seed = 0;
  std::string findings = ".";
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--mutate" || arg == "--seed" || arg == "--findings") && i + 1 < argc) {
      const std::string value = argv[++i];
      if (arg == "--mutate") mutate_runs = std::stoll(value);
      if (arg == "--seed") seed = std::stoull(value);
      if (arg == "--findings") findings = value;
    } else if (std::filesystem::is_directory(arg)) {
      for (const auto& entry : std::filesystem::recursive_directory_iterator(arg)) {
        if (entry.is_regular_file()) files.push_back(entry.path());
      }
    } else {
      files.push_back(arg);
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::cerr << "replay: no inputs" << std::endl;
    return 1;
  }
  if (mutate_runs == 0) {
    for (const auto& path : files) {
      const std::string bytes = read_file(path);
      LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    }
    std::cout << files.size() << " inputs replayed" << std::endl;
    return 0;
  }
  std::vector<std::string> inputs;
  for (const auto& path : files) inputs.push_back(read_file(path));
  for (int s : {SIGABRT, SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGALRM}) std::signal(s, save_in_flight);
  std::mt19937_64 random(seed);
  for (long long run = 0; run < mutate_runs; ++run) {
    in_flight = mutate(inputs[random() % inputs.size()], random);
    const std::string path = findings + "/crash-" + std::to_string(seed) + "-" + std::to_string(run);
    path.copy(crash_path, sizeof crash_path - 1);
    crash_path[std::min(path.size(), sizeof crash_path - 1)] = '\0';
    ::alarm(5);  // a hang, as libFuzzer's -timeout=5
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(in_flight.data()), in_flight.size());
  }
  ::alarm(0);
  std::cout << mutate_runs << " mutated inputs of " << inputs.size() << " run, seed " << seed << std::endl;
  return 0;
}
