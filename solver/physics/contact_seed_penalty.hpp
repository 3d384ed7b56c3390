#pragma once
// The seed paper's interaction force between a pinion particle i and a rack
// particle j, read dimensionally (method.md): an acceleration
//   a_i = D (E_ij / rho_i) (r0 - r) / r0^2 n_ij,  n_ij = (x_i - x_j)/r,  r < r0
// and zero for r >= r0. As a pair force with equal volumes this is
//   F_ij = D E_ij V_ij (r0 - r) / r0^2 n_ij
// with V_ij the harmonic mean of the two particle volumes (per unit
// thickness), so that F_ji = -F_ij also for unequal particles. E_ij is the
// pair's contact modulus E* (Hertz: 1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j).
// "D is related to relative velocity" is read as the optional dashpot of
// contact.hpp, not folded into D.
namespace gearsph::physics {

// Normal force magnitude (>= 0) and the pair stiffness k = dF/d(overlap).
struct PairLaw {
  double force;
  double stiffness;
  double energy;  // stored penalty energy
};

inline PairLaw seed_penalty(double D, double e_star, double volume, double r0, double overlap) {
  const double k = D * e_star * volume / (r0 * r0);
  return {k * overlap, k, 0.5 * k * overlap * overlap};
}

}  // namespace gearsph::physics
