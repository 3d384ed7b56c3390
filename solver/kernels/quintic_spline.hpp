#pragma once
// Quintic B-spline (M6), support 3h. Morris, Fox & Zhu 1997;
// normalisation 1/120, 7/(478 pi), 1/(120 pi) in 1D/2D/3D.
#include <numbers>

namespace gearsph::kernels {

struct QuinticSpline {
  static constexpr const char* name = "quintic_spline";
  static constexpr double support = 3.0;
  static constexpr double norm_1d = 1.0 / 120.0;
  static constexpr double norm_2d = 7.0 / (478.0 * std::numbers::pi);
  static constexpr double norm_3d = 1.0 / (120.0 * std::numbers::pi);

  static double shape(double q) {
    if (q >= 3.0) return 0.0;
    const double a = 3.0 - q, a2 = a * a;
    double f = a2 * a2 * a;
    if (q < 2.0) {
      const double b = 2.0 - q, b2 = b * b;
      f -= 6.0 * b2 * b2 * b;
      if (q < 1.0) {
        const double c = 1.0 - q, c2 = c * c;
        f += 15.0 * c2 * c2 * c;
      }
    }
    return f;
  }

  static double shape_derivative(double q) {
    if (q >= 3.0) return 0.0;
    const double a = 3.0 - q, a2 = a * a;
    double d = -5.0 * a2 * a2;
    if (q < 2.0) {
      const double b = 2.0 - q, b2 = b * b;
      d += 30.0 * b2 * b2;
      if (q < 1.0) {
        const double c = 1.0 - q, c2 = c * c;
        d -= 75.0 * c2 * c2;
      }
    }
    return d;
  }
};

}  // namespace gearsph::kernels
