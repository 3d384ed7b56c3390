#pragma once
// The seed paper's quartic kernel (seed paper, "novel quartic smoothing kernel"),
// support 3h. Shape f(R) with R = r/h; W = alpha_d f(R).
// alpha_d = 1/(88 h), 1/(46 pi h^2), 105/(8464 pi h^3) in 1D/2D/3D.
// f'(0) = -64: the kernel has a cusp at the origin (method.md keeps it).
#include <numbers>

namespace gearsph::kernels {

struct SeedQuartic {
  static constexpr const char* name = "seed_quartic";
  static constexpr double support = 3.0;  // in units of h
  static constexpr double norm_1d = 1.0 / 88.0;
  static constexpr double norm_2d = 1.0 / (46.0 * std::numbers::pi);
  static constexpr double norm_3d = 105.0 / (8464.0 * std::numbers::pi);

  static double shape(double q) {
    if (q >= 3.0) return 0.0;
    const double a = 3.0 - q, a2 = a * a;
    double f = a2 * a2;
    if (q < 2.0) {
      const double b = 2.0 - q, b2 = b * b;
      f -= 0.5 * b2 * b2;
      if (q < 1.0) {
        const double c = 1.0 - q, c2 = c * c;
        f -= 7.0 * c2 * c2;
      }
    }
    return f;
  }

  static double shape_derivative(double q) {
    if (q >= 3.0) return 0.0;
    const double a = 3.0 - q;
    double d = -4.0 * a * a * a;
    if (q < 2.0) {
      const double b = 2.0 - q;
      d += 2.0 * b * b * b;
      if (q < 1.0) {
        const double c = 1.0 - q;
        d += 28.0 * c * c * c;
      }
    }
    return d;
  }
};

}  // namespace gearsph::kernels
