// Google Benchmark micro-benchmarks: kernel evaluation and the pair loops.
#include <benchmark/benchmark.h>

#include <cmath>

#include <nlohmann/json.hpp>

#include "solver/integrate/integrator.hpp"
#include "solver/job/job.hpp"
#include "solver/kernels/kernel.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/total_lagrangian.hpp"

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

// The pair loops on a prepared scene, one thread: the plate of validation.md
// section 5 at H/dx = 10 (1250 particles) and the seed paper's gear case. Items
// are directed pair entries, so items/s is pair interactions per second.
gearsph::PreparedJob prepared(const char* scene) {
  const nlohmann::json plate = {
      {"scene", {{"type", "plate"}, {"length_m", 0.2}, {"thickness_m", 0.02}, {"Vf", 0.01}}}};
  nlohmann::json gear = {{"scene", {{"type", "rack_pinion"}}}};
  // The gear with hourglass control (Ganzenmueller 2015), to price it.
  if (std::string(scene) == "gear_hourglass")
    gear["method"] = {{"hourglass", {{"coefficient", 0.5}}}};
  gearsph::PreparedJob job = gearsph::prepare_job(std::string(scene) == "plate" ? plate : gear, 1);
  gearsph::integrate::initialise(job.scene.sim);
  for (int s = 0; s < 10; ++s) gearsph::integrate::step(job.scene.sim);
  return job;
}

void BM_TotalLagrangianStress(benchmark::State& state, const char* scene) {
  gearsph::PreparedJob job = prepared(scene);
  for (auto _ : state) gearsph::physics::total_lagrangian_stress(job.scene.sim);
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(job.scene.sim.reference.entries()));
}

void BM_TotalLagrangianMomentum(benchmark::State& state, const char* scene) {
  gearsph::PreparedJob job = prepared(scene);
  for (auto _ : state) gearsph::physics::total_lagrangian_momentum(job.scene.sim, 0.0);
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(job.scene.sim.reference.entries()));
}

void BM_Contact(benchmark::State& state) {
  gearsph::PreparedJob job = prepared("gear");
  for (auto _ : state) gearsph::physics::contact_forces(job.scene.sim, 0.0);
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(job.scene.sim.contacts.entries()));
}

void BM_Step(benchmark::State& state, const char* scene) {
  gearsph::PreparedJob job = prepared(scene);
  for (auto _ : state) gearsph::integrate::step(job.scene.sim);
  state.SetItemsProcessed(state.iterations() *
                          static_cast<std::int64_t>(job.scene.sim.particles.n));
}

BENCHMARK_CAPTURE(BM_TotalLagrangianStress, plate, "plate");
BENCHMARK_CAPTURE(BM_TotalLagrangianStress, gear, "gear");
BENCHMARK_CAPTURE(BM_TotalLagrangianMomentum, plate, "plate");
BENCHMARK_CAPTURE(BM_TotalLagrangianMomentum, gear, "gear");
BENCHMARK_CAPTURE(BM_TotalLagrangianMomentum, gear_hourglass, "gear_hourglass");
BENCHMARK(BM_Contact);
BENCHMARK_CAPTURE(BM_Step, plate, "plate");
BENCHMARK_CAPTURE(BM_Step, gear, "gear");
BENCHMARK_CAPTURE(BM_Step, gear_hourglass, "gear_hourglass");

}  // namespace

BENCHMARK_MAIN();
