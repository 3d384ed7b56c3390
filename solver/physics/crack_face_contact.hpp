#pragma once
// Contact between a crack's faces (docs/cracks.md): where the faces close
// they must not pass through each other, and they must not stick. In the
// total-Lagrangian frame the faces are known from the reference pairs the
// crack cut (physics/crack_cut.hpp): a cut pair (i, j) close enough to face
// each other, with the crack's normal n (from i's side to j's) and its
// reference gap g0 = (X_j - X_i) . n, pushes its ends apart along n with
//
//   f = k (g0 - g)  when  g = (x_j - x_i) . n < g0  (the faces closing),
//   f = 0           otherwise (an open crack carries no tension across),
//
// equal and opposite on i and j, frictionless (no force along the faces).
// The stiffness k gives a closed face the normal stiffness of the uncut
// material: a uniform closing strain eps across the faces, g0 - g = eps g0
// for every pair, puts the traction E' eps on a face particle's spacing
// (E' = E / (1 - nu^2), plane strain) when k = E' dx / G, G the sum of the
// particle's pairs' reference gaps (the mean of both ends' sums). The normal
// is the reference one: rotations of the faces are taken small.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/physics/crack_cut.hpp"

namespace gearsph {
struct Simulation;
}

namespace gearsph::physics {

struct CrackFacePair {
  std::uint32_t i = 0, j = 0;
  double nx = 0.0, ny = 0.0;  // the crack's unit normal, from i towards j
  double gap = 0.0;           // reference gap along n [m]
  double stiffness = 0.0;     // k [N/m per m of thickness, i.e. Pa]
};

// The face pairs among the cut ones: those at most kFaceReach spacings
// apart (a lattice's facing and diagonal neighbours), with their stiffness.
std::vector<CrackFacePair> crack_face_pairs(const Simulation& sim, const std::vector<CutPair>& cut);

// The faces' contact force on particle pairs (f above), added to the external
// accelerations ext_ax, ext_ay. Returns the number of closed pairs.
std::size_t crack_face_contact(Simulation& sim);

// The pair's contact force f above, >= 0 (on j along n, on i against it).
double crack_face_force(const Simulation& sim, const CrackFacePair& f);

// The energy the closed face pairs store, sum of k (g0 - g)^2 / 2 [J/m].
double crack_face_energy(const Simulation& sim);

}  // namespace gearsph::physics
