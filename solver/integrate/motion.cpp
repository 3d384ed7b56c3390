#include "solver/integrate/motion.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

#include "solver/core/simulation.hpp"

namespace gearsph::integrate {

namespace {

// Rigid-body rotation of a torque-driven group over half a step: the moment
// of the forces on its particles about the axis (internal, contact, loads)
// plus the applied torque turns the group and what is attached to it.
// SPH pair forces are equal and opposite but not central, so the group's
// own pairs leave a small residual moment (angular momentum is not exactly
// conserved by the momentum equation: Bonet & Lok 1999).
void spin(Simulation& sim, std::size_t k, double dt_half) {
  Motion& m = sim.motions[k];
  const Particles& p = sim.particles;
  double moment = 0.0, inertia = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.motion[i] != static_cast<std::uint16_t>(k)) continue;
    const double rx = p.x[i] - m.cx, ry = p.y[i] - m.cy;
    moment += p.mass[i] * (rx * (p.ay[i] + p.ext_ay[i]) - ry * (p.ax[i] + p.ext_ax[i]));
    inertia += p.mass[i] * (rx * rx + ry * ry);
  }
  m.group_inertia = inertia;
  m.alpha = (load_ramp(sim) * m.torque + moment) / (inertia + m.attached_inertia);
  m.omega += dt_half * m.alpha;
}

// What the constraint of particle i supplies: what the internal, contact and
// load forces would otherwise change in the prescribed motion.
double drive_power(const Particles& p, const Motion& m, std::size_t i) {
  if (m.kind == Motion::Kind::Free) return 0.0;
  const double ax = p.ax[i] + p.ext_ax[i], ay = p.ay[i] + p.ext_ay[i];
  if (m.kind == Motion::Kind::GuidedX) return -p.mass[i] * ay * p.vy[i];  // v_y = 0: no work
  return -p.mass[i] * (ax * p.vx[i] + ay * p.vy[i]);
}

// Half-step velocity of particle i. Before the drift a driven rotation gets
// the chord velocity (x^{n+1} - x^n)/dt of its exact placement, whose
// gradient, mapped to mid-step, is a pure spin (no dilatation); after it,
// the velocity at the new position.
inline void kick_particle(Particles& p, const Motion& m, std::size_t i, double dt_half,
                          bool before_drift) {
  switch (m.kind) {
    case Motion::Kind::Free:
      p.vx[i] += dt_half * (p.ax[i] + p.ext_ax[i]);
      p.vy[i] += dt_half * (p.ay[i] + p.ext_ay[i]);
      break;
    case Motion::Kind::GuidedX:
      p.vx[i] += dt_half * (p.ax[i] + p.ext_ax[i]);
      p.vy[i] = 0.0;
      break;
    case Motion::Kind::Fixed:
      p.vx[i] = p.vy[i] = 0.0;
      break;
    case Motion::Kind::Velocity:
      p.vx[i] = m.vx;
      p.vy[i] = m.vy;
      break;
    case Motion::Kind::Rotation:
      if (before_drift) {
        const double c = m.cos_next, s = m.sin_next;
        const double rx = p.x0[i] - m.cx, ry = p.y0[i] - m.cy;
        p.vx[i] = (m.cx + c * rx - s * ry - p.x[i]) / (2.0 * dt_half);
        p.vy[i] = (m.cy + s * rx + c * ry - p.y[i]) / (2.0 * dt_half);
      } else {
        p.vx[i] = -m.omega * (p.y[i] - m.cy);
        p.vy[i] = m.omega * (p.x[i] - m.cx);
      }
      break;
  }
}

// New position of particle i at time t = sim.time + dt.
inline void drift_particle(Particles& p, const Motion& m, std::size_t i, double dt, double t) {
  switch (m.kind) {
    case Motion::Kind::Free:
    case Motion::Kind::GuidedX:
      p.x[i] += dt * p.vx[i];
      p.y[i] += dt * p.vy[i];
      break;
    case Motion::Kind::Fixed:
      p.x[i] = p.x0[i];
      p.y[i] = p.y0[i];
      break;
    case Motion::Kind::Velocity:
      p.x[i] = p.x0[i] + m.vx * t;
      p.y[i] = p.y0[i] + m.vy * t;
      break;
    case Motion::Kind::Rotation: {
      const double c = m.cos_next, s = m.sin_next;
      const double rx = p.x0[i] - m.cx, ry = p.y0[i] - m.cy;
      p.x[i] = m.cx + c * rx - s * ry;
      p.y[i] = m.cy + s * rx + c * ry;
      break;
    }
  }
}

}  // namespace

// The angle of each driven rotation at x^{n+1}, once per group.
void place_rotations(Simulation& sim, double dt) {
  const double t = sim.time + dt;
  for (Motion& m : sim.motions) {
    if (m.kind != Motion::Kind::Rotation) continue;
    // Held: placed exactly at omega t, no drift over a million steps.
    m.angle = m.torque_driven ? m.angle + dt * m.omega : m.omega * t;
    m.cos_next = std::cos(m.angle);
    m.sin_next = std::sin(m.angle);
  }
}

