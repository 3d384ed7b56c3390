// validation.md section 1 on graded, body-fitted particles: the kernel sums
// with a smoothing length per pair h_ij = (h_i + h_j) / 2 stay near one in
// the interior, the corrected gradients of the total-Lagrangian pairs are
// exact for linear and quadratic fields everywhere (outline rows and the
// graded zone included), and pairs are equal and opposite.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "solver/job/job.hpp"
#include "solver/physics/total_lagrangian.hpp"

namespace gearsph {
namespace {

// A plate with a hole, graded 8:1 from the hole (0.25 mm) to 2 mm.
PreparedJob graded_plate(const char* kernel = "seed_quartic", double grading = 0.0) {
  nlohmann::json d = {{"spacing_mm", 2.0}, {"fine_spacing_mm", 0.25}, {"kernel", kernel}};
  if (grading > 0.0) d["grading"] = grading;
  return prepare_job({{"scene",
                       {{"type", "plate_with_hole"},
                        {"width_m", 0.04},
                        {"length_m", 0.08},
                        {"hole_radius_m", 0.0025}}},
                      {"discretization", d}},
                     1);
}

TEST(GradedKernel, TheSetIsGradedEightToOne) {
  const PreparedJob job = graded_plate();
  const Particles& p = job.scene.sim.particles;
  const auto [lo, hi] = std::minmax_element(p.spacing.begin(), p.spacing.end());
  EXPECT_NEAR(*lo, 0.25e-3, 1e-12);
  EXPECT_GE(*hi / *lo, 7.5);
}

// The smooth kernels' sums stay within a few per cent of one across the 8:1
// grading (validation.md section 1). Measured: 2.1-2.4 % at worst in the
// graded zone against 0.7-1.5 % on relaxed uniform 2 mm particles; the
// excess is the second-order term of a smoothing length that varies across
// the support (h_ij = (h_i + h_j) / 2 cancels the first-order one). The
// pair's smaller length instead of the mean gives 3.3-4.3 %, the larger
// 6.3-6.9 %. The seed paper's quartic is left out: with its cusp (f'(0) = -64) and h = dx
// its own term is 0.46 of the sum, so its sums depend on the packing, not
// the grading: 1.10-1.13 in the uniform 2 mm bulk of this plate, whose
// relaxed packing is nearly hexagonal (docs/method.md). The total-Lagrangian
// form uses only corrected gradients (next test), which are exact either way.
class GradedKernelSums : public ::testing::TestWithParam<const char*> {};

TEST_P(GradedKernelSums, StayNearOneInTheInterior) {
  PreparedJob job = graded_plate(GetParam());
  Simulation& sim = job.scene.sim;
  physics::total_lagrangian_setup(sim);
  const Particles& p = sim.particles;
  const ReferencePairs& rp = sim.reference;
  ASSERT_FALSE(rp.hp.empty()) << "graded particles have a smoothing length each";
  std::vector<double> sum(p.n, 0.0);
  with_kernel(sim.discretization.kernel, 1.0, [&](const auto& k) {
    using K = std::decay_t<decltype(k)>;
    for (std::size_t i = 0; i < p.n; ++i) {
      sum[i] += rp.vol0[i] * K::W_at(0.0, rp.hp[i]);
      for (std::uint32_t e = rp.rows[i]; e < rp.rows[i + 1]; ++e) {
        const std::uint32_t j = rp.j[e];
        const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
        const double w = K::W_at(std::sqrt(dx * dx + dy * dy), 0.5 * (rp.hp[i] + rp.hp[j]));
        sum[i] += rp.vol0[j] * w;
        sum[j] += rp.vol0[i] * w;
      }
    }
  });
  // Interior: no support of the particle or of its coarser neighbours
  // reaches the outline (the hole of radius 2.5 mm at the centre, the edges).
  double worst = 0.0;
  std::size_t interior = 0;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double reach = 2.0 * kernel_support(sim.discretization.kernel) *
                         sim.discretization.h_over_dx * p.spacing[i];
    const double r = std::hypot(p.x0[i], p.y0[i]);
    if (r < 2.5e-3 + reach || std::abs(p.x0[i]) > 0.04 - reach ||
        std::abs(p.y0[i]) > 0.02 - reach) {
      continue;
    }
    ++interior;
    worst = std::max(worst, std::abs(sum[i] - 1.0));
  }
  EXPECT_GT(interior, 20u);
  EXPECT_LT(worst, 0.03) << "kernel sum in the graded interior";
}

INSTANTIATE_TEST_SUITE_P(SmoothKernels, GradedKernelSums,
                         ::testing::Values("wendland_c2", "cubic_spline", "quintic_spline"));

TEST(GradedKernel, CorrectedGradientsAreExactForQuadraticFieldsEverywhere) {
  PreparedJob job = graded_plate();
  Simulation& sim = job.scene.sim;
  physics::total_lagrangian_setup(sim);
  const Particles& p = sim.particles;
  const ReferencePairs& rp = sim.reference;
  // u(x) = a + b.x + x^T C x in millimetres, and its exact gradient.
  auto u = [](double x, double y) {
    x *= 1e3;
    y *= 1e3;
    return 0.3 + 1.1 * x - 0.7 * y + 0.2 * x * x - 0.5 * x * y + 0.35 * y * y;
  };
  auto du = [](double x, double y) {
    x *= 1e3;
    y *= 1e3;
    return std::pair{1e3 * (1.1 + 0.4 * x - 0.5 * y), 1e3 * (-0.7 - 0.5 * x + 0.7 * y)};
  };
  std::vector<double> gx(p.n, 0.0), gy(p.n, 0.0), mxx(p.n, 0.0), myy(p.n, 0.0), mxy(p.n, 0.0);
  for (std::size_t i = 0; i < p.n; ++i) {
    for (std::uint32_t e = rp.rows[i]; e < rp.rows[i + 1]; ++e) {
      const std::uint32_t j = rp.j[e];
      const double d = u(p.x0[j], p.y0[j]) - u(p.x0[i], p.y0[i]);
      gx[i] += rp.vol0[j] * d * rp.g[4 * e];
      gy[i] += rp.vol0[j] * d * rp.g[4 * e + 1];
      gx[j] -= rp.vol0[i] * d * rp.g[4 * e + 2];
      gy[j] -= rp.vol0[i] * d * rp.g[4 * e + 3];
      // sum_j V_j (X_j - X_i) (x) G_ij = I (linear consistency)
      const double rx = p.x0[j] - p.x0[i], ry = p.y0[j] - p.y0[i];
      mxx[i] += rp.vol0[j] * rx * rp.g[4 * e];
      myy[i] += rp.vol0[j] * ry * rp.g[4 * e + 1];
      mxy[i] += rp.vol0[j] * rx * rp.g[4 * e + 1];
      mxx[j] -= rp.vol0[i] * rx * rp.g[4 * e + 2];
      myy[j] -= rp.vol0[i] * ry * rp.g[4 * e + 3];
      mxy[j] -= rp.vol0[i] * rx * rp.g[4 * e + 3];
    }
  }
  std::size_t quadratic = 0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.correction_order[i] != static_cast<std::uint8_t>(GradientCorrection::Quadratic)) continue;
    ++quadratic;
    const auto [ex, ey] = du(p.x0[i], p.y0[i]);
    const double scale = std::hypot(ex, ey);
    ASSERT_NEAR(gx[i], ex, 1e-8 * scale) << i;
    ASSERT_NEAR(gy[i], ey, 1e-8 * scale) << i;
    ASSERT_NEAR(mxx[i], 1.0, 1e-9) << i;
    ASSERT_NEAR(myy[i], 1.0, 1e-9) << i;
    ASSERT_NEAR(mxy[i], 0.0, 1e-9) << i;
  }
  // Every particle of a smooth outline keeps the quadratic correction.
  EXPECT_EQ(quadratic, p.n);
}

