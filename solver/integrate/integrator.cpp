#include "solver/integrate/integrator.hpp"

#include <malloc.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <sstream>
#include <type_traits>

#include "solver/core/simulation.hpp"
#include "solver/diagnostics/guard.hpp"
#include "solver/integrate/motion.hpp"
#include "solver/physics/contact.hpp"
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
    // kernel itself (the coupling whose adhesion the paper avoids).
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

// Accelerations from outside the bodies' own stress on particles lo .. hi:
// applied loads, (quasi-static scenes) mass-proportional damping and, with
// `contact`, the contact accelerations of this step. Returns the energy the
// damping removed over dt. One vector loop: raw pointers, and the energy
// summed as a simd reduction (a scalar sum kept the loop scalar).
double external_accelerations(Particles& p, std::size_t lo, std::size_t hi, double ramp, double c,
                              double dt, bool contact) {
  double *ext_ax = p.ext_ax.data(), *ext_ay = p.ext_ay.data();
  const double *load_ax = p.load_ax.data(), *load_ay = p.load_ay.data();
  const double *vx = p.vx.data(), *vy = p.vy.data(), *mass = p.mass.data();
  const double *contact_ax = p.contact_ax.data(), *contact_ay = p.contact_ay.data();
  double dissipated = 0.0;
  auto run = [&](auto with_contact) {
#pragma omp simd reduction(+ : dissipated)
    for (std::size_t i = lo; i < hi; ++i) {
      const double ax = ramp * load_ax[i] - c * vx[i], ay = ramp * load_ay[i] - c * vy[i];
      ext_ax[i] = with_contact ? ax + contact_ax[i] : ax;
      ext_ay[i] = with_contact ? ay + contact_ay[i] : ay;
      dissipated += c * mass[i] * (vx[i] * vx[i] + vy[i] * vy[i]) * dt;
    }
  };
  if (contact) {
    run(std::true_type{});
  } else {
    run(std::false_type{});
  }
  return dissipated;
}

void external_forces(Simulation& sim, double dt) {
  Particles& p = sim.particles;
  const std::size_t n = p.n;
  const double c = sim.damping_1_s, ramp = load_ramp(sim);
  double dissipated = 0.0;
#pragma omp parallel num_threads(sim.threads) reduction(+ : dissipated)
  {
    const std::size_t team = omp_get_num_threads(), me = omp_get_thread_num();
    dissipated += external_accelerations(p, n * me / team, n * (me + 1) / team, ramp, c, dt, false);
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

// A whole total-Lagrangian step, x^n and v^n to x^{n+1} and v^{n+1}, in one
// parallel region (no torque-driven groups: their spin needs every
// particle's acceleration first). Each pass runs over the calling thread's
// chunks of rows (RowChunks); a barrier stands wherever a pass reads what
// another thread wrote. Returns the drift's findings; with a particle
// outside the domain the force passes are skipped and the caller stops the
// run.
struct RegionStep {
  Drift drift;
  KickPowers power;
};

RegionStep total_lagrangian_step(Simulation& sim, double dt) {
  physics::TotalLagrangianPasses tl = physics::total_lagrangian_passes(sim);
  // Kicks, drift, momentum and accelerations by the momentum cut, F and
  // stress by the deformation cut (ReferencePairs).
  const RowChunks& chunks = tl.momentum;
  const bool contact = penalty_contact(sim);
  // Smoothed contact forces are gathered from the surface around each particle.
  const bool spread = contact && physics::contact_smoothing(sim);
  const double damping = sim.damping_1_s;
  place_rotations(sim, dt);
  double ramp = 0.0, viscous = 0.0, damped = 0.0;
  Drift drift;
  std::exception_ptr failed;
  physics::ContactTally touched;
  KickPowers power;
  // The passes, run by every thread of the region on its own sums (the
  // reduction's copies).
  auto region = [&](double& viscous_sum, double& damped_sum, physics::ContactTally& touched_sum,
                    KickPowers& power_sum) {
    // v^{n+1/2}, x^{n+1}, u = x - X.
    Drift mine;
    for_my_chunks(chunks, [&](int c) {
      kick_drift_particles(sim, dt, chunks.begin(c), chunks.end(c), mine);
    });
#pragma omp atomic
    drift.outside += mine.outside;
#pragma omp atomic
    drift.contacts_moved += mine.contacts_moved;
#pragma omp barrier
    // One thread: the clock, and the contact list if its skin is used up
    // (about every 3,000 steps of the meshing gear; built on one thread here).
#pragma omp single
    {
      sim.time += dt;
      ++sim.step;
      ramp = load_ramp(sim);
      if (drift.outside == 0) {
        try {
          refresh_neighbours(sim, drift.contacts_moved > 0);
        } catch (...) {
          failed = std::current_exception();
        }
      }
    }
    if (drift.outside == 0 && !failed) {
      // F - I from the displacements.
      for_my_chunks(tl.deformation, [&](int c) { physics::deformation_sums(sim, tl, c); });
#pragma omp barrier
      // F, P, sigma, rho; contact normals turned.
      for_my_chunks(tl.deformation, [&](int c) { physics::stress_from_deformation(sim, tl, c); });
#pragma omp barrier
      // Contact (its own static split) and the momentum pair sums.
      if (contact) physics::contact_pairs(sim, dt, touched_sum);
      for_my_chunks(chunks, [&](int c) { viscous_sum += physics::momentum_sums(sim, tl, c); });
#pragma omp barrier
      // Per particle: a^{n+1}, external accelerations, v^{n+1}.
      for_my_chunks(chunks, [&](int c) {
        viscous_sum += physics::accelerations(sim, tl, c);
        damped_sum += external_accelerations(sim.particles, chunks.begin(c), chunks.end(c), ramp,
                                             damping, dt, contact && !spread);
        if (spread) physics::add_contact_accelerations(sim, chunks.begin(c), chunks.end(c));
        power_sum += closing_kick_particles(sim, 0.5 * dt, chunks.begin(c), chunks.end(c));
      });
    }
  };
  if (chunks.chunks() == 1) {
    // One thread: no region. libgomp wakes a team of one through the kernel
    // at every barrier (a futex call each, ~7 a step: 7 % of a 1,250-
    // particle plate's step on this machine); the barriers and the single
    // block bind to no team here and cost nothing.
    region(viscous, damped, touched, power);
  } else {
#pragma omp parallel num_threads(chunks.chunks()) reduction(+ : viscous, damped, touched, power)
    region(viscous, damped, touched, power);
  }
  if (failed) std::rethrow_exception(failed);
  if (drift.outside > 0) return {drift, power};
  sim.energy.dissipated += dt * viscous;  // the same order as separate calls
  sim.energy.dissipated += damped;
  if (contact) physics::record_contact(sim, touched);
  physics::gather_largest_j2(sim);
  return {drift, power};
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
