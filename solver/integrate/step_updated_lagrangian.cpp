// The updated-Lagrangian time step (the seed paper's method) as one table
// of passes (core/passes.hpp), read top to bottom: kick-drift-kick
// (velocity Verlet) around the velocity gradient and continuity, the
// Jaumann stress rate and the momentum sums over the kernel's neighbour
// list, with the contact between bodies. Per-particle passes run over even
// shares of the particles, one a thread.
#include <cstddef>

#include "solver/core/passes.hpp"
#include "solver/diagnostics/guard.hpp"
#include "solver/integrate/motion.hpp"
#include "solver/integrate/step_passes.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/external_loads.hpp"
#include "solver/physics/momentum.hpp"
#include "solver/physics/simulation.hpp"
#include "solver/physics/stress_rate.hpp"
#include "solver/physics/velocity_gradient.hpp"

namespace gearsph::integrate {

void updated_lagrangian_step(Simulation& sim, bool apart) {
  const std::size_t n = sim.particles.n;
  const double dt = sim.dt, t = sim.time + dt;  // t: read before the clock moves
  const bool torque = torque_driven(sim), contact = penalty_contact(sim);
  const bool surface = contact && sim.contact.model == ContactModel::Surface;
  const bool spread = contact && physics::contact_smoothing(sim);  // forces gathered around
  std::size_t outside = 0, moved = 0;  // shared by the threads (add_shared)
  double ramp = 0.0;
  using S = StepSums;
  auto particles = [&](int me, int team, auto&& f) {
    const Share part = share(n, me, team);
    f(part.lo, part.hi);
  };

  auto spin = [&](int, int, S&) { spin_groups(sim, 0.5 * dt); };
  auto rotations = [&](int, int, S&) { place_rotations(sim, dt); };
  auto kick_and_drift = [&](int me, int team, S&) {  // v^{n+1/2}, x^{n+1}
    particles(me, team, [&](auto lo, auto hi) { kick_drift_particles(sim, dt, t, lo, hi); });
  };
  auto domain_check = [&](int me, int team, S&) {
    particles(me, team, [&](auto lo, auto hi) {
      add_shared(outside, diagnostics::outside_domain(sim, lo, hi));
    });
  };
  auto contact_skin = [&](int me, int team, S&) {
    particles(me, team, [&](auto lo, auto hi) { add_shared(moved, contacts_moved(sim, lo, hi)); });
  };
  auto clock = [&](int, int, S&) {  // counts the step also when the domain check stops it
    advance_clock(sim);
    ramp = physics::load_ramp(sim);
  };
  auto lists = [&](int, int, S&) { refresh_neighbours(sim, moved > 0); };
  auto velocity_gradient = [&](int me, int team, S&) {  // L and drho/dt at x^{n+1}, v^{n+1/2}
    particles(me, team, [&](auto lo, auto hi) { physics::velocity_gradient(sim, dt, lo, hi); });
  };
  auto stress = [&](int me, int team, S&) {  // rho, p and S at n+1
    particles(me, team, [&](auto lo, auto hi) { physics::update_stress(sim, dt, lo, hi); });
  };
  auto momentum = [&](int me, int team, S& s) {  // a^{n+1}
    particles(me, team, [&](auto lo, auto hi) { s.viscous += physics::momentum(sim, lo, hi); });
  };
  auto external = [&](int me, int team, S& s) {  // loads and damping
    particles(me, team, [&](auto lo, auto hi) {
      s.damped +=
          physics::external_accelerations(sim.particles, lo, hi, ramp, sim.damping_1_s, dt, false);
    });
  };
  auto normals = [&](int me, int team, S&) {
    particles(me, team,
              [&](auto lo, auto hi) { physics::turn_contact_normals_by_rot(sim, lo, hi); });
  };
  auto smoothing = [&](int me, int team, S&) { physics::smooth_contact_points(sim, me, team); };
  auto contact_pairs = [&](int me, int team, S& s) {
    physics::contact_pairs(sim, dt, me, team, s.touched);
  };
  auto contact_forces = [&](int me, int team, S&) {
    particles(me, team, [&](auto lo, auto hi) { physics::add_contact_accelerations(sim, lo, hi); });
  };
  auto closing_kick = [&](int me, int team, S& s) {  // v^{n+1}
    particles(me, team,
              [&](auto lo, auto hi) { s.power += closing_kick_particles(sim, 0.5 * dt, lo, hi); });
  };

  // A barrier is needed where a pass reads other particles' values; the
  // passes over a thread's own share continue without (Sync::Continues).
  // The closing kick always waits: the momentum sums read the neighbours'
  // velocities that it changes.
  const Pass<S> step[] = {
      {"opening spin", Runs::OnCallingThread, nullptr, spin, Sync::Barrier, torque},
      {"driven rotations", Runs::OnCallingThread, nullptr, rotations, Sync::Barrier, true},
      {"kick and drift", Runs::OnEveryThread, nullptr, kick_and_drift, Sync::Barrier, true},
      {"domain check", Runs::OnEveryThread, nullptr, domain_check, Sync::Continues, true},
      {"contact skin", Runs::OnEveryThread, nullptr, contact_skin, Sync::Continues, contact},
      {"clock", Runs::OnOneThread, nullptr, clock, Sync::Continues, true},
      {"neighbour lists", Runs::OnCallingThread, nullptr, lists, Sync::Barrier, true},
      {"velocity gradient", Runs::OnEveryThread, nullptr, velocity_gradient, Sync::Barrier, true},
      {"stress", Runs::OnEveryThread, nullptr, stress, Sync::Barrier, true},
      {"momentum", Runs::OnEveryThread, nullptr, momentum, Sync::Barrier, true},
      {"external forces", Runs::OnEveryThread, nullptr, external, Sync::Continues, true},
      {"contact normals", Runs::OnEveryThread, nullptr, normals, Sync::Continues, surface},
      {"contact smoothing", Runs::OnEveryThread, nullptr, smoothing, Sync::Continues, spread},
      {"contact pairs", Runs::OnEveryThread, nullptr, contact_pairs, Sync::Barrier, contact},
      {"contact forces", Runs::OnEveryThread, nullptr, contact_forces, Sync::Barrier, contact},
      {"closing spin", Runs::OnOneThread, nullptr, spin, Sync::Barrier, torque},
      {"closing kick", Runs::OnEveryThread, nullptr, closing_kick, Sync::Barrier, true},
  };
  // A particle outside the domain stops the table after the clock.
  const S sums = run_step_passes<S>(sim, step, sim.threads, outside, apart);
  if (outside > 0) diagnostics::throw_divergence(sim, "domain check");
  book_step(sim, sums, contact, torque);
}

}  // namespace gearsph::integrate
