#include "solver/diagnostics/energy.hpp"

#include "solver/physics/crack_face_contact.hpp"
#include "solver/physics/elastic_law.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::diagnostics {

EnergyState energy(const Simulation& sim) {
  const Particles& p = sim.particles;
  EnergyState e;
  const bool tl = sim.method.formulation == Formulation::TotalLagrangian;
  const double *m = p.mass.data(), *vx = p.vx.data(), *vy = p.vy.data();
  // Body by body, the material's moduli hoisted: a loop the compiler
  // vectorises (per particle, the material's look-up and the moduli's
  // divisions were 7 % of a short run that samples every step).
  for (const Body& b : sim.bodies) {
    const Material& mat = b.material;
    const double lambda = mat.lame_lambda(), mu = mat.shear_modulus();
    const double inv_2k = 1.0 / (2.0 * mat.bulk_modulus()), inv_4g = 1.0 / (4.0 * mu);
    double kinetic = 0.0, elastic = 0.0;
    if (tl) {
      const double *Fxx = p.fxx.data(), *Fxy = p.fxy.data(), *Fyx = p.fyx.data();
      const double *Fyy = p.fyy.data(), *rho0 = p.rho0.data();
#pragma omp simd reduction(+ : kinetic, elastic)
      for (std::size_t i = b.begin; i < b.end; ++i) {
        kinetic += 0.5 * m[i] * (vx[i] * vx[i] + vy[i] * vy[i]);
        const physics::GreenLagrange strain =
            physics::green_lagrange(Fxx[i], Fxy[i], Fyx[i], Fyy[i]);
        elastic += physics::saint_venant_kirchhoff_energy(strain, lambda, mu) * m[i] / rho0[i];
      }
    } else {
#pragma omp simd reduction(+ : kinetic, elastic)
      for (std::size_t i = b.begin; i < b.end; ++i) {
        kinetic += 0.5 * m[i] * (vx[i] * vx[i] + vy[i] * vy[i]);
        const double w = physics::linear_elastic_energy(p.p[i], p.sxx[i], p.syy[i], p.szz[i],
                                                        p.sxy[i], inv_2k, inv_4g);
        elastic += w * m[i] / p.rho[i];
      }
    }
    e.kinetic += kinetic;
    e.elastic += elastic;
  }
  e.contact = sim.contact_state.stored_energy + physics::crack_face_energy(sim);
  e.dissipated = sim.energy.dissipated;
  e.drive_work = sim.energy.drive_work;
  e.external_work = sim.energy.external_work;
  return e;
}

Momentum momentum(const Simulation& sim, int body) {
  const Particles& p = sim.particles;
  Momentum m;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (body >= 0 && p.body[i] != body) continue;
    m.px += p.mass[i] * p.vx[i];
    m.py += p.mass[i] * p.vy[i];
  }
  return m;
}

StressPeak max_von_mises(const Simulation& sim, int body) {
  const Particles& p = sim.particles;
  StressPeak s;
  // Found by this step's stress pass (total Lagrangian): no pass here.
  if (body < 0 && sim.largest_j2.step == sim.step) {
    s.particle = sim.largest_j2.particle;
    if (s.particle >= 0) s.von_mises = p.von_mises(static_cast<std::size_t>(s.particle));
    return s;
  }
  // The largest J2, one square root at the end (called every step): von
  // Mises = sqrt(3 J2) is monotonic in J2 (Particles::von_mises).
  double j2_max = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (body >= 0 && p.body[i] != body) continue;
    const double j2 = p.j2(i);
    if (j2 > j2_max) {
      j2_max = j2;
      s.particle = static_cast<long>(i);
    }
  }
  if (s.particle >= 0) s.von_mises = p.von_mises(static_cast<std::size_t>(s.particle));
  return s;
}

}  // namespace gearsph::diagnostics
