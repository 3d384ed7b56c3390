#include "solver/gear/mesh_dynamics_sdof.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace gearsph::gear::dynamics {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

double wrap(double s) {
  return s - std::floor(s);
}

// The step: a whole number of steps per mesh period, so that the stiffness
// table is sampled at the same phases every period, and enough of them to
// resolve the stiffest mode (RK4 is accurate to a phase error of
// (omega dt)^4 / 120 per step: 4e-6 at 80 steps a period).
int steps_per_period(const SdofModel& m, double f_mesh, const SdofOptions& opt) {
  const double f_max = natural_frequency_Hz(m.stiffness.max(), m.mass_kg);
  const double n = std::ceil(opt.steps_per_natural_period * f_max / f_mesh);
  return std::max(opt.steps_per_mesh_period_min, static_cast<int>(n));
}

double acceleration(const SdofModel& m, double c, double s, double x, double v) {
  const double e = m.error.value.empty() ? 0.0 : m.error.at(s);
  const double g = backlash_deflection(x - e, m.backlash_m);
  const double f = g != 0.0 ? m.stiffness.at(s) * g + c * v : 0.0;
  return (m.load_N - f) / m.mass_kg;
}

// One classical Runge-Kutta step over dt of the mesh phase s0 -> s0 + ds.
void rk4_step(const SdofModel& m, double c, double s0, double ds, double dt, SdofState& y) {
  const double a1 = acceleration(m, c, s0, y.x, y.v);
  const double x2 = y.x + 0.5 * dt * y.v, v2 = y.v + 0.5 * dt * a1;
  const double a2 = acceleration(m, c, s0 + 0.5 * ds, x2, v2);
  const double x3 = y.x + 0.5 * dt * v2, v3 = y.v + 0.5 * dt * a2;
  const double a3 = acceleration(m, c, s0 + 0.5 * ds, x3, v3);
  const double x4 = y.x + dt * v3, v4 = y.v + dt * a3;
  const double a4 = acceleration(m, c, s0 + ds, x4, v4);
  y.x += dt / 6.0 * (y.v + 2.0 * v2 + 2.0 * v3 + v4);
  y.v += dt / 6.0 * (a1 + 2.0 * a2 + 2.0 * a3 + a4);
}

struct PeriodExtremes {
  double f_lo = kInf, f_hi = -kInf, x_lo = kInf, x_hi = -kInf;
  void add(double f, double x) {
    f_lo = std::min(f_lo, f);
    f_hi = std::max(f_hi, f);
    x_lo = std::min(x_lo, x);
    x_hi = std::max(x_hi, x);
  }
};

struct Accumulated {
  double f_sum = 0.0, x_sum = 0.0, x2_sum = 0.0;
  long samples = 0, apart = 0, reverse = 0;
  PeriodExtremes ext;
};

// Advances one mesh period of n steps from phase `period` (an integer),
// reporting each step's end state to `acc` when given.
void advance_period(const SdofModel& m, double c, double f_mesh, int n, long period, SdofState& y,
                    PeriodExtremes& ext, Accumulated* acc) {
  const double dt = 1.0 / (f_mesh * n), ds = 1.0 / n;
  for (int k = 0; k < n; ++k) {
    const double s0 = static_cast<double>(period) + k * ds;
    rk4_step(m, c, s0, ds, dt, y);
    const double s1 = s0 + ds;
    const double f = mesh_force(m, s1, y.x, y.v);
    ext.add(f, y.x);
    if (acc == nullptr) continue;
    acc->f_sum += f;
    acc->x_sum += y.x;
    acc->x2_sum += y.x * y.x;
    ++acc->samples;
    const double e = m.error.value.empty() ? 0.0 : m.error.at(s1);
    const double u = y.x - e;
    acc->apart += (u <= 0.0 && u >= -m.backlash_m) ? 1 : 0;
    acc->reverse += u < -m.backlash_m ? 1 : 0;
  }
}

}  // namespace

double MeshCycleTable::at(double s) const {
  const std::size_t n = position.size();
  if (n == 0) return 0.0;
  if (n == 1) return value[0];
  const double w = wrap(s);
  // The interval [position[k], position[k+1]) holding w; across the end
  // the period's last sample joins the first one plus one.
  const auto it = std::upper_bound(position.begin(), position.end(), w);
  const std::size_t hi = static_cast<std::size_t>(it - position.begin());
  const std::size_t k0 = hi == 0 ? n - 1 : hi - 1;
  const std::size_t k1 = hi == n ? 0 : hi;
  double p0 = position[k0], p1 = position[k1];
  if (hi == 0) {
    p0 -= 1.0;
  } else if (hi == n) {
    p1 += 1.0;
  }
  if (p1 - p0 <= 0.0) return value[k0];
  const double t = (w - p0) / (p1 - p0);
  return value[k0] + t * (value[k1] - value[k0]);
}

