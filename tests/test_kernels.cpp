// validation.md section 1: every kernel integrates to one, and on a lattice
// the SPH sums reproduce a constant and the gradient of a linear field.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "solver/kernels/kernel.hpp"

namespace gearsph {
namespace {

const KernelType kAll[] = {KernelType::SeedQuartic, KernelType::CubicSpline,
                           KernelType::QuinticSpline, KernelType::WendlandC2};

class KernelShape : public ::testing::TestWithParam<KernelType> {};

// Composite Simpson on [0, support] of f(q) q^(dim-1), split at the knots
// q = 1, 2 where the piecewise polynomials change.
template <class Shape>
double radial_integral(int dim) {
  auto g = [dim](double q) { return Shape::shape(q) * std::pow(q, dim - 1); };
  double total = 0.0;
  for (int piece = 0; piece < static_cast<int>(Shape::support); ++piece) {
    const int n = 2000;
    const double a = piece, b = piece + 1, step = (b - a) / n;
    double s = g(a) + g(b);
    for (int k = 1; k < n; ++k) s += g(a + k * step) * (k % 2 ? 4.0 : 2.0);
    total += s * step / 3.0;
  }
  return total;
}

TEST_P(KernelShape, IntegratesToOneIn1D2D3D) {
  with_kernel(GetParam(), 1.0, [](const auto& k) {
    using S = typename std::remove_cvref_t<decltype(k)>::shape_type;
    EXPECT_NEAR(2.0 * S::norm_1d * radial_integral<S>(1), 1.0, 1e-6) << S::name;
    EXPECT_NEAR(2.0 * std::numbers::pi * S::norm_2d * radial_integral<S>(2), 1.0, 1e-6) << S::name;
    EXPECT_NEAR(4.0 * std::numbers::pi * S::norm_3d * radial_integral<S>(3), 1.0, 1e-6) << S::name;
  });
}

TEST_P(KernelShape, DerivativeMatchesFiniteDifference) {
  with_kernel(GetParam(), 0.7, [](const auto& k) {
    for (double r = 0.013; r < k.radius; r += 0.0371) {
      const double e = 1e-6;
      const double fd = (k.W(r + e) - k.W(r - e)) / (2 * e);
      EXPECT_NEAR(k.dW(r), fd, 1e-6 * (1.0 + std::abs(fd))) << "r = " << r;
    }
    EXPECT_NEAR(k.W(k.radius), 0.0, 1e-30);
    EXPECT_EQ(k.dW(k.radius * 1.01), 0.0);
  });
}

// Lattice sums at an interior point of a unit-spacing lattice.
struct LatticeSums {
  double shepard = 0.0;                       // sum_j W_ij V_j
  double mxx = 0, mxy = 0, myx = 0, myy = 0;  // sum_j (x_j - x_i) (x) grad_i W_ij V_j
};

LatticeSums lattice_sums(KernelType type, double h_over_dx, double shift_x = 0.0) {
  return with_kernel(type, h_over_dx, [&](const auto& k) {
    LatticeSums s;
    const int reach = static_cast<int>(std::ceil(k.radius)) + 1;
    for (int a = -reach; a <= reach; ++a) {
      for (int b = -reach; b <= reach; ++b) {
        const double dx = a + shift_x, dy = b;  // x_j - x_i
        const double r = std::hypot(dx, dy);
        s.shepard += k.W(r);
        if (r == 0.0) continue;
        const double gx = -k.dW(r) * dx / r, gy = -k.dW(r) * dy / r;  // grad_i W_ij
        s.mxx += dx * gx;
        s.mxy += dx * gy;
        s.myx += dy * gx;
        s.myy += dy * gy;
      }
    }
    return s;
  });
}

// On the lattice the sums are only as good as the kernel: measured at each
// kernel's default h/dx (1.0 for support-3h, 1.5 for support-2h kernels).
struct LatticeQuality {
  KernelType kernel;
  double shepard, moment;  // expected sum_j W V_j and M_xx
  double tolerance;
};

TEST(Kernels, LatticeSumsAtDefaultSmoothingLength) {
  // The seed paper's quartic has a cusp (f'(0) = -64) that inflates W(0): at its
  // own h = dx the Shepard sum is 10.6 % high and the gradient moment 5.9 %
  // low, against 0.01 % for the quintic spline of the same support. Kept as
  // measured (method.md: do not "fix" it); the gradient correction removes
  // the moment error in the solver, see docs/method.md.
  const LatticeQuality expected[] = {{KernelType::SeedQuartic, 1.1057, 0.9414, 2e-4},
                                     {KernelType::CubicSpline, 1.0034, 1.0067, 2e-4},
                                     {KernelType::QuinticSpline, 1.0001, 1.0008, 2e-4},
                                     {KernelType::WendlandC2, 1.0051, 0.9974, 2e-4}};
  for (const LatticeQuality& q : expected) {
    const double kappa = kernel_support(q.kernel) >= 3.0 ? 1.0 : 1.5;
    const LatticeSums s = lattice_sums(q.kernel, kappa);
    EXPECT_NEAR(s.shepard, q.shepard, q.tolerance) << kernel_name(q.kernel);
    EXPECT_NEAR(s.mxx, q.moment, q.tolerance) << kernel_name(q.kernel);
    EXPECT_NEAR(s.myy, s.mxx, 1e-12) << kernel_name(q.kernel);
    EXPECT_NEAR(s.mxy, 0.0, 1e-12);
    EXPECT_NEAR(s.myx, 0.0, 1e-12);
  }
}

TEST_P(KernelShape, LatticeSumsConvergeWithSmoothingLength) {
  // validation.md 1: sum_j W_ij V_j -> 1 and the moment -> I as h/dx grows;
  // within 1.5 % for every kernel at h/dx = 2.
  const LatticeSums s = lattice_sums(GetParam(), 2.0);
  EXPECT_NEAR(s.shepard, 1.0, 0.015);
  EXPECT_NEAR(s.mxx, 1.0, 0.015);
  EXPECT_NEAR(s.myy, 1.0, 0.015);
}

TEST(SeedQuartic, HasTheDocumentedCusp) {
  // f'(0) = -64 (method.md): a cusp at the origin, kept on purpose.
  EXPECT_DOUBLE_EQ(kernels::SeedQuartic::shape_derivative(0.0), -64.0);
  EXPECT_DOUBLE_EQ(kernels::SeedQuartic::shape(0.0), 81.0 - 8.0 - 7.0);
}

TEST(KernelNames, RoundTrip) {
  for (KernelType t : kAll) EXPECT_EQ(kernel_from_name(kernel_name(t)), t);
  EXPECT_FALSE(kernel_from_name("gaussian").has_value());
}

INSTANTIATE_TEST_SUITE_P(Kernels, KernelShape, ::testing::ValuesIn(kAll),
                         [](const ::testing::TestParamInfo<KernelType>& p) {
                           return std::string(kernel_name(p.param));
                         });

}  // namespace
}  // namespace gearsph
