#pragma once
// The particle store: one array per quantity (structure of arrays), sized
// once when the scene is built. Nothing here allocates during a time step.
//
// Conventions: 2D plane strain, SI units, quantities per unit thickness
// (mass in kg/m). Stress is split into pressure p and deviator S with the
// out-of-plane component S_zz kept (plane strain: eps_zz = 0, S_zz != 0).
#include <cstddef>
#include <cstdint>
#include <vector>

#include "solver/core/cache_aligned.hpp"

namespace gearsph {

// Particles deeper than this many spacings below their body's surface never
// take part in contact (scene/surfaces.hpp finds the depths).
constexpr double kSurfaceReachOverDx = 1.5;

struct Particles {
  std::size_t n = 0;

  // Identity and bookkeeping.
  std::vector<std::int32_t> body;     // index into Scene::bodies
  std::vector<std::uint16_t> motion;  // index into Scene::motions (0 = free)

  // Reference configuration (initial positions; TL reference).
  Column<double> x0, y0;
  Column<double> mass;  // [kg/m]
  Column<double> rho0;  // [kg/m^3]
  Column<double> cs;    // signal (P-wave) speed of the material [m/s]
  // Particle spacing around the particle [m]: the lattice spacing, or the
  // local spacing of graded body-fitted particles; the smoothing length is
  // h_i = h_over_dx * spacing_i.
  Column<double> spacing;

  // State.
  Column<double> x, y;                // position [m]
  Column<double> vx, vy;              // velocity [m/s]
  Column<double> rho;                 // density [kg/m^3]
  Column<double> p;                   // pressure [Pa], positive in compression
  Column<double> sxx, syy, sxy, szz;  // deviatoric stress [Pa]

  // Rates and per-step work arrays.
  Column<double> ax, ay;              // acceleration [m/s^2]
  Column<double> drho;                // density rate [kg/m^3/s]
  Column<double> lxx, lxy, lyx, lyy;  // velocity gradient L = grad v [1/s]
  // Gradient correction C = [b | bq] (physics/kernel_correction.hpp):
  // linear block b (2x2) and quadratic block bq (2x3, rows x and y).
  Column<double> bxx, bxy, byx, byy;
  Column<double> bqx0, bqx1, bqx2, bqy0, bqy1, bqy2;
  std::vector<std::uint8_t> correction_order;  // GradientCorrection actually used
  Column<double> fxx, fxy, fyx, fyy;           // deformation gradient (total Lagrangian)
  Column<double> rxx, ryy, rxy;                // artificial stress R_i / rho^2 (Monaghan 2000)
  // (sigma_i / rho_i^2) C_i, cached for the momentum loop: linear and quadratic blocks.
  Column<double> qxx, qxy, qyx, qyy;
  Column<double> qqx0, qqx1, qqx2, qqy0, qqy1, qqy2;
  Column<double> ext_ax, ext_ay;          // external (contact, load) accel. this step
  Column<double> load_ax, load_ay;        // applied loads, as accelerations (times the ramp)
  Column<double> contact_ax, contact_ay;  // contact part of ext_ax/ext_ay, last step
  // Surface of the body, for contact (scene/surfaces.hpp): outward normal in
  // the reference configuration and depth of the particle below the surface;
  // depth = +inf for interior particles. rot: current rotation angle of the
  // material around the particle (CCW), which turns the normal (updated
  // Lagrangian; the total-Lagrangian stress pass turns it by F's rotation).
  Column<double> surf_nx, surf_ny, surf_depth, rot;
  // Curvature of the outline at the particle [1/m], positive where the body
  // is convex, averaged over the particle's spacing along the outline; 0 for
  // surfaces found without an outline (contact_near_field.hpp). Its rate of
  // change along the particle's own tangent (-n_y, n_x) [1/m^2]: the
  // outline's cubic term (contact_surface.hpp, curved_surface_pair). And
  // the curvature a Hertz contact there meets: the same mean without the
  // turn of a corner within the spacing (a sharp corner has no Hertz radius;
  // its turn over a spacing is one that follows the spacing), a corner's
  // own particle taking its two sides' (the near field's curvature,
  // contact_near_field.hpp).
  Column<double> surf_curvature, surf_curvature_rate, surf_hertz_curvature;

  void resize(std::size_t count);
  // Frees the arrays only the updated-Lagrangian step uses (density rate,
  // velocity gradient, gradient correction, artificial stress, the cached
  // sigma/rho^2 C blocks, the material rotation): 29 doubles a particle a
  // total-Lagrangian run never touches (its corrections live in its pair
  // gradients, and its stress pass turns the contact normals by F). A later
  // resize() brings them back.
  void release_updated_lagrangian();
  void add(double px, double py, double m, double density, int body_index, int motion_index,
           double particle_spacing);

  double volume(std::size_t i) const { return mass[i] / rho[i]; }

  // sigma = -p I + S, in-plane components and zz.
  double sigma_xx(std::size_t i) const { return -p[i] + sxx[i]; }
  double sigma_yy(std::size_t i) const { return -p[i] + syy[i]; }
  double sigma_xy(std::size_t i) const { return sxy[i]; }
  double sigma_zz(std::size_t i) const { return -p[i] + szz[i]; }
  // Second invariant of the deviator, J2 = S:S / 2, S with all three normal
  // components; von Mises equivalent stress sqrt(3 J2).
  double j2(std::size_t i) const {
    return 0.5 * (sxx[i] * sxx[i] + syy[i] * syy[i] + szz[i] * szz[i]) + sxy[i] * sxy[i];
  }
  double von_mises(std::size_t i) const;
};

}  // namespace gearsph
