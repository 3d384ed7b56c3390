#include "solver/gear/iso6336_life.hpp"

#include <cmath>
#include <limits>

namespace gearsph::gear::iso6336 {

namespace {

// The line with its long-life tail: to kLongLifeFactor at 1e10 or flat.
LifeLine with_tail(const LifeLine& line, bool optimum) {
  LifeLine full = line;
  full.cycles.push_back(kLongLifeCycles);
  full.factors.push_back(optimum ? 1.0 : kLongLifeFactor);
  return full;
}

// Log-log interpolation of ys over xs at x (clamped at both ends).
double log_log(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (x <= xs.front()) return ys.front();
  for (std::size_t k = 1; k < xs.size(); ++k) {
    if (x <= xs[k]) {
      const double t = std::log(x / xs[k - 1]) / std::log(xs[k] / xs[k - 1]);
      return ys[k - 1] * std::pow(ys[k] / ys[k - 1], t);
    }
  }
  return ys.back();
}

}  // namespace

// ISO 6336-2:2006, Table 2. Limited pitting permitted: St, V, GJS, GTS and
// the case-carburised and flame or induction hardened steels (Eh, IF) alike.
// GJL and the nitrided steels (NT, NV(nitr)) share the 1.3 line; only the
// nitrocarburised NV(nitrocar) has the 1.1 one.
LifeLine pitting_life_line(const GearMaterial& m, bool limited_pitting) {
  switch (m.cls) {
    case MaterialClass::St:
    case MaterialClass::V:
    case MaterialClass::GJS:
    case MaterialClass::GTS:
    case MaterialClass::Eh:
    case MaterialClass::IF:
      if (limited_pitting) return {{6e5, 1e7, 1e9}, {1.6, 1.3, 1.0}};
      return {{1e5, 5e7}, {1.6, 1.0}};
    case MaterialClass::GJL:
    case MaterialClass::NT:
      return {{1e5, 2e6}, {1.3, 1.0}};
    case MaterialClass::NV:
      if (m.nitrocarburised) return {{1e5, 2e6}, {1.1, 1.0}};
      return {{1e5, 2e6}, {1.3, 1.0}};
  }
  return {{1e5, 5e7}, {1.6, 1.0}};
}

// ISO 6336-3:2006, Table 4: NV(nitr) with NT and GJL (1.6 at 1e3), the
// nitrocarburised NV(nitrocar) alone at 1.1.
LifeLine bending_life_line(const GearMaterial& m) {
  switch (m.cls) {
    case MaterialClass::St:
    case MaterialClass::V:
    case MaterialClass::GJS:
    case MaterialClass::GTS:
      return {{1e4, 3e6}, {2.5, 1.0}};
    case MaterialClass::Eh:
    case MaterialClass::IF:
      return {{1e3, 3e6}, {2.5, 1.0}};
    case MaterialClass::GJL:
    case MaterialClass::NT:
      return {{1e3, 3e6}, {1.6, 1.0}};
    case MaterialClass::NV:
      if (m.nitrocarburised) return {{1e3, 3e6}, {1.1, 1.0}};
      return {{1e3, 3e6}, {1.6, 1.0}};
  }
  return {{1e4, 3e6}, {2.5, 1.0}};
}

double life_factor(const LifeLine& line, double cycles, bool optimum) {
  const LifeLine full = with_tail(line, optimum);
  return log_log(full.cycles, full.factors, cycles);
}

double static_factor(const LifeLine& line) {
  return line.factors.front();
}

double reference_cycles(const LifeLine& line) {
  return line.cycles.back();
}

double permissible_stress(const LifeLine& line, double sigma_static, double sigma_ref,
                          double cycles, bool optimum) {
  const double n_static = line.cycles.front(), n_ref = reference_cycles(line);
  const double z = life_factor(line, cycles, optimum);
  if (cycles >= n_ref) return sigma_ref * z;
  if (cycles <= n_static) return sigma_static;
  // The influence factors' share fades from 1 at the reference to the
  // static ratio at the static limit, log-log in the cycles.
  const double ratio = sigma_static / (sigma_ref * static_factor(line));
  const double t = std::log(n_ref / cycles) / std::log(n_ref / n_static);
  return sigma_ref * z * std::pow(ratio, t);
}

double cycles_to_stress(const LifeLine& line, double sigma_static, double sigma_ref,
                        double sigma_needed, bool optimum) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (sigma_needed > sigma_static) return 0.0;
  if (sigma_needed <= permissible_stress(line, sigma_static, sigma_ref, kLongLifeCycles, optimum)) {
    return kInf;
  }
  // permissible_stress falls monotonically in log N: bisect there.
  double lo = std::log(line.cycles.front()), hi = std::log(kLongLifeCycles);
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    const double s = permissible_stress(line, sigma_static, sigma_ref, std::exp(mid), optimum);
    (s > sigma_needed ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

}  // namespace gearsph::gear::iso6336
