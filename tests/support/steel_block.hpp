#pragma once
// A free square block of n x n steel particles, 1 mm apart, at rest and
// unconstrained: the scene of the pair-loop tests, which then add their own
// random velocities and position jiggle.
#include "solver/physics/simulation.hpp"

namespace gearsph::testing_support {

inline Simulation steel_block(int n, Formulation formulation, GradientCorrection correction,
                              double h_over_dx, int threads) {
  Simulation sim;
  const Material mat{2e11, 0.3, 7800};
  Body b;
  b.name = "block";
  b.material = mat;
  sim.bodies.push_back(b);
  const double dx = 1e-3;
  sim.discretization.dx = dx;
  sim.discretization.h_over_dx = h_over_dx;
  sim.discretization.kernel = KernelType::SeedQuartic;
  sim.method.formulation = formulation;
  sim.method.correction = correction;
  sim.threads = threads;
  for (int a = 0; a < n; ++a) {
    for (int c = 0; c < n; ++c) {
      sim.particles.add((a + 0.5) * dx, (c + 0.5) * dx, mat.rho0 * dx * dx, mat.rho0, 0, 0, dx);
    }
  }
  for (std::size_t i = 0; i < sim.particles.n; ++i) sim.particles.cs[i] = mat.p_wave_speed();
  sim.bodies[0].end = sim.particles.n;
  sim.domain = {-1.0, -1.0, 1.0, 1.0};
  return sim;
}

}  // namespace gearsph::testing_support