TEST(GradedKernel, PairsAreSymmetricInTheirSmoothingLength) {
  PreparedJob job = graded_plate();
  Simulation& sim = job.scene.sim;
  physics::total_lagrangian_setup(sim);
  const ReferencePairs& rp = sim.reference;
  const Particles& p = sim.particles;
  // dW/dr of a pair is one number for both ends: its h is (h_i + h_j) / 2,
  // and the pair is kept when within the support of that h.
  with_kernel(sim.discretization.kernel, 1.0, [&](const auto& k) {
    using K = std::decay_t<decltype(k)>;
    for (std::size_t i = 0; i < p.n; ++i) {
      for (std::uint32_t e = rp.rows[i]; e < rp.rows[i + 1]; ++e) {
        const std::uint32_t j = rp.j[e];
        const double h = 0.5 * (rp.hp[i] + rp.hp[j]);
        const double dx = p.x0[i] - p.x0[j], dy = p.y0[i] - p.y0[j];
        const double r = std::sqrt(dx * dx + dy * dy);  // as the set-up computes it
        ASSERT_LT(r, K::shape_type::support * h);
        // To round-off on the scale of the gradient at r = h.
        ASSERT_NEAR(rp.dw0[e], K::dW_at(r, h), 1e-10 * std::abs(K::dW_at(h, h)));
      }
    }
  });
}