double MeshCycleTable::mean() const {
  const std::size_t n = position.size();
  if (n == 0) return 0.0;
  if (n == 1) return value[0];
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t k1 = (k + 1) % n;
    const double width = k + 1 < n ? position[k1] - position[k] : position[0] + 1.0 - position[k];
    sum += 0.5 * (value[k] + value[k1]) * width;
  }
  return sum;
}

double MeshCycleTable::max() const {
  return value.empty() ? 0.0 : *std::max_element(value.begin(), value.end());
}

double MeshCycleTable::min() const {
  return value.empty() ? 0.0 : *std::min_element(value.begin(), value.end());
}

MeshCycleTable two_level_stiffness(double k_single, double k_double, double eps, double edge) {
  if (!(eps > 1.0 && eps < 2.0)) {
    throw std::invalid_argument("two_level_stiffness: the contact ratio must lie in (1, 2)");
  }
  const double d = eps - 1.0;  // double contact over [0, d)
  // A square wave is two samples at each step, a ramp of `edge` apart (a
  // tiny one for a square wave: the table is linear between samples).
  const double ramp = std::max(edge, 1e-9);
  if (!(ramp < std::min(d, 1.0 - d))) {
    throw std::invalid_argument("two_level_stiffness: the edge must be shorter than each level");
  }
  // Each ramp centred on its step, so that the levels' shares are eps - 1
  // and 2 - eps exactly.
  const double h = 0.5 * ramp;
  MeshCycleTable t;
  t.position = {h, d - h, d + h, 1.0 - h};
  t.value = {k_double, k_double, k_single, k_single};
  return t;
}

MeshCycleTable harmonic_table(double mean, double amplitude, int samples) {
  MeshCycleTable t;
  for (int k = 0; k < samples; ++k) {
    const double s = static_cast<double>(k) / samples;
    t.position.push_back(s);
    t.value.push_back(mean * (1.0 + amplitude * std::cos(2.0 * kPi * s)));
  }
  return t;
}

double pinion_mass_on_line_of_action(double inertia_kg_m2, double base_radius_m) {
  return inertia_kg_m2 / (base_radius_m * base_radius_m);
}

double rack_mass_on_line_of_action(double mass_kg, double pressure_angle_rad) {
  const double c = std::cos(pressure_angle_rad);
  return mass_kg / (c * c);
}

double effective_mesh_mass(double m1, double m2) {
  if (std::isinf(m1)) return m2;
  if (std::isinf(m2)) return m1;
  return m1 * m2 / (m1 + m2);
}

double natural_frequency_Hz(double k, double m) {
  return std::sqrt(k / m) / (2.0 * kPi);
}

double damping_coefficient(double zeta, double k, double m) {
  return 2.0 * zeta * std::sqrt(k * m);
}

double backlash_deflection(double u, double backlash) {
  if (u > 0.0) return u;
  if (u < -backlash) return u + backlash;
  return 0.0;
}

double mesh_force(const SdofModel& m, double s, double x, double v) {
  const double e = m.error.value.empty() ? 0.0 : m.error.at(s);
  const double g = backlash_deflection(x - e, m.backlash_m);
  if (g == 0.0) return 0.0;
  const double c = damping_coefficient(m.damping_ratio, m.stiffness.mean(), m.mass_kg);
  return m.stiffness.at(s) * g + c * v;
}

SdofState static_state(const SdofModel& m) {
  const double e = m.error.value.empty() ? 0.0 : m.error.at(0.0);
  SdofState y;
  y.x = e + m.load_N / m.stiffness.at(0.0);
  return y;
}