void kick_drift_particles(Simulation& sim, double dt, std::size_t lo, std::size_t hi,
                          Drift& drift) {
  Particles& p = sim.particles;
  const std::size_t n = p.n;
  const Motion* motions = sim.motions.data();
  const Box box = sim.domain;
  const double dt_half = 0.5 * dt, t = sim.time + dt;
  // The total-Lagrangian F loop reads displacements u = x - X (two gathers
  // a neighbour instead of four); written here, where x is at hand.
  const bool reference = sim.reference.ux.size() == n;
  double* ux = sim.reference.ux.data();
  double* uy = sim.reference.uy.data();
  // The contact list's skin check, here where the new position is at hand.
  const NeighbourList* contacts = sim.contacts.built_for(n) ? &sim.contacts : nullptr;
  for (std::size_t i = lo; i < hi; ++i) {
    const Motion& m = motions[p.motion[i]];
    kick_particle(p, m, i, dt_half, true);
    drift_particle(p, m, i, dt, t);
    if (reference) {
      ux[i] = p.x[i] - p.x0[i];
      uy[i] = p.y[i] - p.y0[i];
    }
    // NaN fails both comparisons, so a non-finite position counts as outside.
    drift.outside += box.contains(p.x[i], p.y[i]) ? 0 : 1;
    drift.contacts_moved += contacts && contacts->moved_too_far(i, p.x[i], p.y[i]) ? 1 : 0;
  }
}

Drift kick_drift(Simulation& sim, double dt) {
  for (std::size_t k = 0; k < sim.motions.size(); ++k) {
    if (sim.motions[k].torque_driven) spin(sim, k, 0.5 * dt);
  }
  place_rotations(sim, dt);
  const std::size_t n = sim.particles.n;
  // Total-Lagrangian runs move the rows each thread owns in the momentum
  // pass and the accelerations (RowChunks): what a thread writes in the step
  // stays in its own cache.
  const RowChunks& chunks = sim.reference.momentum_chunks;
  const bool by_chunks = chunks.chunks() == std::max(1, sim.threads);
  std::size_t outside = 0, contacts_moved = 0;
#pragma omp parallel num_threads(sim.threads) reduction(+ : outside, contacts_moved)
  {
    Drift d;
    if (by_chunks) {
      for_my_chunks(
          chunks, [&](int c) { kick_drift_particles(sim, dt, chunks.begin(c), chunks.end(c), d); });
    } else {
      const std::size_t team = omp_get_num_threads(), me = omp_get_thread_num();
      kick_drift_particles(sim, dt, n * me / team, n * (me + 1) / team, d);
    }
    outside += d.outside;
    contacts_moved += d.contacts_moved;
  }
  return {outside, contacts_moved};
}

bool torque_driven(const Simulation& sim) {
  for (const Motion& m : sim.motions) {
    if (m.torque_driven) return true;
  }
  return false;
}

KickPowers closing_kick_particles(Simulation& sim, double dt_half, std::size_t lo, std::size_t hi) {
  Particles& p = sim.particles;
  const Motion* motions = sim.motions.data();
  const double ramp = load_ramp(sim);
  KickPowers power;
  for (std::size_t i = lo; i < hi; ++i) {
    const Motion& m = motions[p.motion[i]];
    kick_particle(p, m, i, dt_half, false);
    power.drive += drive_power(p, m, i);
    power.load += ramp * p.mass[i] * (p.load_ax[i] * p.vx[i] + p.load_ay[i] * p.vy[i]);
  }
  return power;
}

KickPowers closing_kick(Simulation& sim, double dt_half) {
  for (std::size_t k = 0; k < sim.motions.size(); ++k) {
    if (sim.motions[k].torque_driven) spin(sim, k, dt_half);
  }
  Particles& p = sim.particles;
  const std::size_t n = p.n;
  const Motion* motions = sim.motions.data();
  const double ramp = load_ramp(sim);
  double drive = 0.0, load = 0.0;
#pragma omp parallel for num_threads(sim.threads) schedule(static) reduction(+ : drive, load)
  for (std::size_t i = 0; i < n; ++i) {
    const Motion& m = motions[p.motion[i]];
    kick_particle(p, m, i, dt_half, false);
    drive += drive_power(p, m, i);
    load += ramp * p.mass[i] * (p.load_ax[i] * p.vx[i] + p.load_ay[i] * p.vy[i]);
  }
  // A torque-driven group is also accelerated along its rotation: the drive
  // supplies that too (in all, the applied torque's power less what goes
  // into the attached inertia, which is not among the particles' energy).
  for (const Motion& m : sim.motions) {
    if (m.torque_driven) drive += m.group_inertia * m.alpha * m.omega;
  }
  return {drive, load};
}

double load_ramp(const Simulation& sim) {
  return sim.load_ramp_s > 0.0 ? std::min(1.0, sim.time / sim.load_ramp_s) : 1.0;
}

}  // namespace gearsph::integrate
