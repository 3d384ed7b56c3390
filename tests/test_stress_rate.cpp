// Constitutive update (physics/stress_rate.hpp): plane-strain bookkeeping
// and the Jaumann rotation, checked on single particles against numbers
// derived by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/physics/simulation.hpp"
#include "solver/physics/stress_rate.hpp"

namespace gearsph {
namespace {

Simulation one_particle(const Material& mat) {
  Simulation sim;
  Body b;
  b.name = "block";
  b.material = mat;
  sim.bodies.push_back(b);
  sim.particles.add(0.0, 0.0, mat.rho0 * 1e-6, mat.rho0, 0, 0, 1e-3);
  sim.bodies[0].end = 1;
  sim.method.artificial_stress.epsilon = 0.0;
  return sim;
}

const Material kSteel{2e11, 0.3, 7800};

TEST(StressRate, UniaxialStrainGivesThePWaveModulus) {
  // D = diag(e, 0), D_zz = 0 (plane strain, laterally confined):
  // sigma_xx = (K + 4G/3) e dt, sigma_yy = sigma_zz = (K - 2G/3) e dt = lambda e dt.
  Simulation sim = one_particle(kSteel);
  Particles& p = sim.particles;
  const double rate = 1e-3, dt = 1e-6;
  p.lxx[0] = rate;
  p.drho[0] = -p.rho[0] * rate;  // continuity
  physics::update_stress(sim, dt);
  const double e = rate * dt;
  const double K = kSteel.bulk_modulus(), G = kSteel.shear_modulus();
  // Extension is tension. The density becomes rho0 (1 - e), so p = -K e; the
  // tolerance covers the round-off of 1 - 1e-9.
  EXPECT_NEAR(p.sigma_xx(0), (K + 4 * G / 3) * e, 1e-6 * K * e);
  EXPECT_NEAR(p.sigma_yy(0), (K - 2 * G / 3) * e, 1e-6 * K * e);
  EXPECT_NEAR(p.sigma_zz(0), kSteel.lame_lambda() * e, 1e-6 * K * e);
  // Deviator is trace-free with the 1/3 of a 3D deviator (not 1/dim).
  EXPECT_NEAR(p.sxx[0] + p.syy[0] + p.szz[0], 0.0, 1e-9 * G * e);
  EXPECT_NEAR(p.szz[0], -2.0 * G * e / 3.0, 1e-6 * G * e);
}

TEST(StressRate, SimpleShearBuildsShearStressOnly) {
  Simulation sim = one_particle(kSteel);
  Particles& p = sim.particles;
  const double gamma_dot = 2e-3, dt = 1e-7;
  p.lxy[0] = gamma_dot;  // v_x = gamma_dot y
  physics::update_stress(sim, dt);
  // D_xy = gamma_dot / 2 -> S_xy = G gamma_dot dt; the spin rotates a zero stress: nothing.
  EXPECT_NEAR(p.sxy[0], kSteel.shear_modulus() * gamma_dot * dt, 1e-6);
  EXPECT_NEAR(p.sxx[0], 0.0, 1e-9);
  EXPECT_NEAR(p.syy[0], 0.0, 1e-9);
  EXPECT_NEAR(p.p[0], 0.0, 1e-9);
}

TEST(StressRate, JaumannRotationIsExactForARigidSpin) {
  // L = omega [[0, -1], [1, 0]] (counter-clockwise): S(t) = R S0 R^T.
  Simulation sim = one_particle(kSteel);
  Particles& p = sim.particles;
  p.sxx[0] = 3e7;
  p.syy[0] = -1e7;
  p.sxy[0] = 5e6;
  p.szz[0] = -2e7;
  const double omega = 1000.0, dt = 1e-5;
  const int steps = 400;
  for (int s = 0; s < steps; ++s) {
    p.lxy[0] = -omega;
    p.lyx[0] = omega;
    physics::update_stress(sim, dt);
  }
  // Hughes-Winget turns each step by 2 atan(omega dt / 2).
  const double angle = steps * 2.0 * std::atan(0.5 * omega * dt);
  const double c = std::cos(angle), s = std::sin(angle);
  const double xx = 3e7, yy = -1e7, xy = 5e6;
  EXPECT_NEAR(p.sxx[0], c * c * xx - 2 * c * s * xy + s * s * yy, 1e-6);
  EXPECT_NEAR(p.syy[0], s * s * xx + 2 * c * s * xy + c * c * yy, 1e-6);
  EXPECT_NEAR(p.sxy[0], c * s * (xx - yy) + (c * c - s * s) * xy, 1e-6);
  EXPECT_DOUBLE_EQ(p.szz[0], -2e7);  // out of plane: untouched by an in-plane spin
  // and the turned angle is the true one to second order in omega dt.
  EXPECT_NEAR(angle, steps * omega * dt, steps * std::pow(omega * dt, 3) / 12 + 1e-12);
}

TEST(StressRate, RotationKeepsTheStressMagnitude) {
  Simulation sim = one_particle(kSteel);
  Particles& p = sim.particles;
  p.sxx[0] = 1e8;
  p.syy[0] = -4e7;
  p.szz[0] = -6e7;
  p.sxy[0] = 2e7;
  auto norm = [&] { return p.sxx[0] * p.sxx[0] + p.syy[0] * p.syy[0] + 2 * p.sxy[0] * p.sxy[0]; };
  const double before = norm();
  for (int s = 0; s < 100000; ++s) {
    p.lxy[0] = -3e4;  // a large spin: omega dt = 0.3
    p.lyx[0] = 3e4;
    physics::update_stress(sim, 1e-5);
  }
  EXPECT_NEAR(norm() / before, 1.0, 1e-10);
}

}  // namespace
}  // namespace gearsph
