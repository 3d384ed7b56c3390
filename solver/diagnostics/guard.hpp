#pragma once
// Divergence guard: a run that produces NaN/Inf or throws a particle out of
// its domain stops with the step, the particle and the quantity.
namespace gearsph {
struct Simulation;
namespace diagnostics {
// Scans every particle; throws DivergenceError naming the first bad one.
void check_health(const Simulation& sim);
// Called when the drift found a particle outside the domain: always throws.
[[noreturn]] void throw_divergence(const Simulation& sim);
}  // namespace diagnostics
}  // namespace gearsph
