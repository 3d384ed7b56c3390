#include "solver/integrate/motion.hpp"

#include <algorithm>
#include <cmath>

#include "solver/core/row_chunks.hpp"
#include "solver/physics/external_loads.hpp"
#include "solver/physics/simulation.hpp"

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
  m.alpha = (physics::load_ramp(sim) * m.torque + moment) / (inertia + m.attached_inertia);
  m.omega += dt_half * m.alpha;
}

// Raw pointers to what a kick and a drift touch. The loops below run over a
// stretch of particles that share one motion, through these, so that they
// vectorise: through Particles& each store makes the compiler reload the
// next array's address, and a switch per particle stops the vectoriser
// (docs/speed-accuracy-history.md, "the per-particle passes as vector loops").
struct Kinematics {
  double *x, *y, *vx, *vy;
  const double *x0, *y0, *ax, *ay, *ext_ax, *ext_ay, *mass, *load_ax, *load_ay;
  explicit Kinematics(Particles& p)
      : x(p.x.data()),
        y(p.y.data()),
        vx(p.vx.data()),
        vy(p.vy.data()),
        x0(p.x0.data()),
        y0(p.y0.data()),
        ax(p.ax.data()),
        ay(p.ay.data()),
        ext_ax(p.ext_ax.data()),
        ext_ay(p.ext_ay.data()),
        mass(p.mass.data()),
        load_ax(p.load_ax.data()),
        load_ay(p.load_ay.data()) {}
};

// Calls f(lo, hi, motion) for each stretch lo .. hi of particles with one
// motion (a scene lists a body's hub and teeth in stretches of tens to
// hundreds of particles). A stretch that starts mid cache line is called
// in two parts, the second from the next line: a vector loop whose loads
// all straddle two lines runs 50 % slower (measured on the gear's rack).
template <typename F>
void for_each_motion_run(const Particles& p, const Motion* motions, std::size_t lo, std::size_t hi,
                         F&& f) {
  const std::uint16_t* motion = p.motion.data();
  while (lo < hi) {
    std::size_t end = lo + 1;
    while (end < hi && motion[end] == motion[lo]) ++end;
    const std::size_t line = (lo + kRowAlign - 1) / kRowAlign * kRowAlign;
    if (line > lo && line < end) {
      f(lo, line, motions[motion[lo]]);
      f(line, end, motions[motion[lo]]);
    } else {
      f(lo, end, motions[motion[lo]]);
    }
    lo = end;
  }
}

// The opening kick and the drift of particles lo .. hi, all with motion m:
// v^{n+1/2}, then x at time t = sim.time + dt. Before the drift a driven
// rotation gets the chord velocity (x^{n+1} - x^n)/dt of its exact
// placement, whose gradient, mapped to mid-step, is a pure spin (no
// dilatation).
void open_run(const Kinematics& k, const Motion& m, std::size_t lo, std::size_t hi, double dt,
              double t) {
  const double dt_half = 0.5 * dt;
  double *x = k.x, *y = k.y, *vx = k.vx, *vy = k.vy;
  switch (m.kind) {
    case Motion::Kind::Free:
#pragma omp simd
      for (std::size_t i = lo; i < hi; ++i) {
        vx[i] += dt_half * (k.ax[i] + k.ext_ax[i]);
        vy[i] += dt_half * (k.ay[i] + k.ext_ay[i]);
        x[i] += dt * vx[i];
        y[i] += dt * vy[i];
      }
      break;
    case Motion::Kind::GuidedX: {
      const double kick = dt_half / m.inertia_scale;
#pragma omp simd
      for (std::size_t i = lo; i < hi; ++i) {
        vx[i] += kick * (k.ax[i] + k.ext_ax[i]);
        vy[i] = 0.0;
        x[i] += dt * vx[i];
      }
      break;
    }
    case Motion::Kind::Fixed:
#pragma omp simd
      for (std::size_t i = lo; i < hi; ++i) {
        vx[i] = vy[i] = 0.0;
        x[i] = k.x0[i];
        y[i] = k.y0[i];
      }
      break;
    case Motion::Kind::Velocity:
#pragma omp simd
      for (std::size_t i = lo; i < hi; ++i) {
        vx[i] = m.vx;
        vy[i] = m.vy;
        x[i] = k.x0[i] + m.vx * t;
        y[i] = k.y0[i] + m.vy * t;
      }
      break;
    case Motion::Kind::Rotation: {
      // Held: placed exactly at omega t, no drift over a million steps.
      const double cos_t = m.cos_next, sin_t = m.sin_next;
#pragma omp simd
      for (std::size_t i = lo; i < hi; ++i) {
        const double rx = k.x0[i] - m.cx, ry = k.y0[i] - m.cy;
        const double nx = m.cx + cos_t * rx - sin_t * ry, ny = m.cy + sin_t * rx + cos_t * ry;
        vx[i] = (nx - x[i]) / dt;
        vy[i] = (ny - y[i]) / dt;
        x[i] = nx;
        y[i] = ny;
      }
      break;
    }
  }
}

