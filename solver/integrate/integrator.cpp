#include "solver/integrate/integrator.hpp"

#include <malloc.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "solver/core/passes.hpp"
#include "solver/core/simulation.hpp"
#include "solver/diagnostics/guard.hpp"
#include "solver/integrate/motion.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/external_loads.hpp"
#include "solver/physics/momentum.hpp"
#include "solver/physics/stress_rate.hpp"
#include "solver/physics/total_lagrangian.hpp"
#include "solver/physics/velocity_gradient.hpp"
#include "solver/scene/surfaces.hpp"

namespace gearsph::integrate {

namespace {

// Verlet skin: a tenth of the spacing lasts thousands of steps.
constexpr double kSkinOverDx = 0.1;

bool total_lagrangian(const Simulation& sim) {
  return sim.method.formulation == Formulation::TotalLagrangian;
}

bool penalty_contact(const Simulation& sim) {
  return sim.bodies.size() > 1 && physics::is_penalty(sim.contact.model);
}

// How far apart two contact candidates may be. Lattice surfaces reach 1.5
// spacings into each body, plus the hat's spacing across; body-fitted
// surfaces are their outline rows (depth 0), so twice the coarsest spacing
// of a surface particle covers the hat and a slanted approach.
double contact_reach(const Simulation& sim) {
  const double dx = sim.discretization.dx;
  if (sim.contact.model != ContactModel::Surface) return sim.contact.r0_over_dx * dx;
  const bool fitted =
      std::any_of(sim.bodies.begin(), sim.bodies.end(), [](const Body& b) { return b.fitted; });
  if (!fitted) return (2.0 * scenes::kSurfaceReachOverDx + 1.0) * dx;
  const Particles& p = sim.particles;
  double reach = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (std::isfinite(p.surf_depth[i]))
      reach = std::max(reach, 2.0 * (p.surf_depth[i] + p.spacing[i]));
  }
  return reach;
}

// `contacts_moved`: the drift found a particle beyond half the contact
// list's skin (kick_drift), so the list needs no scan of its own here.
void refresh_neighbours(Simulation& sim, bool contacts_moved) {
  const double skin = kSkinOverDx * sim.discretization.dx;
  if (!total_lagrangian(sim) &&
      (sim.neighbours.builds() == 0 || sim.neighbours.needs_rebuild(sim.particles))) {
    // Kernel interactions stay inside a body unless the contact model is the
    // kernel itself (the coupling whose adhesion the seed paper avoids).
    const PairSelection selection = sim.contact.model == ContactModel::Kernel
                                        ? PairSelection::AnyBody
                                        : PairSelection::SameBody;
    const double radius = kernel_support(sim.discretization.kernel) * sim.h();
    sim.neighbours.set_skin(skin);
    sim.neighbours.build(sim.particles, radius + skin, selection, /*reference=*/false, sim.threads);
  }
  if (penalty_contact(sim) && (contacts_moved || !sim.contacts.built_for(sim.particles.n))) {
    sim.contacts.set_skin(skin);
    const double reach = contact_reach(sim);
    sim.contacts.build(sim.particles, reach + skin, PairSelection::OtherBody,
                       /*reference=*/false, sim.threads, physics::contact_eligible(sim));
    physics::prepare_contact(sim);  // normals' scratch and candidates, before any stress pass
  }
}

void external_forces(Simulation& sim, double dt) {
  Particles& p = sim.particles;
  const std::size_t n = p.n;
  const double damping = sim.damping_1_s, ramp = physics::load_ramp(sim);
  double dissipated = 0.0;
#pragma omp parallel num_threads(sim.threads) reduction(+ : dissipated)
  {
    const std::size_t team = omp_get_num_threads(), me = omp_get_thread_num();
    dissipated += physics::external_accelerations(p, n * me / team, n * (me + 1) / team, ramp,
                                                  damping, dt, false);
  }
  sim.energy.dissipated += dissipated;
  if (penalty_contact(sim)) physics::contact_forces(sim, dt);  // adds to ext
}

// Rates and accelerations at the current positions; stress advanced by dt.
void forces(Simulation& sim, double dt) {
  if (total_lagrangian(sim)) {
    physics::total_lagrangian_forces(sim, dt);
  } else {
    physics::velocity_gradient(sim, dt);
    physics::update_stress(sim, dt);
    physics::momentum(sim, dt);
  }
}

// What the passes of a total-Lagrangian step add up; each thread its own
// (run_passes adds them in thread order).
struct StepSums {
  double viscous = 0.0;  // power the viscosity (and hourglass control) remove [W/m]
  double damped = 0.0;   // energy the mass damping removed over the step
  physics::ContactTally touched;
  KickPowers power;
  StepSums& operator+=(const StepSums& o) {
    viscous += o.viscous;
    damped += o.damped;
    touched += o.touched;
    power += o.power;
    return *this;
  }
};

struct RegionStep {
  Drift drift;
  KickPowers power;
};

// A whole total-Lagrangian step, x^n and v^n to x^{n+1} and v^{n+1}, as one
// list of passes in one parallel region (no torque-driven groups: their
// spin needs every particle's acceleration first). Kicks, drift, momentum
// and accelerations run over the momentum cut of the rows, F and stress
// over the deformation cut (ReferencePairs). Returns the drift's findings;
// with a particle outside the domain the force passes are skipped and the
// caller stops the run.
RegionStep total_lagrangian_step(Simulation& sim, double dt) {
  physics::TotalLagrangianPasses tl = physics::total_lagrangian_passes(sim);
  const bool contact = penalty_contact(sim);
  // Smoothed contact forces are gathered from the surface around each particle.
  const bool spread = contact && physics::contact_smoothing(sim);
  place_rotations(sim, dt);
  double ramp = 0.0;
  Drift drift;

  // v^{n+1/2}, x^{n+1}, u = x - X.
  auto kick_and_drift = [&](int c, StepSums&) {
    Drift mine;
    kick_drift_particles(sim, dt, tl.momentum.begin(c), tl.momentum.end(c), mine);
#pragma omp atomic
    drift.outside += mine.outside;
#pragma omp atomic
    drift.contacts_moved += mine.contacts_moved;
  };
  // The clock, and the contact list if its skin is used up (about every
  // 3,000 steps of the meshing gear).
  auto clock_and_contact_list = [&](int, StepSums&) {
    sim.time += dt;
    ++sim.step;
    ramp = physics::load_ramp(sim);
    refresh_neighbours(sim, drift.contacts_moved > 0);
  };
  // F - I from the displacements; then F, P, sigma, rho and the turned
  // contact normals per particle.
  auto deformation = [&](int c, StepSums&) { physics::deformation_sums(sim, tl, c); };
  auto stress = [&](int c, StepSums&) { physics::stress_from_deformation(sim, tl, c); };
  // The contact (its own static split of the candidates) and the momentum
  // pair sums.
  auto contact_and_momentum = [&](int, StepSums& s) {
    if (contact) physics::contact_pairs(sim, dt, s.touched);
    for_my_chunks(tl.momentum, [&](int c) { s.viscous += physics::momentum_sums(sim, tl, c); });
  };
  // Per particle: a^{n+1}, external accelerations, v^{n+1}.
  auto accelerations_and_kick = [&](int c, StepSums& s) {
    const std::size_t lo = tl.momentum.begin(c), hi = tl.momentum.end(c);
    s.viscous += physics::accelerations(sim, tl, c);
    s.damped += physics::external_accelerations(sim.particles, lo, hi, ramp, sim.damping_1_s, dt,
                                                contact && !spread);
    if (spread) physics::add_contact_accelerations(sim, lo, hi);
    s.power += closing_kick_particles(sim, 0.5 * dt, lo, hi);
  };

  const Pass<StepSums> step[] = {
      {"kick and drift", Runs::OverChunks, &tl.momentum, kick_and_drift},
      {"clock and contact list", Runs::OnOneThread, nullptr, clock_and_contact_list},
      {"deformation gradient", Runs::OverChunks, &tl.deformation, deformation},
      {"stress", Runs::OverChunks, &tl.deformation, stress},
      {"contact and momentum sums", Runs::OnEveryThread, nullptr, contact_and_momentum},
      {"accelerations and closing kick", Runs::OverChunks, &tl.momentum, accelerations_and_kick},
  };
  // A particle outside the domain (final after the drift's barrier) stops
  // the list before the clock; the clock still counts the step.
  const StepSums sums = run_passes<StepSums>(step, tl.momentum.chunks(), drift.outside);
  if (drift.outside > 0) {
    sim.time += dt;
    ++sim.step;
    return {drift, sums.power};
  }
  sim.energy.dissipated += dt * sums.viscous;  // the same order as separate calls
  sim.energy.dissipated += sums.damped;
  if (contact) physics::record_contact(sim, sums.touched);
  physics::gather_largest_j2(sim);
  return {drift, sums.power};
}

}  // namespace

