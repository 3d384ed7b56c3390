// Gradient correction (physics/kernel_correction.hpp): the corrected SPH
// gradient is exact for linear fields (linear) and quadratic fields
// (quadratic), also where the kernel support is cut by a free surface or a
// corner, and the order is lowered where a fit cannot be trusted.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "solver/kernels/kernel.hpp"
#include "solver/physics/kernel_correction.hpp"

namespace gearsph {
namespace {

using physics::Correction;
using physics::Moments;

struct Neighbour {
  double dx, dy;  // d = x_i - x_j
  double dw_r;    // W'(r)/r = -w
};

// Unit lattice neighbours of a particle, keeping those with keep(a, b) true
// where (a, b) = x_j - x_i in lattice units.
template <class Keep>
std::vector<Neighbour> neighbourhood(KernelType type, double h, Keep keep) {
  return with_kernel(type, h, [&](const auto& k) {
    std::vector<Neighbour> out;
    const int reach = static_cast<int>(std::ceil(k.radius));
    for (int a = -reach; a <= reach; ++a) {
      for (int b = -reach; b <= reach; ++b) {
        const double r = std::hypot(a, b);
        if (r == 0.0 || r >= k.radius || !keep(a, b)) continue;
        out.push_back({-double(a), -double(b), k.dW(r) / r});
      }
    }
    return out;
  });
}

Correction correct(const std::vector<Neighbour>& nb, GradientCorrection order, double h) {
  Moments m;
  for (const Neighbour& n : nb) m.add(-n.dw_r, n.dx, n.dy, order == GradientCorrection::Quadratic);
  return physics::correction_from_moments(m, order, h);
}

// Gradient of u at the particle (x_i = 0) with corrected weights
// G_ij = -w C phi(d) = dw_r C phi(d).
template <class Field>
std::pair<double, double> gradient(const std::vector<Neighbour>& nb, const Correction& c, Field u) {
  double gx = 0, gy = 0;
  for (const Neighbour& n : nb) {
    const double du = u(-n.dx, -n.dy) - u(0.0, 0.0);
    const double q0 = n.dx * n.dx, q1 = n.dx * n.dy, q2 = n.dy * n.dy;
    gx += du * n.dw_r * (c.lxx * n.dx + c.lxy * n.dy + c.qx[0] * q0 + c.qx[1] * q1 + c.qx[2] * q2);
    gy += du * n.dw_r * (c.lyx * n.dx + c.lyy * n.dy + c.qy[0] * q0 + c.qy[1] * q1 + c.qy[2] * q2);
  }
  return {gx, gy};
}

const KernelType kAll[] = {KernelType::SeedQuartic, KernelType::CubicSpline,
                           KernelType::QuinticSpline, KernelType::WendlandC2};

class CorrectionEveryKernel : public ::testing::TestWithParam<KernelType> {
 protected:
  double h() const { return kernel_support(GetParam()) >= 3.0 ? 1.0 : 1.5; }
};

auto linear_field = [](double x, double y) { return 2 * x - 3 * y + 0.5; };
// Bending: u_x = -kappa x y; its x-gradient at the particle is 0 but at a
// surface an uncorrected fit sees the curvature.
auto quadratic_field = [](double x, double y) {
  return 0.7 * x * x - 1.3 * x * y + 0.4 * y * y + x;
};

TEST_P(CorrectionEveryKernel, InteriorLinearAndQuadraticAgree) {
  const auto nb = neighbourhood(GetParam(), h(), [](int, int) { return true; });
  const Correction lin = correct(nb, GradientCorrection::Linear, h());
  const Correction quad = correct(nb, GradientCorrection::Quadratic, h());
  EXPECT_EQ(quad.order, GradientCorrection::Quadratic);
  // Symmetric support: odd moments vanish, the quadratic block is zero.
  EXPECT_NEAR(lin.lxx, quad.lxx, 1e-12);
  EXPECT_NEAR(lin.lyy, quad.lyy, 1e-12);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(quad.qx[k], 0.0, 1e-12);
  const auto [gx, gy] = gradient(nb, quad, quadratic_field);
  EXPECT_NEAR(gx, 1.0, 1e-12);  // d/dx at the origin
  EXPECT_NEAR(gy, 0.0, 1e-12);
}

TEST_P(CorrectionEveryKernel, SurfaceLinearCorrectionIsExactForLinearOnly) {
  // Free surface above: neighbours with y_j <= y_i only.
  const auto nb = neighbourhood(GetParam(), h(), [](int, int b) { return b <= 0; });
  const Correction lin = correct(nb, GradientCorrection::Linear, h());
  ASSERT_EQ(lin.order, GradientCorrection::Linear);
  auto [lx, ly] = gradient(nb, lin, linear_field);
  EXPECT_NEAR(lx, 2.0, 1e-12);
  EXPECT_NEAR(ly, -3.0, 1e-12);
  // The curvature leaks into the linear fit at a surface...
  auto [qx, qy] = gradient(nb, lin, quadratic_field);
  EXPECT_GT(std::abs(qy - 0.0), 0.1) << "a surface should spoil the linear fit of a curved field";
  (void)qx;
  // ...and the quadratic correction removes it.
  const Correction quad = correct(nb, GradientCorrection::Quadratic, h());
  ASSERT_EQ(quad.order, GradientCorrection::Quadratic);
  auto [cx, cy] = gradient(nb, quad, quadratic_field);
  EXPECT_NEAR(cx, 1.0, 1e-10);
  EXPECT_NEAR(cy, 0.0, 1e-10);
}

TEST_P(CorrectionEveryKernel, CornerStillQuadratic) {
  const auto nb = neighbourhood(GetParam(), h(), [](int a, int b) { return a <= 0 && b <= 0; });
  const Correction quad = correct(nb, GradientCorrection::Quadratic, h());
  EXPECT_EQ(quad.order, GradientCorrection::Quadratic);
  auto [cx, cy] = gradient(nb, quad, quadratic_field);
  EXPECT_NEAR(cx, 1.0, 1e-9);
  EXPECT_NEAR(cy, 0.0, 1e-9);
}

TEST_P(CorrectionEveryKernel, OneRowThickFeatureFallsBackToLinearOrNone) {
  // A single row of particles: no information across it, a quadratic (and
  // even a linear) fit in y is impossible.
  const auto nb = neighbourhood(GetParam(), h(), [](int, int b) { return b == 0; });
  const Correction c = correct(nb, GradientCorrection::Quadratic, h());
  EXPECT_EQ(c.order, GradientCorrection::None);
  EXPECT_DOUBLE_EQ(c.lxx, 1.0);
  EXPECT_DOUBLE_EQ(c.lyy, 1.0);
}

TEST(GradientCorrection, NamesAreTheSchemaValues) {
  EXPECT_STREQ(gradient_correction_name(GradientCorrection::None), "none");
  EXPECT_STREQ(gradient_correction_name(GradientCorrection::Linear), "linear");
  EXPECT_STREQ(gradient_correction_name(GradientCorrection::Quadratic), "quadratic");
}

INSTANTIATE_TEST_SUITE_P(Kernels, CorrectionEveryKernel, ::testing::ValuesIn(kAll),
                         [](const ::testing::TestParamInfo<KernelType>& p) {
                           return std::string(kernel_name(p.param));
                         });

}  // namespace
}  // namespace gearsph
