#include "solver/diagnostics/steady_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

namespace gearsph::diagnostics {

namespace {

struct PeriodStats {
  std::size_t begin = 0, end = 0;  // samples [begin, end)
  double mean = 0.0, peak = 0.0;
};

// The samples of each whole mesh period from t.front().
std::vector<PeriodStats> mesh_periods(const std::vector<double>& t, const std::vector<double>& f,
                                      double period) {
  std::vector<PeriodStats> out;
  const std::size_t n = std::min(t.size(), f.size());
  if (n < 2 || !(period > 0.0)) return out;
  std::size_t k = 0;
  for (long p = 0;; ++p) {
    const double t1 = t.front() + static_cast<double>(p + 1) * period;
    if (t1 > t[n - 1] + 1e-12 * period) break;
    PeriodStats s;
    s.begin = k;
    double sum = 0.0;
    s.peak = -1e300;
    while (k < n && t[k] < t1) {
      sum += f[k];
      s.peak = std::max(s.peak, f[k]);
      ++k;
    }
    s.end = k;
    if (s.end == s.begin) break;  // sampled more coarsely than a mesh period
    s.mean = sum / static_cast<double>(s.end - s.begin);
    out.push_back(s);
  }
  return out;
}

// The first period from which every later one stays within the tolerance of
// the reference (the last periods' mean and peak); periods.size() if none.
std::size_t first_steady_period(const std::vector<PeriodStats>& periods,
                                const SteadyMeshOptions& opt) {
  const std::size_t n = periods.size();
  const std::size_t m = static_cast<std::size_t>(opt.reference_periods);
  if (n < m) return n;
  double mean_ref = 0.0, peak_ref = 0.0;
  for (std::size_t k = n - m; k < n; ++k) {
    mean_ref += periods[k].mean / static_cast<double>(m);
    peak_ref += periods[k].peak / static_cast<double>(m);
  }
  if (!(mean_ref > 0.0)) return n;
  std::size_t first = n;
  for (std::size_t k = n; k-- > 0;) {
    const bool ok = std::abs(periods[k].mean - mean_ref) <= opt.tolerance * mean_ref &&
                    std::abs(periods[k].peak - peak_ref) <= opt.tolerance * peak_ref;
    if (!ok) break;
    first = k;
  }
  return first;
}

}  // namespace

SteadyMesh steady_mesh(const MeshHistories& h, const SteadyMeshOptions& opt) {
  SteadyMesh out;
  out.mesh_frequency_Hz = h.mesh_frequency_Hz;
  const std::size_t n = std::min(h.t.size(), h.total_force_N.size());
  if (n < 2 || !(h.mesh_frequency_Hz > 0.0)) {
    out.note = "no mesh frequency (the pinion does not turn) or no history";
    return out;
  }
  const double period = 1.0 / h.mesh_frequency_Hz;
  const std::vector<PeriodStats> periods = mesh_periods(h.t, h.total_force_N, period);
  out.periods_in_run = static_cast<int>(periods.size());
  const std::size_t first = first_steady_period(periods, opt);
  const std::size_t steady_n = periods.size() - first;
  std::size_t begin = 0, end = n;
  char text[320];
  if (first < periods.size() && steady_n >= static_cast<std::size_t>(std::max(
                                                opt.min_steady_periods, opt.reference_periods))) {
    out.steady = true;
    out.steady_periods = static_cast<int>(steady_n);
    begin = periods[first].begin;
    end = periods.back().end;
  } else {
    std::snprintf(text, sizeof text,
                  "no steady mesh reached: the run covers %zu whole mesh periods of %.4g s and "
                  "the mesh force's per-period mean and peak do not settle within %.0f %% over "
                  "%d of them; the numbers are over the run's second half",
                  periods.size(), period, 100.0 * opt.tolerance,
                  std::max(opt.min_steady_periods, opt.reference_periods));
    out.note = text;
    const double half = 0.5 * (h.t.front() + h.t[n - 1]);
    while (begin < n && h.t[begin] < half) ++begin;
  }
  if (begin >= end) return out;
  out.steady_from_s = h.t[begin];
  out.window_s = h.t[end - 1] - h.t[begin];
  const double count = static_cast<double>(end - begin);
  double f_sum = 0.0, f_peak = -1e300, x_sum = 0.0, x2_sum = 0.0, x_lo = 1e300, x_hi = -1e300;
  for (std::size_t k = begin; k < end; ++k) {
    f_sum += h.total_force_N[k];
    f_peak = std::max(f_peak, h.total_force_N[k]);
    if (k < h.dte_m.size()) {
      x_sum += h.dte_m[k];
      x2_sum += h.dte_m[k] * h.dte_m[k];
      x_lo = std::min(x_lo, h.dte_m[k]);
      x_hi = std::max(x_hi, h.dte_m[k]);
    }
  }
  out.mean_force_N = f_sum / count;
  out.peak_force_N = f_peak;
  out.K_v = out.mean_force_N > 0.0 ? f_peak / out.mean_force_N : 0.0;
  long apart = 0;
  for (std::size_t k = begin; k < end; ++k) {
    apart += h.total_force_N[k] <= opt.contact_threshold * out.mean_force_N ? 1 : 0;
  }
  out.contact_loss_fraction = static_cast<double>(apart) / count;
  if (h.dte_m.size() >= end) {
    out.dte_mean_m = x_sum / count;
    out.dte_pp_m = x_hi - x_lo;
    out.dte_rms_m = std::sqrt(std::max(0.0, x2_sum / count - out.dte_mean_m * out.dte_mean_m));
  }
  for (const auto& [tooth, f] : h.tooth_force_N) {
    ToothLoad tl;
    tl.tooth = tooth;
    double sum = 0.0, peak = 0.0;
    long loaded = 0;
    for (std::size_t k = begin; k < end && k < f.size(); ++k) {
      sum += f[k];
      peak = std::max(peak, f[k]);
      loaded += f[k] > 0.05 * h.total_force_N[k] && h.total_force_N[k] > 0.0 ? 1 : 0;
    }
    tl.mean_N = sum / count;
    tl.peak_N = peak;
    tl.loaded_fraction = static_cast<double>(loaded) / count;
    out.teeth.push_back(tl);
  }
  return out;
}

RingDown ring_down(const std::vector<double>& t, const std::vector<double>& v, double t_from,
                   double t_to) {
  RingDown out;
  const std::size_t n = std::min(t.size(), v.size());
  std::size_t a = 0, b = n;
  while (a < n && t[a] < t_from) ++a;
  while (b > a && t[b - 1] > t_to) --b;
  if (b - a < 8) return out;
  // The ringing's centre: the mean of its last quarter.
  const std::size_t q = a + 3 * (b - a) / 4;
  double centre = 0.0;
  for (std::size_t k = q; k < b; ++k) centre += v[k] / static_cast<double>(b - q);
  std::vector<double> times, logs;
  bool last_positive = false;
  double largest = 0.0;
  for (std::size_t k = a + 1; k + 1 < b; ++k) {
    const double d0 = v[k - 1] - centre, d = v[k] - centre, d1 = v[k + 1] - centre;
    const bool extreme = (d > d0 && d >= d1 && d > 0.0) || (d < d0 && d <= d1 && d < 0.0);
    if (!extreme) continue;
    // Extremes alternate in sign, one per half cycle: a second one of the
    // same sign is a wiggle within the half cycle, the larger one kept.
    if (!logs.empty() && (d > 0.0) == last_positive) {
      if (std::log(std::abs(d)) > logs.back()) {
        logs.back() = std::log(std::abs(d));
        times.back() = t[k];
      }
      continue;
    }
    largest = std::max(largest, std::abs(d));
    // Below 5 % of the largest swing the ringing is lost in the noise.
    if (std::abs(d) < 0.05 * largest) break;
    times.push_back(t[k]);
    logs.push_back(std::log(std::abs(d)));
    last_positive = d > 0.0;
  }
  out.extremes = static_cast<int>(logs.size());
  if (logs.size() < 3) return out;
  // Least squares of ln|d| on the half-cycle index j: slope = -delta / 2.
  const double m = static_cast<double>(logs.size());
  double sj = 0.0, sl = 0.0, sjj = 0.0, sjl = 0.0;
  for (std::size_t j = 0; j < logs.size(); ++j) {
    const double x = static_cast<double>(j);
    sj += x;
    sl += logs[j];
    sjj += x * x;
    sjl += x * logs[j];
  }
  const double slope = (m * sjl - sj * sl) / (m * sjj - sj * sj);
  const double delta = -2.0 * slope;
  out.damping_ratio = delta / std::sqrt(4.0 * std::numbers::pi * std::numbers::pi + delta * delta);
  out.frequency_Hz = 0.5 * (m - 1.0) / (times.back() - times.front());
  return out;
}

}  // namespace gearsph::diagnostics
