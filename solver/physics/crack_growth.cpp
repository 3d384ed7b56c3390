#include "solver/physics/crack_growth.hpp"

#include <cmath>
#include <limits>

namespace gearsph::physics {

double max_tangential_stress_kink(double K_I, double K_II) {
  if (K_II == 0.0) return 0.0;
  // Erdogan & Sih 1963: tan(theta/2) = (K_I - sqrt(K_I^2 + 8 K_II^2)) / (4 K_II), the
  // root of K_I sin(theta) + K_II (3 cos(theta) - 1) = 0 where the hoop stress peaks
  // (the other root, with +sqrt, is its minimum).
  return 2.0 * std::atan((K_I - std::sqrt(K_I * K_I + 8.0 * K_II * K_II)) / (4.0 * K_II));
}

double near_tip_hoop_stress(double K_I, double K_II, double theta) {
  const double c = std::cos(0.5 * theta);
  return c * (K_I * c * c - 1.5 * K_II * std::sin(theta));
}

geometry::Point grown_tip(geometry::Point tip, geometry::Point direction, double kink,
                          double increment) {
  const double c = std::cos(kink), s = std::sin(kink);
  const geometry::Point turned{c * direction.x - s * direction.y,
                               s * direction.x + c * direction.y};
  return tip + increment * turned;
}

}  // namespace gearsph::physics

namespace gearsph::physics {

double equivalent_K(double K_I, double K_II) {
  return near_tip_hoop_stress(K_I, K_II, max_tangential_stress_kink(K_I, K_II));
}

double paris_cycles(const std::vector<double>& da_m, const std::vector<double>& K_eq_Pa_sqrt_m,
                    double C, double m) {
  double cycles = 0.0;
  for (std::size_t k = 0; k < da_m.size() && k + 1 < K_eq_Pa_sqrt_m.size(); ++k) {
    const double a = 1e-6 * K_eq_Pa_sqrt_m[k], b = 1e-6 * K_eq_Pa_sqrt_m[k + 1];
    if (a <= 0.0 || b <= 0.0) return std::numeric_limits<double>::infinity();
    cycles += da_m[k] * 0.5 * (1.0 / (C * std::pow(a, m)) + 1.0 / (C * std::pow(b, m)));
  }
  return cycles;
}

}  // namespace gearsph::physics
