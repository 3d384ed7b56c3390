#include "solver/physics/stress_rate.hpp"

#include "solver/core/passes.hpp"
#include "solver/physics/artificial_stress.hpp"
#include "solver/physics/elastic_law.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::physics {

namespace {

void cache_for_momentum(Particles& p, std::size_t i, const ArtificialStress& as) {
  const double inv_rho2 = 1.0 / (p.rho[i] * p.rho[i]);
  const double sxx = (p.sxx[i] - p.p[i]) * inv_rho2;
  const double syy = (p.syy[i] - p.p[i]) * inv_rho2;
  const double sxy = p.sxy[i] * inv_rho2;
  // (sigma / rho^2) C, both blocks: with C = [I | 0] this is the plain SPH
  // stress term.
  p.qxx[i] = sxx * p.bxx[i] + sxy * p.byx[i];
  p.qxy[i] = sxx * p.bxy[i] + sxy * p.byy[i];
  p.qyx[i] = sxy * p.bxx[i] + syy * p.byx[i];
  p.qyy[i] = sxy * p.bxy[i] + syy * p.byy[i];
  p.qqx0[i] = sxx * p.bqx0[i] + sxy * p.bqy0[i];
  p.qqx1[i] = sxx * p.bqx1[i] + sxy * p.bqy1[i];
  p.qqx2[i] = sxx * p.bqx2[i] + sxy * p.bqy2[i];
  p.qqy0[i] = sxy * p.bqx0[i] + syy * p.bqy0[i];
  p.qqy1[i] = sxy * p.bqx1[i] + syy * p.bqy1[i];
  p.qqy2[i] = sxy * p.bqx2[i] + syy * p.bqy2[i];
  if (as.enabled()) {
    const Sym2 r = artificial_stress(as, p.sxx[i] - p.p[i], p.syy[i] - p.p[i], p.sxy[i], p.rho[i]);
    p.rxx[i] = r.xx;
    p.ryy[i] = r.yy;
    p.rxy[i] = r.xy;
  }
}

}  // namespace

void update_stress(Simulation& sim, double dt, std::size_t lo, std::size_t hi) {
  Particles& p = sim.particles;
  const ArtificialStress& as = sim.method.artificial_stress;
  for (std::size_t i = lo; i < hi; ++i) {
    const Material& mat = sim.material_of(i);
    const double K = mat.bulk_modulus(), two_g = 2.0 * mat.shear_modulus();

    p.rho[i] += dt * p.drho[i];
    p.p[i] = pressure_from_density(K, p.rho[i], p.rho0[i]);

    const double dxx = p.lxx[i], dyy = p.lyy[i], dxy = 0.5 * (p.lxy[i] + p.lyx[i]);
    const double w = 0.5 * (p.lxy[i] - p.lyx[i]);  // Omega_xy
    const double third_tr = (dxx + dyy) / 3.0;

    // Q = Cayley transform of dt Omega: rotation by 2 atan(dt w / 2).
    const double a = 0.5 * dt * w, den = 1.0 / (1.0 + a * a);
    const double c = (1.0 - a * a) * den, s = 2.0 * a * den;
    const double sxx = p.sxx[i], syy = p.syy[i], sxy = p.sxy[i];
    const double cc = c * c, ss = s * s, cs = c * s;
    p.sxx[i] = cc * sxx + 2.0 * cs * sxy + ss * syy + dt * two_g * (dxx - third_tr);
    p.syy[i] = ss * sxx - 2.0 * cs * sxy + cc * syy + dt * two_g * (dyy - third_tr);
    p.sxy[i] = cs * (syy - sxx) + (cc - ss) * sxy + dt * two_g * dxy;
    p.szz[i] += dt * two_g * (-third_tr);
    p.rot[i] -= dt * w;  // material rotation rate (CCW) is -Omega_xy

    cache_for_momentum(p, i, as);
  }
}

void update_stress(Simulation& sim, double dt) {
  over_shares<int>("stress", sim.particles.n, sim.threads,
                   [&](std::size_t lo, std::size_t hi, int&) { update_stress(sim, dt, lo, hi); });
}

void prepare_momentum(Simulation& sim) {
  Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) cache_for_momentum(p, i, sim.method.artificial_stress);
}

}  // namespace gearsph::physics
