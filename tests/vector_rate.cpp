// The C++ side of scripts/bench_python: env steps per second of a VectorEnv
// stepped synchronously with zero actions, as python/chore steps it.
//   chore_vector_rate [--batch-rendering] [--size N] ACTIVITY ENVS THREADS STEPS [OBSERVATION...]
// --batch-rendering: VectorEnvConfig::rendering = Rendering::batch; --size:
// the images' width and height (default the env's, 128).
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "env/vector_env.hpp"

int main(int argc, char** argv) {
  chore::VectorEnvConfig config;
  for (;;) {
    const std::string option = argc > 1 ? argv[1] : "";
    if (option == "--batch-rendering") {
      config.rendering = chore::Rendering::batch;
    } else if (option == "--size" && argc > 2 && std::atoi(argv[2]) > 0) {
      config.env.width = config.env.height = std::atoi(argv[2]);
      ++argv, --argc;
    } else {
      break;
    }
    ++argv, --argc;
  }
  if (argc < 5) {
    std::cerr << "usage: chore_vector_rate [--batch-rendering] [--size N] ACTIVITY ENVS THREADS STEPS "
                 "[OBSERVATION...]\n";
    return 2;
  }
  try {
    config.env.activity = argv[1];
    if (argc > 5) config.env.observations.assign(argv + 5, argv + argc);
    config.num_envs = std::atoi(argv[2]);
    config.num_threads = std::atoi(argv[3]);
    const int steps = std::atoi(argv[4]);
    chore::VectorEnv envs(config);
    const std::vector<float> zero(envs.num_envs() * envs.single_action_space().element_count(), 0.f);
    envs.reset(0);
    for (int i = 0; i < 10; ++i) envs.step(zero);  // warm-up, as the Python side
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < steps; ++i) envs.step(zero);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cout << steps * envs.num_envs() / seconds << "\n";
    return 0;
  } catch (const chore::Error& e) {
    std::cerr << "chore_vector_rate: " << e.what() << "\n";
    return 2;
  }
}
