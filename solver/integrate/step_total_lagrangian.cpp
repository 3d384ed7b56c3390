// The total-Lagrangian time step as one table of passes (core/passes.hpp),
// read top to bottom: kick-drift-kick (velocity Verlet) around F, the
// stress, the contact and the momentum sums over the fixed reference pairs.
// Kicks, drift, momentum and accelerations run over the momentum cut of the
// rows, F and the stress over the deformation cut (ReferencePairs).
#include <cstddef>

#include "solver/core/passes.hpp"
#include "solver/diagnostics/guard.hpp"
#include "solver/integrate/motion.hpp"
#include "solver/integrate/step_passes.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/crack_face_contact.hpp"
#include "solver/physics/external_loads.hpp"
#include "solver/physics/simulation.hpp"
#include "solver/physics/total_lagrangian.hpp"

namespace gearsph::integrate {

void total_lagrangian_step(Simulation& sim, bool apart) {
  physics::TotalLagrangianPasses tl = physics::total_lagrangian_passes(sim);
  const RowChunks *const f_rows = &tl.deformation, *const m_rows = &tl.momentum;
  const double dt = sim.dt, t = sim.time + dt;  // t: read before the clock moves
  const bool torque = torque_driven(sim), contact = penalty_contact(sim);
  const bool spread = contact && physics::contact_smoothing(sim);  // forces gathered around
  std::size_t outside = 0, moved = 0;  // shared by the threads (add_shared)
  double ramp = 0.0;
  using S = StepSums;
  auto range = [&](const RowChunks* rows, int c, auto&& f) { f(rows->begin(c), rows->end(c)); };

  auto spin = [&](int, int, S&) { spin_groups(sim, 0.5 * dt); };
  auto rotations = [&](int, int, S&) { place_rotations(sim, dt); };
  auto kick_and_drift = [&](int c, int, S&) {  // v^{n+1/2}, x^{n+1}
    range(m_rows, c, [&](auto lo, auto hi) { kick_drift_particles(sim, dt, t, lo, hi); });
  };
  auto displacements = [&](int c, int, S&) {  // u = x - X, beside V0 for the F loop
    range(m_rows, c, [&](auto lo, auto hi) { physics::displacements(sim, lo, hi); });
  };
  auto domain_check = [&](int c, int, S&) {
    range(m_rows, c,
          [&](auto lo, auto hi) { add_shared(outside, diagnostics::outside_domain(sim, lo, hi)); });
  };
  auto contact_skin = [&](int c, int, S&) {
    range(m_rows, c, [&](auto lo, auto hi) { add_shared(moved, contacts_moved(sim, lo, hi)); });
  };
  auto clock = [&](int, int, S&) {  // counts the step also when the domain check stops it
    advance_clock(sim);
    ramp = physics::load_ramp(sim);
  };
  auto contact_list = [&](int, int, S&) { refresh_contacts(sim, moved > 0); };
  auto deformation = [&](int c, int, S&) { physics::deformation_sums(sim, tl, c); };
  auto smoothing = [&](int me, int team, S&) { physics::smooth_contact_points(sim, me, team); };
  auto stress = [&](int c, int, S&) { physics::stress_from_deformation(sim, tl, c); };
  auto normals = [&](int c, int, S&) {
    range(f_rows, c, [&](auto lo, auto hi) { physics::turn_contact_normals(sim, lo, hi); });
  };
  auto peak = [&](int c, int, S&) { physics::note_peak_stress(sim, tl, c); };
  auto contact_pairs = [&](int me, int team, S& s) {
    physics::contact_pairs(sim, dt, me, team, s.touched);
  };
  auto momentum = [&](int c, int, S& s) { s.viscous += physics::momentum_sums(sim, tl, c); };
  auto accelerations = [&](int c, int, S& s) { s.viscous += physics::accelerations(sim, tl, c); };
  auto external = [&](int c, int, S& s) {  // loads, damping, and the contact's own share
    range(m_rows, c, [&](auto lo, auto hi) {
      s.damped += physics::external_accelerations(sim.particles, lo, hi, ramp, sim.damping_1_s, dt,
                                                  contact && !spread);
    });
  };
  const bool faces = !sim.reference.faces.empty();
  auto crack_faces = [&](int, int, S&) { physics::crack_face_contact(sim); };
  auto contact_spread = [&](int c, int, S&) {
    range(m_rows, c, [&](auto lo, auto hi) { physics::add_contact_accelerations(sim, lo, hi); });
  };
  auto closing_kick = [&](int c, int, S& s) {  // v^{n+1}
    range(m_rows, c,
          [&](auto lo, auto hi) { s.power += closing_kick_particles(sim, 0.5 * dt, lo, hi); });
  };

  // A barrier is needed where a pass reads other chunks' rows; the passes
  // over one chunk's own rows continue without (Sync::Continues).
  const Sync after_contact = contact ? Sync::Continues : Sync::Barrier;
  const Sync after_spin = torque ? Sync::Barrier : Sync::Continues;
  // The crack's faces add to both ends of pairs of any chunk, after every
  // chunk's external accelerations are set.
  const Sync after_external = faces ? Sync::Barrier : Sync::Continues;
  const Pass<S> step[] = {
      {"opening spin", Runs::OnCallingThread, nullptr, spin, Sync::Barrier, torque},
      {"driven rotations", Runs::OnCallingThread, nullptr, rotations, Sync::Barrier, true},
      {"kick and drift", Runs::OverChunks, m_rows, kick_and_drift, Sync::Barrier, true},
      {"displacements", Runs::OverChunks, m_rows, displacements, Sync::Continues, true},
      {"domain check", Runs::OverChunks, m_rows, domain_check, Sync::Continues, true},
      {"contact skin", Runs::OverChunks, m_rows, contact_skin, Sync::Continues, contact},
      {"clock", Runs::OnOneThread, nullptr, clock, Sync::Continues, true},
      {"contact list", Runs::OnOneThread, nullptr, contact_list, Sync::Barrier, contact},
      {"deformation gradient", Runs::OverChunks, f_rows, deformation, Sync::Barrier, true},
      {"contact smoothing", Runs::OnEveryThread, nullptr, smoothing, Sync::Continues, spread},
      {"stress", Runs::OverChunks, f_rows, stress, Sync::Barrier, true},
      {"contact normals", Runs::OverChunks, f_rows, normals, Sync::Continues, contact},
      {"peak stress", Runs::OverChunks, f_rows, peak, Sync::Continues, true},
      {"contact pairs", Runs::OnEveryThread, nullptr, contact_pairs, Sync::Barrier, contact},
      {"momentum sums", Runs::OverChunks, m_rows, momentum, after_contact, true},
      {"accelerations", Runs::OverChunks, m_rows, accelerations, Sync::Barrier, true},
      {"external forces", Runs::OverChunks, m_rows, external, after_external, true},
      {"crack faces", Runs::OnOneThread, nullptr, crack_faces, Sync::Barrier, faces},
      {"contact spread", Runs::OverChunks, m_rows, contact_spread, Sync::Continues, spread},
      {"closing spin", Runs::OnOneThread, nullptr, spin, Sync::Barrier, torque},
      {"closing kick", Runs::OverChunks, m_rows, closing_kick, after_spin, true},
  };
  // A particle outside the domain stops the table after the clock.
  const S sums = run_step_passes<S>(sim, step, m_rows->chunks(), outside, apart);
  if (outside > 0) diagnostics::throw_divergence(sim, "domain check");
  book_step(sim, sums, contact, torque);
  physics::gather_largest_j2(sim);
}

}  // namespace gearsph::integrate