void initialise(Simulation& sim) {
  if (total_lagrangian(sim)) {
    physics::total_lagrangian_setup(sim);        // keeps the pairs the stable-step estimate built
    sim.particles.release_updated_lagrangian();  // this run never takes a UL step
  }
  refresh_neighbours(sim, sim.contacts.needs_rebuild(sim.particles));
  forces(sim, 0.0);  // accelerations at t = 0, stress unchanged
  external_forces(sim, 0.0);
  // The setup's temporaries (moment matrices, the stable-step estimate's
  // vectors) went back to the heap in pieces the allocator keeps;
  // return them to the system, so that a long run holds only what it uses
  // (~22 % of the resident memory at 1e6 particles; docs/speed-accuracy.md).
  malloc_trim(0);
}

namespace {

void advance(Simulation& sim, bool one_region) {
  const double dt = sim.dt;
  KickPowers power;
  if (one_region) {
    const RegionStep done = total_lagrangian_step(sim, dt);  // all of the below
    if (done.drift.outside > 0) diagnostics::throw_divergence(sim);
    power = done.power;
  } else {
    const Drift drift = kick_drift(sim, dt);  // v^{n+1/2}, x^{n+1}
    sim.time += dt;
    ++sim.step;
    if (drift.outside > 0) diagnostics::throw_divergence(sim);  // names particle + quantity
    refresh_neighbours(sim, drift.contacts_moved > 0);          // Verlet lists, skin used up?
    forces(sim, dt);                                            // rho, S at n+1; a^{n+1}
    external_forces(sim, dt);                                   // loads, contact, damping
    power = closing_kick(sim, 0.5 * dt);                        // v^{n+1}
  }
  sim.energy.drive_work += dt * power.drive;
  sim.energy.external_work += dt * power.load;
}

}  // namespace

void step(Simulation& sim) {
  advance(sim, total_lagrangian(sim) && !torque_driven(sim));
}

void step_by_terms(Simulation& sim) {
  advance(sim, false);
}

}  // namespace gearsph::integrate
