#pragma once
// Contact between bodies (method.md, "the seed paper's modified interaction
// force"). Particles of different bodies do not interact through the kernel
// unless the model is `kernel`; instead a pair closer than r0 feels a
// repulsive force along the line of centres, which is zero for r >= r0, so
// it can never pull: bodies cannot stick when they separate.
//
// Every model computes the pair force F_ij from quantities symmetric in
// (i, j), so F_ji = -F_ij and momentum is conserved to round-off.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/core/particles.hpp"

namespace gearsph {

struct Simulation;

enum class ContactModel {
  SeedPenalty,  // the seed paper's force, linear in the overlap (contact_seed_penalty.hpp)
  Surface,      // the same law on the gap between the true surfaces (contact_surface.hpp)
  Hertz,        // a Hertz-type penalty, overlap^(3/2) (contact_hertz.hpp)
  Kernel,       // bodies coupled through the SPH sums (shows the seed paper's adhesion)
  None,         // bodies pass through each other (only for single-body scenes)
};

const char* contact_model_name(ContactModel m);

struct ContactConfig {
  ContactModel model = ContactModel::SeedPenalty;
  double D = 1.0;              // dimensionless stiffness coefficient of the seed paper's force
  double damping_ratio = 0.0;  // normal dashpot, fraction of critical for one pair
  double r0_over_dx = 1.0;     // interaction range r0 (the seed paper: the initial spacing)
  // Surface model: radius, in the particle's spacings, of the surface
  // neighbourhood over which a contact is measured and its force spread
  // (contact_smoothing.hpp); 0 acts on single particles.
  double smoothing_spacings = 4.0;
  // Surface model: the normal law gives the continuum's near-field
  // compliance (contact_near_field.hpp); false: the linear law with D.
  bool near_field = true;
};

// A surface particle's smoothed position and velocity (contact_smoothing.hpp).
struct SmoothedPoint {
  double x = 0.0, y = 0.0, vx = 0.0, vy = 0.0;
  double ox = 0.0, oy = 0.0;  // the turned offset from the weighted centroid
  double c = 0.0, s = 0.0;    // C = sum W A.x, S = sum W A x x (the rotation's sums)
};

// What the contact did in the last step.
struct ContactState {
  std::int64_t active_pairs = 0;
  double max_penetration = 0.0;  // max (r0 - r) over active pairs [m]
  // Total contact force on each body [N per metre of thickness].
  std::vector<double> force_x, force_y;
  double stored_energy = 0.0;  // penalty energy in the active pairs [J/m]
  // Scratch of the surface model: each surface particle's outward normal
  // turned by its material rotation, computed once per step rather than per
  // pair (it was a sine and a cosine per pair end).
  Column<double> normal_x, normal_y;
  // The surface model's mask for the contact list: 1 for particles with a
  // surface within reach (finite depth), the only ones that can touch.
  std::vector<std::uint8_t> eligible;
  // Particles with a non-empty row in the contact list, in order, refreshed
  // with each build of the list (prepare_contact). The pair loop visits only
  // these, a sixth of the gear's particles; every other particle's contact
  // acceleration stays zero.
  std::vector<std::uint32_t> candidates;
  std::size_t prepared_build = 0;  // the list's build these belong to
  // Surface smoothing (contact_smoothing.hpp), built once per run from the
  // reference configuration: per source i its receivers k and weights W_ki
  // (rows sum to one), and the offset X_i - sum_k W_ki X_k that puts the
  // smoothed point back on particle i.
  bool smoothing_built = false;
  std::vector<std::uint32_t> smooth_rows, smooth_k;
  std::vector<double> smooth_w;
  // Per receiver, this step: the sum of its shares (add_contact_accelerations;
  // each thread its own rows).
  Column<double> spread_ax, spread_ay;
  std::vector<double> smooth_offset_x, smooth_offset_y;
  // 1 for a surface particle with no corner within one and a half of its
  // spacings along its surface (curved_pair's turning test on itself and
  // its receivers there): it may touch at a point between particles.
  std::vector<std::uint8_t> smooth_surface;
  // Each surface particle's log-moment Lambda (contact_near_field.hpp).
  std::vector<double> log_moment;
  // The receivers' weighted centroid in the reference configuration.
  std::vector<double> smooth_centre_x, smooth_centre_y;
  // Per source, this step: the moment M of its force about that centroid
  // times dtheta/dC and dtheta/dS of its receivers' rotation
  // (contact_smoothing.hpp); add_contact_accelerations applies the couple.
  std::vector<double> couple_c, couple_s;
  // Per candidate, this step: its smoothed point, found once before the
  // pair loop (each candidate has several partners).
  std::vector<SmoothedPoint> smoothed;
};

namespace physics {

// Models that act through the contact list (not through the kernel).
bool is_penalty(ContactModel m);

// The pair stiffness dF/d(overlap) at zero overlap... for the time-step bound:
// the stiffest contact oscillator, omega^2 = k (1/m_i + 1/m_j) times the
// number of partners a particle can have within r0.
double contact_time_step_limit(const Simulation& sim);

// Adds contact accelerations to ext_ax/ext_ay (which the caller zeroed) and
// fills sim.contact_state; dissipated energy goes to the ledger. The
// passes below as a table of their own (the first step's forces, tests);
// the time step's tables run them among theirs.
void contact_forces(Simulation& sim, double dt);

// What one thread's share of the contact pairs did; summed over threads in
// thread order by the executor (core/passes.hpp).
struct ContactTally {
  static constexpr int kMaxBodies = 8;  // bodies beyond this get no force total
  std::int64_t active = 0;
  double stored = 0.0, dissipated = 0.0, deepest = 0.0;
  double fx[kMaxBodies] = {}, fy[kMaxBodies] = {};
  ContactTally& operator+=(const ContactTally& o);
};

// The mask for the contact list's build (NeighbourList::build): with the
// surface model only particles with a surface within reach may pair (an
// interior particle's pairs were skipped each step, half the list's
// entries in the gear); nullptr (all) otherwise.
const std::uint8_t* contact_eligible(Simulation& sim);
// After each build of the contact list, outside any parallel region: sizes
// the surface model's normals, lists the candidates and zeroes every
// particle's contact acceleration. A no-op if done for this build already.
void prepare_contact(Simulation& sim);
// Surface model: particle i's outward normal turned by its material
// rotation, given as its cosine and sine, into the state's scratch. The
// total-Lagrangian stress pass turns them by F's rotation; contact_forces
// turns them by the updated-Lagrangian angle rot.
inline void turn_normal(double cos_t, double sin_t, double nx0, double ny0, double& nx,
                        double& ny) {
  nx = cos_t * nx0 - sin_t * ny0;
  ny = sin_t * nx0 + cos_t * ny0;
}
inline void turn_surface_normal(const Particles& p, ContactState& state, std::size_t i,
                                double cos_t, double sin_t) {
  turn_normal(cos_t, sin_t, p.surf_nx[i], p.surf_ny[i], state.normal_x[i], state.normal_y[i]);
}
// Total-Lagrangian runs: the normals of particles lo .. hi that have
// contact candidates, turned by the rotation of the polar decomposition of
// their deformation gradient F = R U (after the stress pass has set F).
void turn_contact_normals(Simulation& sim, std::size_t lo, std::size_t hi);
// Updated-Lagrangian runs: the normals of particles lo .. hi that have
// contact candidates, turned by their material rotation angle rot.
void turn_contact_normals_by_rot(Simulation& sim, std::size_t lo, std::size_t hi);
// With surface smoothing, the smoothed point of share `index` of `of` of the
// candidates (after prepare_contact), read by every candidate's pairs: a
// barrier must follow before contact_pairs (contact_pairs.cpp).
void smooth_contact_points(Simulation& sim, int index, int of);
// The pair loop over share `index` of `of` of the candidates: contact_ax,
// contact_ay of each, and this share of the totals. Reads positions,
// velocities, density, the turned normals and the smoothed points.
void contact_pairs(Simulation& sim, double dt, int index, int of, ContactTally& tally);
// Both of the above over every candidate, on the calling thread.
void contact_pairs(Simulation& sim, double dt, ContactTally& tally);
// Contact accelerations of particles lo .. hi added to ext_ax/ext_ay: each
// particle's own (contact_ax), or with surface smoothing the share of the
// forces of the sources in its neighbourhood. Reads what contact_pairs wrote
// (call after a barrier).
void add_contact_accelerations(Simulation& sim, std::size_t lo, std::size_t hi);
// Whether the contact forces are spread (surface model with smoothing).
bool contact_smoothing(const Simulation& sim);
// Smoothed position and velocity of surface particle i (contact_smoothing.hpp):
// the offset turned by its receivers' best-fit rotation. Needs the tables
// prepare_contact builds.
SmoothedPoint smoothed_point(const Particles& p, const ContactState& st, std::size_t i);
// The totals of all threads into sim.contact_state and the energy ledger.
void record_contact(Simulation& sim, const ContactTally& tally);

}  // namespace physics
}  // namespace gearsph
