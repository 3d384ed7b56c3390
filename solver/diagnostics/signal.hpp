#pragma once
// Small signal-analysis helpers for histories: oscillation period from zero
// crossings, pulse arrival from the centroid of its energy.
#include <vector>

namespace gearsph::signal {

struct Oscillation {
  std::vector<double> crossings;   // times of sign changes (linear interpolation)
  std::vector<double> amplitudes;  // max |y| in each half cycle, the first from t = 0
  double period = 0.0;             // 2 (last - first crossing) / (count - 1); 0 if < 2 crossings
};

// y is taken about zero (subtract the equilibrium first).
Oscillation analyse_oscillation(const std::vector<double>& t, const std::vector<double>& y);

// Centroid in time of y^2: the arrival time of a pulse passing a probe.
double energy_centroid(const std::vector<double>& t, const std::vector<double>& y);

}  // namespace gearsph::signal
