#pragma once
// Total-Lagrangian SPH (Bonet & Lok 1999; Vidal, Bonet & Huerta 2007):
// kernel sums over the reference configuration X with corrected gradients,
// deformation gradient F, first Piola-Kirchhoff stress P from a
// Saint Venant-Kirchhoff law (plane strain, F_zz = 1). Neighbours never
// change, and there is no tensile instability because the kernel never sees
// the deformed spacing. The method switch that compares the paper's
// updated-Lagrangian form against the form most solid SPH codes now use.
//
//   F_i   = sum_j V0_j (x_j - x_i) (x) B_i grad0_i W_ij
//   S     = lambda tr(E) I + 2 mu E,  E = (F^T F - I)/2,  P = F S
//   dv_i/dt = 1/rho0_i sum_j V0_j (P_i B_i + P_j B_j) grad0_i W_ij - sum_j m_j Pi_ij g_ij
#include <cstdint>
#include <vector>

namespace gearsph {
struct Simulation;

// Fixed pairs of the reference configuration, with everything that never
// changes cached per entry.
struct ReferencePairs {
  std::vector<std::uint32_t> rows, j;
  std::vector<double> gix, giy;  // B_i grad0_i W_ij
  std::vector<double> gjx, gjy;  // B_j grad0_i W_ij
  std::vector<double> w0;        // W(|X_ij|)
  std::vector<double> dw0;       // dW/dr at |X_ij|
  std::vector<double> px, py;    // P (first Piola-Kirchhoff), cached per particle:
  std::vector<double> pyx, pyy;  // P = [[px, py], [pyx, pyy]]
  bool built() const { return !rows.empty(); }
};

namespace physics {
// Builds the reference pairs and the corrected gradients (once per run).
void total_lagrangian_setup(Simulation& sim);
// F from current positions, then P and the Cauchy stress for output.
void total_lagrangian_stress(Simulation& sim);
// Accelerations from P, viscosity and (optional) hourglass control.
void total_lagrangian_momentum(Simulation& sim, double dt);
}  // namespace physics
}  // namespace gearsph
