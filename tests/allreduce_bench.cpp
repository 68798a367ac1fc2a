// What DD-PPO's gradient averaging costs (training/distributed.hpp): one
// Ranks::mean of RL-Prim.'s (and RL-Prim.Hist.'s) parameters' size, two
// ranks over loopback (the second a thread of this process running the same
// all-reduces), one torch thread:
//   build/tests/chore_allreduce_bench [--benchmark_repetitions=5]
// PPO makes one per minibatch: epochs x buffer / batch = 10 x 5 = 50 per update
// at Table A.12's settings, beside BM_PpoMinibatch, one minibatch's update on
// one rank (the trainer's update_ms).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <thread>

#include "test_util.hpp"
#include "training/distributed.hpp"
#include "training/trainer.hpp"

namespace chore {
namespace {

// The baseline's parameters and normalisers, flattened, on CollectTrash.
int64_t parameter_count(const std::string& baseline) {
  TrainConfig config = baseline_config(baseline, "collect_trash");
  config.env.primitive_mode = ExecutionMode::symbolic;
  return static_cast<int64_t>(make_trainer(config)->parameters().size());
}

void BM_GradientMean(benchmark::State& state, const std::string& baseline) {
  torch::set_num_threads(1);
  const int64_t n = parameter_count(baseline);
  const int port = test::free_port();
  constexpr int kIterations = 200;
  std::thread other([&] {
    Ranks ranks({1, 2, "127.0.0.1", port, "torchrun"});
    const torch::Tensor g = torch::ones({n});
    for (int i = 0; i < kIterations + 1; ++i) ranks.mean({g});
  });
  Ranks ranks({0, 2, "127.0.0.1", port, "torchrun"});
  const torch::Tensor g = torch::ones({n});
  ranks.mean({g});  // connections warm
  for (auto _ : state) ranks.mean({g});
  other.join();
  state.counters["parameters"] = static_cast<double>(n);
  state.counters["bytes"] = static_cast<double>(Ranks::bytes({g}));
}
BENCHMARK_CAPTURE(BM_GradientMean, rl_prim, std::string("rl-prim"))->Unit(benchmark::kMillisecond)->Iterations(200);
BENCHMARK_CAPTURE(BM_GradientMean, rl_prim_hist, std::string("rl-prim-hist"))
    ->Unit(benchmark::kMillisecond)
    ->Iterations(200);

// One minibatch's update of RL-Prim. on one rank, as the trainer reports it
// (update_ms: forward, backward, clipping, Adam), 128x128 RGB, batch 64.
void BM_PpoMinibatch(benchmark::State& state) {
  TrainConfig config = baseline_config("rl-prim", "collect_trash");
  config.env.primitive_mode = ExecutionMode::symbolic;
  config.threads = 1;
  const auto trainer = make_trainer(config);
  const auto names = trainer->extra_metric_names();
  const auto update_ms = std::find(names.begin(), names.end(), "update_ms") - names.begin();
  for (auto _ : state) {
    double ms = 0;
    trainer->train(trainer->env_steps() + 1, [&](const MetricsRow& row) { ms = row.extras[update_ms]; });
    state.SetIterationTime(ms / 1000);
  }
}
BENCHMARK(BM_PpoMinibatch)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(5);

}  // namespace
}  // namespace chore

BENCHMARK_MAIN();