// The patch test across the grading: under a uniform strain the pair forces
// of a particle whose support stays off the outline cancel, up to the
// particles' disorder. Measured as the force density times the spacing
// over the stress: uniform body-fitted particles leave a median of 0.4 %
// and a 95th percentile of 1.3 %. Grading adds to it, the more the faster
// the spacing grows, and the gear's fillet stress follows (docs/gears.md):
// the default (0.12) must leave under half the 95th percentile of 0.25.
std::vector<double> uniform_strain_residual(PreparedJob job) {
  Simulation& sim = job.scene.sim;
  sim.method.viscosity.alpha = sim.method.viscosity.beta = 0.0;
  physics::total_lagrangian_setup(sim);
  Particles& p = sim.particles;
  constexpr double e = 1e-4;
  for (std::size_t i = 0; i < p.n; ++i) {
    p.x[i] = p.x0[i] * (1.0 + e);
    p.y[i] = p.y0[i] * (1.0 - 0.3 * e) + 0.5 * e * p.x0[i];
  }
  physics::total_lagrangian_stress(sim);
  physics::total_lagrangian_momentum(sim, 0.0);
  double sigma = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) sigma = std::max(sigma, std::abs(p.sigma_xx(i)));
  // The graded annulus round the hole, 1.5 mm (six fine spacings) from it
  // and 8 mm (four coarse ones) from the plate's edges.
  std::vector<double> residual;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double r = std::hypot(p.x0[i], p.y0[i]);
    if (r < 4e-3 || r > 14e-3 || std::abs(p.y0[i]) > 12e-3) continue;
    residual.push_back(p.rho0[i] * std::hypot(p.ax[i], p.ay[i]) * p.spacing[i] / sigma);
  }
  std::sort(residual.begin(), residual.end());
  return residual;
}

TEST(GradedKernel, UniformStrainIsInEquilibriumAcrossTheGrading) {
  const std::vector<double> graded = uniform_strain_residual(graded_plate());
  const std::vector<double> fast = uniform_strain_residual(graded_plate("seed_quartic", 0.25));
  ASSERT_GT(graded.size(), 100u);
  ASSERT_GT(fast.size(), 40u);
  auto at = [](const std::vector<double>& v, double q) {
    return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
  };
  std::printf(
      "uniform strain residual, median and 95th percentile: grading 0.12 %.4f %.4f, "
      "0.25 %.4f %.4f\n",
      at(graded, 0.5), at(graded, 0.95), at(fast, 0.5), at(fast, 0.95));
  EXPECT_LT(at(graded, 0.95), 0.5 * at(fast, 0.95));
  EXPECT_LT(at(graded, 0.95), 0.05);
}

}  // namespace
}  // namespace gearsph
