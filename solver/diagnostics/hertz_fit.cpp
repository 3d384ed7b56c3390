#include "solver/diagnostics/hertz_fit.hpp"

#include <cmath>

namespace gearsph::diagnostics {

HertzEllipseFit fit_hertz_ellipse(const std::vector<double>& s, const std::vector<double>& p,
                                  double a_guess, double centre) {
  HertzEllipseFit best;
  double best_err = 1e300;
  auto shape = [&](std::size_t k, double a) {
    const double x = s[k] - centre;
    return std::abs(x) < a ? std::sqrt(1.0 - x * x / (a * a)) : 0.0;
  };
  for (double a = 0.3 * a_guess; a <= 3.0 * a_guess; a += 0.001 * a_guess) {
    double sgp = 0.0, sgg = 0.0;
    for (std::size_t k = 0; k < s.size(); ++k) {
      const double g = shape(k, a);
      sgp += g * p[k];
      sgg += g * g;
    }
    if (sgg <= 0.0) continue;
    const double p0 = sgp / sgg;
    double err = 0.0;
    for (std::size_t k = 0; k < s.size(); ++k) {
      const double g = shape(k, a);
      err += (p[k] - p0 * g) * (p[k] - p0 * g);
    }
    if (err < best_err) {
      best_err = err;
      best = {p0, a, std::sqrt(err / static_cast<double>(s.size()))};
    }
  }
  return best;
}

}  // namespace gearsph::diagnostics
