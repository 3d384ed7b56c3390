#pragma once
#include <cstddef>

// Divergence guard: a run that produces NaN/Inf or throws a particle out of
// its domain stops with the step, the particle and the quantity.
namespace gearsph {
struct Simulation;
namespace diagnostics {
// Scans every particle; throws DivergenceError naming the first bad one
// (and, if given, the pass of the step that found it).
void check_health(const Simulation& sim, const char* found_by = nullptr);
// The particles lo .. hi outside the domain or at a non-finite position
// (the step's domain check).
std::size_t outside_domain(const Simulation& sim, std::size_t lo, std::size_t hi);
// Called when the pass `found_by` found a particle outside the domain:
// always throws, naming the particle, the quantity and the pass.
[[noreturn]] void throw_divergence(const Simulation& sim, const char* found_by);
}  // namespace diagnostics
}  // namespace gearsph
