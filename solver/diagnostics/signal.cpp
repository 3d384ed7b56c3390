#include "solver/diagnostics/signal.hpp"

#include <algorithm>
#include <cmath>

namespace gearsph::signal {

Oscillation analyse_oscillation(const std::vector<double>& t, const std::vector<double>& y) {
  Oscillation o;
  const std::size_t n = std::min(t.size(), y.size());
  double peak = 0.0;
  for (std::size_t k = 1; k < n; ++k) {
    peak = std::max(peak, std::abs(y[k - 1]));
    const bool change = (y[k - 1] < 0.0 && y[k] >= 0.0) || (y[k - 1] > 0.0 && y[k] <= 0.0);
    if (!change || y[k - 1] == y[k]) continue;
    const double f = y[k - 1] / (y[k - 1] - y[k]);
    o.crossings.push_back(t[k - 1] + f * (t[k] - t[k - 1]));
    o.amplitudes.push_back(peak);
    peak = 0.0;
  }
  if (o.crossings.size() >= 2) {
    o.period = 2.0 * (o.crossings.back() - o.crossings.front()) /
               static_cast<double>(o.crossings.size() - 1);
  }
  return o;
}

double energy_centroid(const std::vector<double>& t, const std::vector<double>& y) {
  double num = 0.0, den = 0.0;
  for (std::size_t k = 0; k < std::min(t.size(), y.size()); ++k) {
    num += t[k] * y[k] * y[k];
    den += y[k] * y[k];
  }
  return den > 0.0 ? num / den : 0.0;
}

}  // namespace gearsph::signal