// The closing kick of particles lo .. hi, all with motion m, and the powers
// at the velocities it leaves. A constraint supplies what the internal,
// contact and load forces would otherwise change in the prescribed motion:
// -m a . v over its constrained components.
KickPowers close_run(const Kinematics& k, const Motion& m, std::size_t lo, std::size_t hi,
                     double dt_half, double ramp) {
  double *vx = k.vx, *vy = k.vy;
  const double *x = k.x, *y = k.y, *mass = k.mass;
  double drive = 0.0, load = 0.0;
  switch (m.kind) {
    case Motion::Kind::Free:
#pragma omp simd
      for (std::size_t i = lo; i < hi; ++i) {
        vx[i] += dt_half * (k.ax[i] + k.ext_ax[i]);
        vy[i] += dt_half * (k.ay[i] + k.ext_ay[i]);
      }
      break;
    case Motion::Kind::GuidedX: {  // v_y = 0: the guide does no work
      // An attached mass pulls each member with m a (1 / scale - 1), where
      // m a is the member's force: its power is the attached mass's loss
      // of kinetic energy, which the balance counts as drive work.
      const double kick = dt_half / m.inertia_scale, held = 1.0 / m.inertia_scale - 1.0;
#pragma omp simd reduction(+ : drive)
      for (std::size_t i = lo; i < hi; ++i) {
        vx[i] += kick * (k.ax[i] + k.ext_ax[i]);
        vy[i] = 0.0;
        drive += held * mass[i] * (k.ax[i] + k.ext_ax[i]) * vx[i];
      }
      break;
    }
    case Motion::Kind::Fixed:
    case Motion::Kind::Velocity:
    case Motion::Kind::Rotation: {
      // A held rotation moves at the velocity of its new position.
      const bool spins = m.kind == Motion::Kind::Rotation;
      const double ux = m.kind == Motion::Kind::Velocity ? m.vx : 0.0;
      const double uy = m.kind == Motion::Kind::Velocity ? m.vy : 0.0;
#pragma omp simd reduction(+ : drive)
      for (std::size_t i = lo; i < hi; ++i) {
        vx[i] = spins ? -m.omega * (y[i] - m.cy) : ux;
        vy[i] = spins ? m.omega * (x[i] - m.cx) : uy;
        drive -= mass[i] * ((k.ax[i] + k.ext_ax[i]) * vx[i] + (k.ay[i] + k.ext_ay[i]) * vy[i]);
      }
      break;
    }
  }
#pragma omp simd reduction(+ : load)
  for (std::size_t i = lo; i < hi; ++i) {
    load += ramp * mass[i] * (k.load_ax[i] * vx[i] + k.load_ay[i] * vy[i]);
  }
  return {drive, load};
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

void spin_groups(Simulation& sim, double dt_half) {
  for (std::size_t k = 0; k < sim.motions.size(); ++k) {
    if (sim.motions[k].torque_driven) spin(sim, k, dt_half);
  }
}

void kick_drift_particles(Simulation& sim, double dt, double t, std::size_t lo, std::size_t hi) {
  const Kinematics k(sim.particles);
  for_each_motion_run(
      sim.particles, sim.motions.data(), lo, hi,
      [&](std::size_t a, std::size_t b, const Motion& m) { open_run(k, m, a, b, dt, t); });
}

bool torque_driven(const Simulation& sim) {
  for (const Motion& m : sim.motions) {
    if (m.torque_driven) return true;
  }
  return false;
}

KickPowers closing_kick_particles(Simulation& sim, double dt_half, std::size_t lo, std::size_t hi) {
  const Kinematics k(sim.particles);
  const double ramp = physics::load_ramp(sim);
  KickPowers power;
  for_each_motion_run(sim.particles, sim.motions.data(), lo, hi,
                      [&](std::size_t a, std::size_t b, const Motion& m) {
                        power += close_run(k, m, a, b, dt_half, ramp);
                      });
  return power;
}

double torque_drive_power(const Simulation& sim) {
  // A torque-driven group is also accelerated along its rotation: the drive
  // supplies that too (in all, the applied torque's power less what goes
  // into the attached inertia, which is not among the particles' energy).
  double power = 0.0;
  for (const Motion& m : sim.motions) {
    if (m.torque_driven) power += m.group_inertia * m.alpha * m.omega;
  }
  return power;
}

}  // namespace gearsph::integrate
