#pragma once
// Total-Lagrangian SPH (Bonet & Lok 1999; Vidal, Bonet & Huerta 2007):
// kernel sums over the reference configuration X with corrected gradients,
// deformation gradient F, first Piola-Kirchhoff stress P from a
// Saint Venant-Kirchhoff law (plane strain, F_zz = 1). Neighbours never
// change, and there is no tensile instability because the kernel never sees
// the deformed spacing. The method switch that compares the seed paper's
// updated-Lagrangian form against the form most solid SPH codes now use.
//
//   F_i   = sum_j V0_j (x_j - x_i) (x) B_i grad0_i W_ij
//   S     = lambda tr(E) I + 2 mu E,  E = (F^T F - I)/2,  P = F S
//   dv_i/dt = 1/rho0_i sum_j V0_j (P_i B_i + P_j B_j) grad0_i W_ij - sum_j m_j Pi_ij g_ij
#include <cstdint>
#include <vector>

#include "solver/core/cache_aligned.hpp"
#include "solver/core/row_chunks.hpp"
#include "solver/kernels/kernel.hpp"
#include "solver/physics/crack_face_contact.hpp"
#include "solver/physics/kernel_correction.hpp"

namespace gearsph {
struct Simulation;

// Fixed pairs of the reference configuration, each unordered pair once
// (row i holds the neighbours j > i, sorted), with everything that never
// changes cached per pair. Every pair loop writes to both ends through
// RowChunks: half the gathers and half the memory of full rows.
struct ReferencePairs {
  std::vector<std::uint32_t> rows, j;
  // Corrected gradients of the pair, G_ij = C_i grad0_i W_ij and
  // G_ji = C_j grad0_j W_ji (kernel_correction.hpp), side by side per pair:
  // g[4 k .. 4 k + 3] = G_ij x, y, G_ji x, y (one cache line for two
  // pairs; the loops scale them by the other end's reference volume).
  Column<double> g;
  // W(|X_ij|) / (2 |X_ij|^2), the hourglass control's pair weight, kept
  // only with it; and E / rho0 per particle (Ganzenmueller 2015).
  Column<double> w0;
  Column<double> e_over_rho0;
  Column<double> dw0;  // dW/dr at |X_ij|
  // The artificial viscosity of each pair in its reference form,
  // Pi_ij dW/dr / r = v (visc_a v - visc_b) with v = min(v_ij . x_ij, 0)
  // (artificial_viscosity.hpp, reference_viscosity).
  Column<double> visc_a, visc_b;
  // V0 P (the first Piola-Kirchhoff stress times the reference volume) per
  // particle, side by side: pv[4 i .. 4 i + 3] = xx, xy, yx, yy. With the
  // volume in it, a momentum pair takes V0_j P_j G_ji whole (no volume
  // gathered, four products fewer: 4 % of the gear's step).
  Column<double> pv;
  // x, y, vx, vy per particle, side by side (4 i + q), copied by the stress
  // pass for the momentum pass's gathers: one line a neighbour instead of
  // four, and fewer array addresses than registers (docs/speed-accuracy-history.md,
  // twelfth round).
  Column<double> state;
  Column<double> vol0;  // reference volume m/rho0, per particle
  // Smoothing length per particle, for graded particles only (empty when
  // every particle has the same h): a pair takes h_ij = (h_i + h_j) / 2.
  Column<double> hp;
  // One mass for every particle (a scene of one material and one spacing:
  // the seed paper's gear, the plate). The momentum pass then takes it as a
  // constant, a gather a pair fewer. The same arithmetic, so the state is
  // the same bit for bit as with the gathers. (The F pass ran slower with
  // its volume as a constant, and gathers it.)
  struct Uniform {
    bool all = false;
    double mass = 0.0;
  };
  Uniform uniform;
  // Per particle, side by side (4 i + q): the displacement x - X (refreshed
  // each step by the drift) and the reference volume V0, the F pass's
  // gathers of a neighbour in one line (4 i + 3 unused).
  Column<double> u;
  // sum_j V0_j G_ij / V0_i over all neighbours, per particle: P_i is
  // constant over i's pairs, so its share of the momentum sum is V0_i P_i
  // times this, with no per-pair work.
  Column<double> sgx, sgy;
  // Four sums per particle, side by side (4 i + q), that a pair adds to its
  // far end as one vector: the F pass's M = F - I (xx, xy, yx, yy), then
  // the momentum pass's stress share and viscous acceleration (x, y, x, y),
  // summed apart so that the pair-once sums end in the same order as full
  // rows would (docs/speed-accuracy-history.md, "a pair's four sums to its far end").
  Column<double> sums;
  // Hourglass accelerations.
  Column<double> hg_ax, hg_ay;
  // The threads' rows, cut twice, once for each pair pass's own spill
  // width and cost per row. The deformation cut serves the F and stress
  // passes, the momentum cut the momentum pass, the accelerations and the
  // kicks and drift, so that each pair pass ends evenly at its barrier.
  RowChunks deformation_chunks, momentum_chunks;
  // Per chunk: the largest J2 of its rows and where (stress pass), gathered
  // into Simulation::largest_j2; a cache line each, as each thread writes
  // its own every step.
  struct alignas(kCacheLine) ChunkPeak {
    double j2 = 0.0;
    long particle = -1;
  };
  std::vector<ChunkPeak> chunk_peaks;
  // The pairs a crack cut whose particles face each other across it, for
  // the faces' contact (physics/crack_face_contact.hpp); empty without cracks.
  std::vector<physics::CrackFacePair> faces;
  // Lame constants per body, so that the step divides nothing per particle.
  std::vector<double> lambda_body, mu_body;
  // What the pairs and gradients were built for. The stable-step estimate
  // builds them on the scene itself, before the run; the run's set-up then
  // keeps them if nothing here changed since (total_lagrangian_setup).
  struct Basis {
    std::size_t particles = 0;
    KernelType kernel = KernelType::SeedQuartic;
    double h = 0.0;
    GradientCorrection correction = GradientCorrection::None;
    bool keep_w = false;
    double h_min = 0.0, h_max = 0.0, h_sum = 0.0;  // per-particle h (graded)
    bool operator==(const Basis&) const = default;
  };
  Basis basis;
  bool built() const { return !rows.empty(); }
  std::size_t pairs() const { return j.size(); }
  // Directed interactions (i, j) and (j, i), as full rows would count them.
  std::size_t entries() const { return 2 * j.size(); }
};

namespace physics {
// Builds the reference pairs and the corrected gradients, and starts the
// per-step state afresh. Pairs from an earlier call are kept if built for
// as many particles with the same kernel, h, correction and hourglass
// setting: the stable-step estimate builds them just before the run's own
// set-up, on the same reference positions, which nothing moves between.
void total_lagrangian_setup(Simulation& sim);

// The passes of a step, for the step's table
// (integrate/step_total_lagrangian.cpp). Each runs over chunk c of the
// rows; a pass that reads other chunks' rows needs a barrier before it.
struct TotalLagrangianPasses {
  RowChunks& deformation;  // F, the stress, the normals and the peak
  RowChunks& momentum;     // the momentum sums and accelerations, and the kicks and drift
  bool hourglass;
};
// Plans the chunks for sim.threads (once per run); call outside the region.
TotalLagrangianPasses total_lagrangian_passes(Simulation& sim);
// The displacements u = x - X of particles lo .. hi into sim.reference.u,
// beside V0, for the F loop's gathers (one line a neighbour).
void displacements(Simulation& sim, std::size_t lo, std::size_t hi);
// The sums M of F = I + M, from the displacements.
void deformation_sums(Simulation& sim, TotalLagrangianPasses& tl, int c);
// F, P, the Cauchy stress and density per particle (Saint Venant-Kirchhoff).
void stress_from_deformation(Simulation& sim, TotalLagrangianPasses& tl, int c);
// The chunk's largest J2, for the run's peak stress without a scan of its own.
void note_peak_stress(Simulation& sim, TotalLagrangianPasses& tl, int c);
// After the step's passes: the chunks' largest J2 into sim.largest_j2.
void gather_largest_j2(Simulation& sim);
// The pair sums of the momentum equation; returns the power the hourglass
// control removes [W/m].
double momentum_sums(Simulation& sim, TotalLagrangianPasses& tl, int c);
// a from the pair sums, per particle; returns the power the viscosity
// removes [W/m].
double accelerations(Simulation& sim, TotalLagrangianPasses& tl, int c);

// F from current positions, then P and the Cauchy stress for output.
void total_lagrangian_stress(Simulation& sim);
// Accelerations from P, viscosity and (optional) hourglass control.
void total_lagrangian_momentum(Simulation& sim, double dt);
// Both of the above in one parallel region (the time step's call).
void total_lagrangian_forces(Simulation& sim, double dt);
}  // namespace physics
}  // namespace gearsph
