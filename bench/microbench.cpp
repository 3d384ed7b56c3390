// Google Benchmark micro-benchmarks: kernel evaluation and the pair loops.
#include <benchmark/benchmark.h>

#include <cmath>

#include "solver/kernels/kernel.hpp"

namespace {

template <class Shape>
void BM_KernelGradient(benchmark::State& state) {
  gearsph::Kernel2D<Shape> k(1.0);
  double r = 0.05, sum = 0;
  for (auto _ : state) {
    for (int i = 0; i < 256; ++i) {
      sum += k.dW(r);
      r += 0.011;
      if (r > k.radius) r -= k.radius;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(state.iterations() * 256);
}

BENCHMARK(BM_KernelGradient<gearsph::kernels::SeedQuartic>);
BENCHMARK(BM_KernelGradient<gearsph::kernels::CubicSpline>);
BENCHMARK(BM_KernelGradient<gearsph::kernels::QuinticSpline>);
BENCHMARK(BM_KernelGradient<gearsph::kernels::WendlandC2>);

}  // namespace

BENCHMARK_MAIN();
