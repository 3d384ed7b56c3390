#pragma once
// Hypoelastic stress update with the Jaumann rate, plane strain.
//   dp/dt = -K tr(D)          (through the density: p = K (rho/rho0 - 1))
//   dS/dt = 2G (D - tr(D)/3 I) + Omega S + S Omega^T
// D and Omega are the symmetric and skew parts of L = grad v. Plane strain:
// D_zz = 0, the deviator uses 1/3 (a 3D deviator, not 1/dim), S_zz evolves.
// The rotation part is integrated with the Hughes-Winget (1980) midpoint
// rotation Q = (I - dt/2 Omega)^{-1} (I + dt/2 Omega): exactly orthogonal, so
// a rigidly rotating stress keeps its magnitude, and second-order accurate.
#include <cstddef>

namespace gearsph {
struct Simulation;
namespace physics {
// Advances rho, p and S over dt from the rates in the particle arrays, then
// caches (sigma/rho^2) B and the artificial stress for the momentum loop.
void update_stress(Simulation& sim, double dt);
// The same for particles lo .. hi (a pass of the step's table).
void update_stress(Simulation& sim, double dt, std::size_t lo, std::size_t hi);
// The same caches, from the current stress, without advancing it.
void prepare_momentum(Simulation& sim);
}  // namespace physics
}  // namespace gearsph
