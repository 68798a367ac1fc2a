// One SAC gradient update of RL-VMC as `chore train` runs it: CollectTrash,
// 128x128 RGB + proprioception + is-grasping, batch 64, 256x256 MLPs
// (Table A.11), on a full replay buffer, one torch thread:
//   build/tests/chore_sac_bench [--benchmark_repetitions=5]
// The time is the trainer's own `update_ms` for each update (manual time):
// the env step between two updates is not counted. BM_FmaPeak is this core's
// ceiling for the update's convolutions: fp32 multiply-adds per second.
#include <benchmark/benchmark.h>
#include <malloc.h>

#include <algorithm>

#include "training/trainer.hpp"

namespace chore {
namespace {

void BM_SacUpdate(benchmark::State& state) {
  TrainConfig config = baseline_config("rl-vmc", "collect_trash");
  config.threads = 1;
  config.sac.learning_starts = config.sac.buffer;  // fill the replay buffer first
  config.sac.report_every = 1;                     // one metrics row per update
  const auto trainer = make_trainer(config);
  const auto names = trainer->extra_metric_names();
  const auto update_ms = std::find(names.begin(), names.end(), "update_ms") - names.begin();
  trainer->train(config.sac.learning_starts, [](const MetricsRow&) {});
  for (auto _ : state) {
    double ms = 0;
    trainer->train(trainer->env_steps() + 1, [&](const MetricsRow& row) { ms = row.extras[update_ms]; });
    state.SetIterationTime(ms / 1000);
  }
}
BENCHMARK(BM_SacUpdate)->UseManualTime()->Unit(benchmark::kMillisecond)->Iterations(50);

// Twelve independent chains of 16-lane multiply-adds, enough in flight to
// fill the FMA pipes (contracted to fused multiply-adds with AVX-512 or AVX2).
using Floats16 = float __attribute__((vector_size(64)));

__attribute__((target_clones("avx512f", "arch=haswell", "default"))) float fma_chains(int64_t rounds, float seed) {
  Floats16 acc[12];
  for (int i = 0; i < 12; ++i) acc[i] = Floats16{} + seed * i;
  const Floats16 a = Floats16{} + 0.9999f, b = Floats16{} + 1e-6f;
  for (int64_t k = 0; k < rounds; ++k) {
#pragma GCC unroll 12
    for (int i = 0; i < 12; ++i) acc[i] = acc[i] * a + b;
  }
  float sum = 0;
  for (int i = 0; i < 12; ++i) sum += acc[i][i];
  return sum;
}

void BM_FmaPeak(benchmark::State& state) {
  constexpr int64_t kRounds = 10'000'000;
  for (auto _ : state) benchmark::DoNotOptimize(fma_chains(kRounds, 0.001f));
  state.counters["multiply_adds_per_s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * kRounds * 12 * 16, benchmark::Counter::kIsRate,
                         benchmark::Counter::kIs1000);
}
BENCHMARK(BM_FmaPeak)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace chore

int main(int argc, char** argv) {
  // As the chore executable does (app/main.cpp): freed tensors stay
  // mapped, else each update pays page faults for its fresh batches.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  mallopt(M_TOP_PAD, 64 << 20);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
