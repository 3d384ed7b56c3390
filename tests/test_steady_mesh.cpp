// The steady mesh read from histories (solver/diagnostics/steady_mesh.hpp)
// on signals whose answers are known: a decaying start transient on a
// periodic mesh force, a force that drops to zero over a known share of
// each cycle, a response that never settles, and free ringings of known
// damping (a formula, and the lumped model's own).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "solver/diagnostics/steady_mesh.hpp"
#include "solver/gear/mesh_dynamics_sdof.hpp"

namespace gearsph::diagnostics {
namespace {

constexpr double kPi = std::numbers::pi;

MeshHistories synthetic(double f_mesh, double end_s, double rate_Hz) {
  MeshHistories h;
  h.mesh_frequency_Hz = f_mesh;
  const int n = static_cast<int>(end_s * rate_Hz);
  for (int k = 0; k <= n; ++k) h.t.push_back(k / rate_Hz);
  return h;
}

TEST(SteadyMesh, FindsTheEndOfTheStartTransient) {
  MeshHistories h = synthetic(100.0, 0.5, 2e4);
  const double F0 = 1000.0, tau = 0.02;
  std::vector<double> t0, t1;
  for (double t : h.t) {
    const double mesh = F0 * (1.0 + 0.3 * std::cos(2 * kPi * 100.0 * t));
    h.total_force_N.push_back(mesh + 2.0 * F0 * std::exp(-t / tau) * std::cos(2 * kPi * 730.0 * t));
    h.dte_m.push_back(1e-5 + 2e-7 * std::sin(2 * kPi * 100.0 * t));
    // Two teeth taking turns, half a cycle each.
    const bool first = std::fmod(t * 100.0, 1.0) < 0.5;
    t0.push_back(first ? h.total_force_N.back() : 0.0);
    t1.push_back(first ? 0.0 : h.total_force_N.back());
  }
  h.tooth_force_N = {{0, t0}, {1, t1}};
  const SteadyMesh s = steady_mesh(h);
  ASSERT_TRUE(s.steady) << s.note;
  // The transient's envelope 2 F0 e^{-t/tau} falls below 5 % of the peak
  // 1.3 F0 at t = tau ln(2 / 0.065) = 0.0686 s: the first whole period
  // after it starts at 0.07 s, or one period before where the envelope's
  // largest excursion does not meet its own peak.
  EXPECT_GE(s.steady_from_s, 0.05);
  EXPECT_LE(s.steady_from_s, 0.0801);
  EXPECT_EQ(s.periods_in_run, 50);
  EXPECT_NEAR(s.mean_force_N, F0, 5e-3 * F0);
  // What is left of the transient in the window is within the detector's
  // 5 % of the peak: K_v lies between 1.3 and 1.3 + 0.05 * 1.3.
  EXPECT_GE(s.K_v, 1.3 - 1e-3);
  EXPECT_LE(s.K_v, 1.3 * 1.05);
  EXPECT_NEAR(s.dte_pp_m, 4e-7, 1e-9);
  EXPECT_NEAR(s.dte_rms_m, 2e-7 / std::sqrt(2.0), 2e-9);
  EXPECT_EQ(s.contact_loss_fraction, 0.0);
  ASSERT_EQ(s.teeth.size(), 2u);
  EXPECT_NEAR(s.teeth[0].loaded_fraction, 0.5, 0.01);
  EXPECT_NEAR(s.teeth[0].mean_N + s.teeth[1].mean_N, s.mean_force_N, 1e-9 * F0);
}

TEST(SteadyMesh, ContactLossIsTheShareOfTimeWithoutForce) {
  MeshHistories h = synthetic(50.0, 0.4, 2e4);
  for (double t : h.t) {
    h.total_force_N.push_back(std::max(0.0, 1000.0 * (1.0 + 1.5 * std::cos(2 * kPi * 50.0 * t))));
  }
  const SteadyMesh s = steady_mesh(h);
  ASSERT_TRUE(s.steady);
  // cos < -2/3 over a share 1 - arccos(-2/3) / pi of each cycle.
  EXPECT_NEAR(s.contact_loss_fraction, 1.0 - std::acos(-2.0 / 3.0) / kPi, 0.005);
  EXPECT_EQ(s.steady_from_s, 0.0);
}

TEST(SteadyMesh, SaysSoWhenTheMeshNeverSettles) {
  MeshHistories h = synthetic(100.0, 0.2, 1e4);
  for (double t : h.t) {
    // A load that keeps rising, 7.5 % a period at the end.
    h.total_force_N.push_back(1000.0 * std::pow(1.0 + t / 0.2, 3) *
                              (1.0 + 0.2 * std::cos(2 * kPi * 100.0 * t)));
  }
  const SteadyMesh s = steady_mesh(h);
  EXPECT_FALSE(s.steady);
  EXPECT_NE(s.note.find("no steady mesh"), std::string::npos);
  EXPECT_NEAR(s.steady_from_s, 0.1, 1e-3);  // the second half, flagged
  // Too short for a mesh period.
  MeshHistories short_run = synthetic(10.0, 0.05, 1e4);
  short_run.total_force_N.assign(short_run.t.size(), 1.0);
  EXPECT_FALSE(steady_mesh(short_run).steady);
}

TEST(RingDown, RecoversTheDampingOfADecayingCosine) {
  const double zeta = 0.03, f = 2000.0, w = 2 * kPi * f;
  std::vector<double> t, v;
  for (int k = 0; k < 20000; ++k) {
    t.push_back(k * 1e-6);
    const double wd = w * std::sqrt(1.0 - zeta * zeta);
    v.push_back(5.0 + 0.5 * std::exp(-zeta * w * t.back()) * std::cos(wd * t.back()));
  }
  const RingDown r = ring_down(t, v, 0.0, 0.02);
  ASSERT_GE(r.extremes, 3);
  EXPECT_NEAR(r.damping_ratio, zeta, 0.02 * zeta);
  EXPECT_NEAR(r.frequency_Hz, f * std::sqrt(1.0 - zeta * zeta), 0.01 * f);
}

TEST(RingDown, RecoversTheLumpedModelsOwnDamping) {
  using namespace gear::dynamics;
  SdofModel m;
  m.mass_kg = 2.0;
  m.stiffness.position = {0.0};
  m.stiffness.value = {3e8};
  m.damping_ratio = 0.05;
  m.load_N = 3000.0;
  const double fn = natural_frequency_Hz(3e8, 2.0), dt = 1.0 / (fn * 100.0);
  const std::vector<double> x = free_response(m, {0.0, 0.0}, dt, 3000);
  std::vector<double> t;
  for (std::size_t k = 0; k < x.size(); ++k) t.push_back(dt * (k + 1));
  const RingDown r = ring_down(t, x, 0.0, t.back());
  EXPECT_NEAR(r.damping_ratio, 0.05, 0.002);
}

}  // namespace
}  // namespace gearsph::diagnostics
