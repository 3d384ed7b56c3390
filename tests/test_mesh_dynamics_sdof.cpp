// The lumped mesh model (solver/gear/mesh_dynamics_sdof.hpp) against what
// can be derived for it: a spring-mass's frequency and static deflection,
// the forced response to a harmonic transmission error, the first-order
// dynamic factor of a harmonically varying stiffness, its super-harmonic
// at half the natural frequency, the threshold of the principal parametric
// resonance at twice it (damped Mathieu equation), and what backlash does.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "solver/gear/mesh_dynamics_iso.hpp"
#include "solver/gear/mesh_dynamics_sdof.hpp"
#include "solver/geometry/gear_profile.hpp"

namespace gearsph::gear::dynamics {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kMass = 1.0, kStiff = 1e8, kLoad = 1000.0;  // f_n = 1591.5 Hz, F / k = 10 um

SdofModel constant_model(double zeta, double load) {
  SdofModel m;
  m.mass_kg = kMass;
  m.stiffness.position = {0.0};
  m.stiffness.value = {kStiff};
  m.damping_ratio = zeta;
  m.load_N = load;
  return m;
}

double f_n() {
  return natural_frequency_Hz(kStiff, kMass);
}

TEST(MeshDynamicsSdof, MassesOnTheLineOfAction) {
  // J / r_b^2 and m / cos^2(alpha); a held pinion leaves the rack's.
  EXPECT_DOUBLE_EQ(pinion_mass_on_line_of_action(2e-3, 0.02), 5.0);
  const double a = 20.0 * kPi / 180.0;
  EXPECT_NEAR(rack_mass_on_line_of_action(1.0, a), 1.0 / (std::cos(a) * std::cos(a)), 1e-12);
  EXPECT_DOUBLE_EQ(effective_mesh_mass(2.0, 2.0), 1.0);
  EXPECT_DOUBLE_EQ(effective_mesh_mass(std::numeric_limits<double>::infinity(), 3.0), 3.0);
}

TEST(MeshDynamicsSdof, TwoLevelStiffnessHasTheContactRatiosShares) {
  const double eps = 1.6, ks = 1e8;
  const MeshCycleTable t = two_level_stiffness(ks, 1.75 * ks, eps);
  EXPECT_NEAR(t.mean(), ks * ((2.0 - eps) + 1.75 * (eps - 1.0)), 1e-6 * ks);
  // ISO 6336-1's c_gamma_alpha = c' (0.75 eps + 0.25) for every eps in (1, 2).
  EXPECT_NEAR(t.mean(), ks * (0.75 * eps + 0.25), 1e-6 * ks);
  EXPECT_DOUBLE_EQ(t.at(0.3), 1.75 * ks);  // double contact over [0, 0.6)
  EXPECT_DOUBLE_EQ(t.at(0.8), ks);
  EXPECT_DOUBLE_EQ(t.at(1.3), 1.75 * ks);  // periodic
  EXPECT_THROW(two_level_stiffness(ks, 2 * ks, 2.1), std::invalid_argument);
}

TEST(MeshDynamicsSdof, BacklashDeadZone) {
  EXPECT_DOUBLE_EQ(backlash_deflection(2e-6, 1e-5), 2e-6);
  EXPECT_DOUBLE_EQ(backlash_deflection(-5e-6, 1e-5), 0.0);
  EXPECT_DOUBLE_EQ(backlash_deflection(-1.2e-5, 1e-5), -2e-6);  // the reverse flank
}

TEST(MeshDynamicsSdof, ConstantStiffnessRingsAtSqrtKOverM) {
  const SdofModel m = constant_model(0.0, 0.0);
  const double T = 1.0 / f_n(), dt = T / 200.0;
  const std::vector<double> x = free_response(m, {1e-6, 0.0}, dt, 20 * 200 + 50);
  // Upward zero crossings, linearly interpolated: 20 periods.
  std::vector<double> up;
  for (std::size_t k = 1; k < x.size(); ++k) {
    if (x[k - 1] < 0.0 && x[k] >= 0.0) up.push_back(dt * (k - x[k] / (x[k] - x[k - 1])));
  }
  ASSERT_GE(up.size(), 20u);
  const double period = (up[19] - up[0]) / 19.0;
  EXPECT_NEAR(1.0 / period, f_n(), 1e-5 * f_n());
}

TEST(MeshDynamicsSdof, SettlesAtTheStaticDeflection) {
  const SdofModel m = constant_model(0.2, kLoad);
  SdofState y;  // released at x = 0: an overshoot, then F / k
  const SdofResponse r = respond_at(m, 0.3 * f_n(), y);
  EXPECT_TRUE(r.steady);
  EXPECT_NEAR(r.dte_mean_m, kLoad / kStiff, 1e-4 * kLoad / kStiff);
  EXPECT_NEAR(r.K_v, 1.0, 1e-3);  // nothing excites a constant mesh
  EXPECT_NEAR(r.mean_force_N, kLoad, 1e-3 * kLoad);
  EXPECT_EQ(r.contact_loss_fraction, 0.0);
}

// A harmonic transmission error e0 cos(Omega t) on a constant mesh is a
// base-excited oscillator: x - x_s = e0 cos(Omega t - phi) / |D|, |D| =
// sqrt((1 - r^2)^2 + (2 zeta r)^2) (any vibration text, e.g. Rao,
// Mechanical Vibrations, 3.6 with the damper on the excitation removed).
TEST(MeshDynamicsSdof, HarmonicErrorGivesTheForcedResponse) {
  const double zeta = 0.05, e0 = 1e-6;
  SdofModel m = constant_model(zeta, kLoad);
  m.error = harmonic_table(1.0, 1.0, 256);
  for (double& v : m.error.value) v = e0 * (v - 1.0);  // e0 cos(2 pi s)
  for (double r : {0.5, 1.0, 1.6}) {
    SdofState y = static_state(m);
    const SdofResponse res = respond_at(m, r * f_n(), y);
    ASSERT_TRUE(res.steady) << r;
    // The damper acts on x', not on (x - e)': the excitation is k e only.
    const double amp = e0 / std::hypot(1.0 - r * r, 2.0 * zeta * r);
    EXPECT_NEAR(res.dte_pp_m, 2.0 * amp, 5e-3 * 2.0 * amp) << r;
    EXPECT_NEAR(res.dte_rms_m, amp / std::sqrt(2.0), 5e-3 * amp) << r;
    // The mesh force's fluctuation is -m x'': m Omega^2 amp.
    const double w = 2.0 * kPi * r * f_n();
    EXPECT_NEAR(res.K_v - 1.0, kMass * w * w * amp / kLoad, 5e-3 * kMass * w * w * amp / kLoad)
        << r;
  }
}

// k0 (1 + eps cos Omega t) under F: to first order in eps the mesh force
// fluctuates by F eps r^2 / |D(r)| (x = x_s (1 - eps H cos), H the
// oscillator's response; the force is F - m x''), so K_v = 1 + eps r^2 /
// |D(r)|, largest just above r = 1.
TEST(MeshDynamicsSdof, VaryingStiffnessResonatesAtTheNaturalFrequency) {
  const double zeta = 0.05, eps = 0.005;
  SdofModel m = constant_model(zeta, kLoad);
  m.stiffness = harmonic_table(kStiff, eps, 256);
  // Away from r = 1/2, where the second-order super-harmonic (next test)
  // adds eps |H(2r)| (2r)^2 / 2 of the first-order term: 2 % at r = 0.35.
  for (double r : {0.35, 1.0, 1.5}) {
    SdofState y = static_state(m);
    const SdofResponse res = respond_at(m, r * f_n(), y);
    ASSERT_TRUE(res.steady) << r;
    const double first_order = eps * r * r / std::hypot(1.0 - r * r, 2.0 * zeta * r);
    EXPECT_NEAR(res.K_v - 1.0, first_order, 0.03 * first_order) << r;
  }
  std::vector<double> ratios, kv;
  for (double r = 0.9; r <= 1.1001; r += 0.01) ratios.push_back(r);
  std::vector<double> f;
  for (double r : ratios) f.push_back(r * f_n());
  for (const SdofResponse& res : sweep(m, f)) kv.push_back(res.K_v);
  // The vertex of eps r^2 / |D|: r = 1 / sqrt(1 - 2 zeta^2) = 1.0025.
  EXPECT_NEAR(peak_abscissa(ratios, kv), 1.0025, 0.005);
}

// The super-harmonic: the stiffness's variation times the response at
// Omega drives the pair at 2 Omega, which resonates at Omega = omega_n / 2.
TEST(MeshDynamicsSdof, VaryingStiffnessHasASuperHarmonicAtHalfTheNaturalFrequency) {
  const double zeta = 0.02, eps = 0.2;
  SdofModel m = constant_model(zeta, kLoad);
  m.stiffness = harmonic_table(kStiff, eps, 256);
  std::vector<double> ratios, kv, f;
  for (double r = 0.40; r <= 0.6001; r += 0.01) {
    ratios.push_back(r);
    f.push_back(r * f_n());
  }
  for (const SdofResponse& res : sweep(m, f)) kv.push_back(res.K_v);
  const double at = peak_abscissa(ratios, kv);
  EXPECT_NEAR(at, 0.5, 0.02);
  // A peak of its own: the first-order curve rises monotonically there.
  EXPECT_GT(kv[10], kv.front() + 0.1);
  EXPECT_GT(kv[10], kv.back() + 0.1);
}

// The principal parametric resonance is at Omega = 2 omega_n (Mathieu):
// there the pair's free motion grows at lambda = omega_n (eps / 4 - zeta)
// (first-order averaging, e.g. Nayfeh & Mook, Nonlinear Oscillations, 5.7),
// unstable above eps = 4 zeta whatever the load (here none).
TEST(MeshDynamicsSdof, PrincipalParametricResonanceAtTwiceTheNaturalFrequency) {
  const double eps = 0.2;
  for (double zeta : {0.02, 0.035, 0.08}) {
    SdofModel m = constant_model(zeta, 0.0);
    m.stiffness = harmonic_table(kStiff, eps, 256);
    SdofState y{1e-7, 0.0};
    const int periods = 400;
    const std::vector<double> a = period_amplitudes(m, 2.0 * f_n(), y, periods);
    const double t = (periods - 101) / (2.0 * f_n());
    const double rate = std::log(a[periods - 1] / a[100]) / t;
    const double expected = 2.0 * kPi * f_n() * (eps / 4.0 - zeta);
    EXPECT_NEAR(rate, expected, 0.05 * std::abs(expected)) << zeta;
  }
  // Off the tongue (Omega = 1.5 omega_n) the same pair decays.
  SdofModel m = constant_model(0.02, 0.0);
  m.stiffness = harmonic_table(kStiff, eps, 256);
  SdofState y{1e-7, 0.0};
  const std::vector<double> a = period_amplitudes(m, 1.5 * f_n(), y, 400);
  EXPECT_LT(a.back(), 0.1 * a.front());
}

// Backlash at light damping and a large stiffness variation: the teeth
// separate near resonance and the response has two branches, so a sweep
// up and one down disagree over a band (the jump); a load that dwarfs a
// fixed transmission error keeps the teeth together, a light one does not.
TEST(MeshDynamicsSdof, BacklashSeparatesAndJumps) {
  const double ks = kStiff;
  SdofModel m;
  m.mass_kg = kMass;
  m.stiffness = two_level_stiffness(ks, kIsoDoubleOverSinglePair * ks, 1.5, 0.02);
  m.damping_ratio = 0.02;
  m.load_N = kLoad;
  m.backlash_m = 20.0 * kLoad / ks;
  const double fn = natural_frequency_Hz(m.stiffness.mean(), kMass);
  std::vector<double> up, down;
  for (double r = 0.70; r <= 1.2001; r += 0.025) up.push_back(r * fn);
  down.assign(up.rbegin(), up.rend());
  const std::vector<SdofResponse> a = sweep(m, up), b = sweep(m, down);
  double widest = 0.0, loss = 0.0;
  for (std::size_t k = 0; k < up.size(); ++k) {
    const SdofResponse& u = a[k];
    const SdofResponse& d = b[up.size() - 1 - k];
    widest = std::max(widest, std::abs(u.K_v - d.K_v));
    loss = std::max({loss, u.contact_loss_fraction, d.contact_loss_fraction});
  }
  EXPECT_GT(loss, 0.05);
  EXPECT_GT(widest, 0.3);
  // The up sweep starts from the static mesh on the branch in contact; the
  // down sweep arrives there on the impacting one (at this damping and
  // stiffness variation the two branches reach below r = 0.7).
  EXPECT_EQ(a.front().contact_loss_fraction, 0.0);
  EXPECT_GT(b.back().contact_loss_fraction, 0.0);
}

TEST(MeshDynamicsSdof, HeavyLoadKeepsContactAgainstAFixedError) {
  const double zeta = 0.05, e0 = 1e-6;
  // At resonance (x - e) swings by about e0 / (2 zeta) = 10 um about F / k.
  for (double load : {200.0, 5000.0}) {
    SdofModel m = constant_model(zeta, load);
    m.backlash_m = 1e-3;
    m.error = harmonic_table(1.0, 1.0, 256);
    for (double& v : m.error.value) v = e0 * (v - 1.0);
    SdofState y = static_state(m);
    const SdofResponse res = respond_at(m, f_n(), y);
    if (load < 1000.0) {
      EXPECT_GT(res.contact_loss_fraction, 0.1) << load;
    } else {
      EXPECT_EQ(res.contact_loss_fraction, 0.0) << load;
    }
  }
}

// Without a fixed error the stiffness's own excitation scales with the
// load: K_v and the contact loss do not depend on it, the DTE is
// proportional to it.
TEST(MeshDynamicsSdof, ParametricResponseScalesWithTheLoad) {
  SdofModel m;
  m.mass_kg = kMass;
  m.stiffness = two_level_stiffness(kStiff, 1.75 * kStiff, 1.6, 0.02);
  m.damping_ratio = 0.05;
  const double fn = natural_frequency_Hz(m.stiffness.mean(), kMass);
  m.load_N = 500.0;
  SdofState y1 = static_state(m);
  const SdofResponse r1 = respond_at(m, 0.8 * fn, y1);
  m.load_N = 5000.0;
  SdofState y2 = static_state(m);
  const SdofResponse r2 = respond_at(m, 0.8 * fn, y2);
  EXPECT_NEAR(r1.K_v, r2.K_v, 1e-3 * r1.K_v);
  EXPECT_NEAR(r2.dte_pp_m, 10.0 * r1.dte_pp_m, 1e-3 * r2.dte_pp_m);
}

// ISO 6336-1 method B for a pinion with its rack: the reduced mass is the
// pinion's alone (6.5.9), n_E1 = 30000 / (pi z_1) sqrt(c_gamma_alpha /
// m_red), and a perfect involute below resonance has K_v = 1 + 0.23 N
// (C_v3 B_k N with B_k = 1, Table 8 for eps_gamma <= 2).
TEST(MeshDynamicsIso, RackPinionResonanceUsesThePinionsMassAlone) {
  geometry::PinionSpec ps;
  ps.teeth = 20;
  ps.tool.module_m = 3e-3;
  const geometry::PinionGeometry pinion(ps);
  const double rho = 7850.0;
  const IsoDynamics iso = iso_rack_pinion_dynamics(pinion, 0.02, 206e9, 206e9, rho, 5000.0, 1000.0);
  const double d_m = (pinion.tip_radius() + pinion.root_radius()) * 1e3;  // mm
  const double d_b = 2e3 * pinion.base_radius();
  const double m_pinion = kPi * rho * 1e-9 * std::pow(d_m, 4) / (8.0 * d_b * d_b);
  EXPECT_NEAR(iso.m_red_kg_mm, m_pinion, 1e-6 * m_pinion);
  const double n_E1 = 30000.0 / (kPi * 20) * std::sqrt(iso.c_gamma_alpha_N_mm_um / m_pinion);
  EXPECT_NEAR(iso.n_E1_rpm, n_E1, 1e-6 * n_E1);
  EXPECT_NEAR(iso.resonance_mesh_Hz, iso.n_E1_rpm * 20 / 60.0, 1e-9);
  ASSERT_EQ(iso.range, "subcritical");
  EXPECT_NEAR(iso.K_v, 1.0 + 0.23 * iso.N, 1e-9);
}

}  // namespace
}  // namespace gearsph::gear::dynamics