SdofResponse respond_at(const SdofModel& m, double f_mesh, SdofState& y, const SdofOptions& opt) {
  if (!(m.mass_kg > 0.0) || !(f_mesh > 0.0) || m.stiffness.value.empty()) {
    throw std::invalid_argument("respond_at: needs a mass, a stiffness table and a frequency");
  }
  const int n = steps_per_period(m, f_mesh, opt);
  const double c = damping_coefficient(m.damping_ratio, m.stiffness.mean(), m.mass_kg);
  const double x_static = std::abs(m.load_N) / m.stiffness.mean();
  SdofResponse r;
  r.mesh_frequency_Hz = f_mesh;
  // The transient: windows of mesh periods until two in a row agree.
  long period = 0;
  PeriodExtremes prev, cur;
  bool have_prev = false;
  for (; period < opt.max_transient_periods; ++period) {
    advance_period(m, c, f_mesh, n, period, y, cur, nullptr);
    if ((period + 1) % opt.window_periods != 0) continue;
    if (have_prev) {
      // Relative to the swing being measured (a small fluctuation on a
      // large mean is settled only when its own extremes are), with a
      // floor for a mesh that does not fluctuate at all.
      const double f_scale = std::max(cur.f_hi - cur.f_lo, 1e-3 * std::abs(m.load_N));
      const double x_scale = std::max(cur.x_hi - cur.x_lo, 1e-3 * x_static);
      const double tol_f = opt.tolerance * f_scale, tol_x = opt.tolerance * x_scale;
      if (std::abs(cur.f_hi - prev.f_hi) <= tol_f && std::abs(cur.f_lo - prev.f_lo) <= tol_f &&
          std::abs(cur.x_hi - prev.x_hi) <= tol_x && std::abs(cur.x_lo - prev.x_lo) <= tol_x) {
        r.steady = true;
        ++period;
        break;
      }
    }
    prev = cur;
    cur = PeriodExtremes{};
    have_prev = true;
  }
  r.transient_periods = static_cast<int>(period);
  Accumulated acc;
  for (int k = 0; k < opt.measured_periods; ++k, ++period) {
    advance_period(m, c, f_mesh, n, period, y, acc.ext, &acc);
  }
  const double count = static_cast<double>(acc.samples);
  r.mean_force_N = acc.f_sum / count;
  r.peak_force_N = acc.ext.f_hi;
  r.min_force_N = acc.ext.f_lo;
  r.K_v = r.mean_force_N != 0.0 ? r.peak_force_N / r.mean_force_N : 0.0;
  r.dte_mean_m = acc.x_sum / count;
  r.dte_pp_m = acc.ext.x_hi - acc.ext.x_lo;
  r.dte_rms_m = std::sqrt(std::max(0.0, acc.x2_sum / count - r.dte_mean_m * r.dte_mean_m));
  r.contact_loss_fraction = static_cast<double>(acc.apart) / count;
  r.reverse_contact_fraction = static_cast<double>(acc.reverse) / count;
  return r;
}

std::vector<double> free_response(const SdofModel& m, SdofState y, double dt, int steps) {
  const double c = damping_coefficient(m.damping_ratio, m.stiffness.mean(), m.mass_kg);
  std::vector<double> out;
  out.reserve(static_cast<std::size_t>(std::max(steps, 0)));
  for (int k = 0; k < steps; ++k) {
    rk4_step(m, c, 0.0, 0.0, dt, y);
    out.push_back(y.x);
  }
  return out;
}

std::vector<double> period_amplitudes(const SdofModel& m, double f_mesh, SdofState& y, int periods,
                                      const SdofOptions& opt) {
  const int n = steps_per_period(m, f_mesh, opt);
  const double c = damping_coefficient(m.damping_ratio, m.stiffness.mean(), m.mass_kg);
  std::vector<double> out;
  for (long p = 0; p < periods; ++p) {
    PeriodExtremes ext;
    advance_period(m, c, f_mesh, n, p, y, ext, nullptr);
    out.push_back(0.5 * (ext.x_hi - ext.x_lo));
  }
  return out;
}

std::vector<SdofResponse> sweep(const SdofModel& m, const std::vector<double>& f,
                                const SdofOptions& opt) {
  SdofState y = static_state(m);
  std::vector<SdofResponse> out;
  for (double fk : f) out.push_back(respond_at(m, fk, y, opt));
  return out;
}

double peak_abscissa(const std::vector<double>& x, const std::vector<double>& y) {
  if (x.empty() || x.size() != y.size()) return 0.0;
  const std::size_t k = static_cast<std::size_t>(std::max_element(y.begin(), y.end()) - y.begin());
  if (k == 0 || k + 1 == x.size()) return x[k];
  // The vertex of the parabola through the three points.
  const double x0 = x[k - 1], x1 = x[k], x2 = x[k + 1];
  const double y0 = y[k - 1], y1 = y[k], y2 = y[k + 1];
  const double d0 = (y1 - y0) / (x1 - x0), d1 = (y2 - y1) / (x2 - x1);
  const double curvature = (d1 - d0) / (x2 - x0);
  if (curvature >= 0.0) return x1;
  return 0.5 * (x0 + x1) - d0 / (2.0 * curvature);
}

}  // namespace gearsph::gear::dynamics
