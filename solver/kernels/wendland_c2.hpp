#pragma once
// Wendland C2, support 2h (Wendland 1995; Dehnen & Aly 2012, table 1).
// Shape (1 - q/2)^4 (2 q + 1), normalised by 3/4, 7/(4 pi), 21/(16 pi) in
// 1D/2D/3D. (The C2 member built for 1D is a different polynomial; only the
// 2D use matters here, the 1D/3D constants let the same shape be checked.)
#include <numbers>

namespace gearsph::kernels {

struct WendlandC2 {
  static constexpr const char* name = "wendland_c2";
  static constexpr double support = 2.0;
  static constexpr double norm_1d = 3.0 / 4.0;
  static constexpr double norm_2d = 7.0 / (4.0 * std::numbers::pi);
  static constexpr double norm_3d = 21.0 / (16.0 * std::numbers::pi);

  static double shape(double q) {
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q, a2 = a * a;
    return a2 * a2 * (2.0 * q + 1.0);
  }

  static double shape_derivative(double q) {
    if (q >= 2.0) return 0.0;
    const double a = 1.0 - 0.5 * q;
    return -5.0 * q * a * a * a;
  }
};

}  // namespace gearsph::kernels
