#pragma once
// Stress intensity factors K_I and K_II at a crack tip by the interaction
// integral (Yau, Wang & Corten 1980, J. Appl. Mech. 47, 335-341), in the
// domain form of Moran & Shih (1987, Eng. Fract. Mech. 27) and Shih &
// Asaro (1988): superpose on the particles' field an auxiliary Williams
// field of unit K_I (or K_II); the cross term of the J-integral is
//
//   I = int_A [sigma_ij u^aux_i,1 + sigma^aux_ij u_i,1 - sigma_ik eps^aux_ik delta_1j] q,j dA
//     = 2 (K_I K^aux_I + K_II K^aux_II) / E',   E' = E / (1 - nu^2) (plane strain),
//
// in the tip's frame (x1 along the crack's advance, x2 across it). The
// weight q is 1 inside r_in, 0 beyond r_out, and between them a cosine
// taper whose gradient is continuous, so that summing particle volumes
// integrates it without the jumps of a linear ramp at the ring's edges.
// Only the ring r_in < r < r_out contributes: the particles of the tip's
// own support, where the visibility criterion and the singularity spoil
// the discrete field, are left out, and the faces are traction-free, as
// the domain form assumes. The crack must be straight inside r_out.
#include <cstddef>
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph {
struct Simulation;
}

namespace gearsph::diagnostics {

struct CrackTip {
  geometry::Point tip;        // reference position [m]
  geometry::Point direction;  // unit vector of the crack's advance at the tip
};

struct DomainRing {
  double r_in = 0.0, r_out = 0.0;  // [m]
};

// One quadrature point of the domain: a particle's reference position and
// volume, its Cauchy stress and its displacement gradient H = du/dX, in
// global axes.
struct DomainPoint {
  geometry::Point X;
  double volume = 0.0;
  double sxx = 0.0, syy = 0.0, sxy = 0.0;
  double hxx = 0.0, hxy = 0.0, hyx = 0.0, hyy = 0.0;  // h_ab = du_a / dX_b
};

struct StressIntensity {
  double K_I = 0.0, K_II = 0.0;  // [Pa m^0.5]
  std::size_t points = 0;        // quadrature points in the ring
};

// The plane-strain Williams near-tip field of K_I and K_II at a point of the
// tip's frame (Anderson, Fracture Mechanics, 3rd ed., table 2.1/2.2):
// stress and displacement gradient du_a/dx_b, both in that frame.
struct WilliamsField {
  double s11 = 0.0, s22 = 0.0, s12 = 0.0;
  double h11 = 0.0, h12 = 0.0, h21 = 0.0, h22 = 0.0;
};
WilliamsField williams_field(double K_I, double K_II, double x1, double x2, double E, double nu);

// K_I and K_II from given quadrature points (plane strain, E and nu).
StressIntensity interaction_integral(const std::vector<DomainPoint>& points, const CrackTip& tip,
                                     const DomainRing& ring, double E, double nu);

// The same from a total-Lagrangian run's particles of `body`: the stress of
// each particle and its displacement gradient from the reference pairs (so
// that the crack's cut holds for it too).
StressIntensity interaction_integral(const Simulation& sim, int body, const CrackTip& tip,
                                     const DomainRing& ring);

}  // namespace gearsph::diagnostics
