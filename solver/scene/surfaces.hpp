#pragma once
// Where each body's surface is, seen from its particles: the outward normal
// and the depth of every particle within reach of the surface (reference
// configuration). The surface contact model (physics/contact_surface.hpp)
// measures the gap between the true surfaces with it, so that a staircase of
// lattice particles slides along a smooth flank instead of a rough one.
//
// With an outline (gear profiles, rectangles, circles): exact closest-point
// distance and normal. Without: the normal of the SPH colour gradient
// -sum_j V_j grad_i W_ij and a depth of dx/2 (a lattice particle's cell).
#include "solver/scene/scene.hpp"

namespace gearsph::scenes {

void assign_surfaces(Scene& scene);

}  // namespace gearsph::scenes
