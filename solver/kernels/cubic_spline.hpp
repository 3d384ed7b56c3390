#pragma once
// Cubic B-spline (M4), support 2h. Monaghan & Lattanzio 1985;
// normalisation 2/3, 10/(7 pi), 1/pi in 1D/2D/3D (Monaghan 1992, eq. 2.6).
#include <numbers>

namespace gearsph::kernels {

struct CubicSpline {
  static constexpr const char* name = "cubic_spline";
  static constexpr double support = 2.0;
  static constexpr double norm_1d = 2.0 / 3.0;
  static constexpr double norm_2d = 10.0 / (7.0 * std::numbers::pi);
  static constexpr double norm_3d = 1.0 / std::numbers::pi;

  static double shape(double q) {
    if (q >= 2.0) return 0.0;
    if (q >= 1.0) {
      const double b = 2.0 - q;
      return 0.25 * b * b * b;
    }
    return 1.0 - 1.5 * q * q + 0.75 * q * q * q;
  }

  static double shape_derivative(double q) {
    if (q >= 2.0) return 0.0;
    if (q >= 1.0) {
      const double b = 2.0 - q;
      return -0.75 * b * b;
    }
    return -3.0 * q + 2.25 * q * q;
  }
};

}  // namespace gearsph::kernels
