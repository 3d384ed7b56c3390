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
  // Corrected gradients times the neighbour's reference volume V0_j, the
  // only form in which the pair loops use them (one product and one gather
  // of V0_j fewer per pair).
  std::vector<double> gix, giy;  // V0_j B_i grad0_i W_ij
  std::vector<double> gjx, gjy;  // V0_j B_j grad0_i W_ij
  std::vector<double> w0;        // W(|X_ij|), kept only with hourglass control
  std::vector<double> dw0;       // dW/dr at |X_ij|
  std::vector<double> px, py;    // P (first Piola-Kirchhoff), cached per particle:
  std::vector<double> pyx, pyy;  // P = [[px, py], [pyx, pyy]]
  std::vector<double> vol0;      // reference volume m/rho0, per particle
  std::vector<double> ux, uy;    // displacement x - X, per particle, refreshed each step
  // sum_j V0_j B_i grad0_i W_ij per particle: P_i is constant over row i, so
  // its share of the momentum sum is P_i times this, with no per-pair work.
  std::vector<double> sgx, sgy;
  // Rows are sorted by j: entries upper[i] .. rows[i+1] of row i have j > i,
  // each unordered pair once (the viscosity is evaluated once per pair).
  std::vector<std::uint32_t> upper;
  // Per-thread sums of the pair-once viscosity: [threads][x | y][n].
  std::vector<double> pair_acc;
  // Lame constants per body, so that the step divides nothing per particle.
  std::vector<double> lambda_body, mu_body;
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
