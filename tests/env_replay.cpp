// The C++ side of the Python binding's bit-for-bit test
// (python/tests/test_env.py): one Env episode, reset with a seed, then low-level
// actions ((7t + 3j) mod 21 - 10) / 10, every observation's bytes and each
// reward (float64) appended to a file, field by field in the space's order.
//   chore_env_replay ACTIVITY SEED STEPS OUT [OBSERVATION...]
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <vector>

#include "base/error.hpp"
#include "env/env.hpp"

namespace {

void write(std::ofstream& out, const chore::ArrayDict& obs) {
  for (const chore::Array& a : obs.arrays()) out.write(reinterpret_cast<const char*>(a.bytes.data()), a.bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: chore_env_replay ACTIVITY SEED STEPS OUT [OBSERVATION...]\n";
    return 2;
  }
  try {
    chore::EnvConfig config;
    config.activity = argv[1];
    if (argc > 5) config.observations.assign(argv + 5, argv + argc);
    chore::Env env(config);
    std::ofstream out(argv[4], std::ios::binary);
    write(out, env.reset(std::strtoull(argv[2], nullptr, 10)).obs);
    const int steps = std::atoi(argv[3]);
    std::vector<float> action(chore::kLowLevelActionSize);
    for (int t = 0; t < steps; ++t) {
      for (int j = 0; j < chore::kLowLevelActionSize; ++j)
        action[j] = static_cast<float>((7 * t + 3 * j) % 21 - 10) / 10;
      const auto r = env.step(action);
      write(out, r.obs);
      out.write(reinterpret_cast<const char*>(&r.reward), sizeof r.reward);
    }
    return out ? 0 : 1;
  } catch (const chore::Error& e) {
    std::cerr << "chore_env_replay: " << e.what() << "\n";
    return 2;
  }
}
