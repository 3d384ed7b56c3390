#pragma once
// The cut a crack makes in the total-Lagrangian reference pairs: a pair
// whose reference segment X_i - X_j crosses a crack of its body does not
// interact (geometry/crack.hpp, the visibility criterion). Applied where
// the pairs are built (total_lagrangian_setup.cpp), before the moment
// matrices, so that the gradient correction of a particle on a face sees
// a free surface there, and every pair term (stress divergence, viscosity,
// hourglass control) stops at the faces alike.
//
// Near the tip, visibility leaves a line of discontinuity ahead of the tip
// in the kernel approximation (Belytschko, Krongauz, Fleming, Organ & Liu
// 1996, Comput. Methods Appl. Mech. Engrg. 139, section 4: diffraction and
// transparency smooth it). With the corrected gradients the particles'
// strains stay first-order consistent on either side of that line, the
// error is confined to a support around the tip, and the stress intensity
// factors are read by a domain integral that leaves out the tip's support
// (diagnostics/stress_intensity.hpp): the plain criterion, as in the
// cracking particles of Rabczuk & Belytschko (2004, IJNME 61), is kept.
#include <cstdint>
#include <vector>

#include "solver/core/particles.hpp"
#include "solver/geometry/crack.hpp"

namespace gearsph::physics {

// A pair the crack cut, with the unit normal of the crack's segment it
// crosses, turned from i's side towards j's.
struct CutPair {
  std::uint32_t i = 0, j = 0;
  double nx = 0.0, ny = 0.0;
};

// Removes from the pair list (rows, js: row i holds the partners j of i, a
// CSR list) every pair of one body whose reference segment crosses one of
// that body's cracks. Returns the number of pairs removed; with `cut_out`,
// appends them there.
std::size_t cut_pairs_across_cracks(const Particles& p, const std::vector<geometry::Crack>& cracks,
                                    std::vector<std::uint32_t>& rows,
                                    std::vector<std::uint32_t>& js,
                                    std::vector<CutPair>* cut_out = nullptr);

}  // namespace gearsph::physics
