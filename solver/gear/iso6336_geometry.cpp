#include "solver/gear/iso6336_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "solver/gear/iso6336_error.hpp"

namespace gearsph::gear::iso6336 {

namespace {

constexpr double kPi = std::numbers::pi;

std::string summarise(const std::vector<RatingIssue>& issues) {
  std::ostringstream s;
  s << "invalid rating:";
  for (const RatingIssue& i : issues)
    s << "\n  " << (i.pointer.empty() ? "/" : i.pointer) << ": " << i.message;
  return s.str();
}

std::string gear_pointer(int k, const char* field) {
  return "/gears/" + std::to_string(k) + "/" + field;
}

// Working transverse pressure angle and centre distance: from the given
// centre distance (ISO 21771, eq. (37)), or from the sum of the profile
// shifts (eq. (39): inv a_wt = inv a_t + 2 tan a_n (x1 + x2)/(z1 + z2)).
void working_pressure_angle(PairGeometry& g) {
  const PairSpec& s = g.spec;
  const double a = 0.5 * (g.d[0] + g.d[1]);
  if (s.a_w > 0.0 && !s.rack) {
    const double c = a * std::cos(g.alpha_t) / s.a_w;
    if (!(c > 0.0 && c < 1.0)) {
      throw InvalidRating("/pair/center_distance_mm",
                          "is too far from the reference centre distance " +
                              std::to_string(a * 1e3) + " mm for an involute mesh");
    }
    g.alpha_wt = std::acos(c);
    g.a_w = s.a_w;
    return;
  }
  const double inv_wt =
      involute(g.alpha_t) + 2.0 * std::tan(s.alpha_n) * (s.x[0] + s.x[1]) / double(s.z[0] + s.z[1]);
  g.alpha_wt = inverse_involute(inv_wt);
  g.a_w = a * std::cos(g.alpha_t) / std::cos(g.alpha_wt);
}

// Distance along the line of action from gear k's base tangent point to
// where its involute starts: the form circle given, or the point generated
// by the end of the tool's straight flank (h_fP - rho_fP (1 - sin a_n) below
// the datum line, shifted by x m_n), not below the base circle.
double form_distance(const PairGeometry& g, int k) {
  const PairSpec& s = g.spec;
  if (s.d_Nf[k] > 0.0) {
    return 0.5 * std::sqrt(std::max(0.0, s.d_Nf[k] * s.d_Nf[k] - g.d_b[k] * g.d_b[k]));
  }
  const double h_Ff = (s.tool.h_fP - s.tool.rho_fP * (1.0 - std::sin(s.alpha_n)) - s.x[k]) * s.m_n;
  return std::max(0.0, 0.5 * g.d[k] * std::sin(g.alpha_t) - h_Ff / std::sin(g.alpha_t));
}

// Transverse contact ratio (ISO 21771, eq. (83)): the path of contact
// between the two tip circles over the transverse base pitch, each end cut
// back to the other gear's form circle where that lies further out.
void path_of_contact(PairGeometry& g) {
  const double T1T2 = g.a_w * std::sin(g.alpha_wt);
  double g_a[2], g_f[2];
  for (int k = 0; k < 2; ++k) {
    g_a[k] = 0.5 * std::sqrt(g.d_a[k] * g.d_a[k] - g.d_b[k] * g.d_b[k]);
    g_f[k] = form_distance(g, k);
    g.d_Nf[k] = 2.0 * std::hypot(0.5 * g.d_b[k], g_f[k]);
  }
  g.path_start = std::max(T1T2 - g_a[1], g_f[0]);
  g.path_end = std::min(g_a[0], T1T2 - g_f[1]);
  g.eps_alpha = (g.path_end - g.path_start) / g.p_bt;
}

}  // namespace

InvalidRating::InvalidRating(std::vector<RatingIssue> list)
    : std::runtime_error(summarise(list)), issues(std::move(list)) {}

double involute(double a) {
  return std::tan(a) - a;
}

double inverse_involute(double inv) {
  // Start from Cheng's cube-root estimate, then Newton on tan(a) - a = inv.
  double a = std::cbrt(3.0 * inv);
  for (int it = 0; it < 50; ++it) {
    const double t = std::tan(a);
    const double step = (t - a - inv) / (t * t);
    a -= step;
    if (std::abs(step) < 1e-15) break;
  }
  return a;
}

PairGeometry pair_geometry(const PairSpec& s) {
  PairGeometry g;
  g.spec = s;
  // ISO 21771, eqs. (3), (5), (10), (12): transverse angles and diameters.
  g.alpha_t = std::atan(std::tan(s.alpha_n) / std::cos(s.beta));
  g.beta_b = std::asin(std::sin(s.beta) * std::cos(s.alpha_n));
  g.u = double(s.z[1]) / double(s.z[0]);
  for (int k = 0; k < 2; ++k) {
    g.d[k] = s.z[k] * s.m_n / std::cos(s.beta);
    g.d_b[k] = g.d[k] * std::cos(g.alpha_t);
    g.d_a[k] = s.d_a[k] > 0.0 ? s.d_a[k] : g.d[k] + 2.0 * s.m_n * (s.tool.h_aP + s.x[k]);
    g.d_f[k] = g.d[k] - 2.0 * s.m_n * (s.tool.h_fP - s.x[k]);
    g.h[k] = 0.5 * (g.d_a[k] - g.d_f[k]);
    // Virtual number of teeth, ISO 6336-3:2006, eq. (D.1).
    g.z_n[k] = s.z[k] / (std::pow(std::cos(g.beta_b), 2) * std::cos(s.beta));
    if (g.d_a[k] <= g.d_b[k]) {
      throw InvalidRating(gear_pointer(k, "tip_diameter_mm"),
                          "lies inside the base circle: the tooth has no involute flank");
    }
  }
  working_pressure_angle(g);
  g.p_bt = kPi * s.m_n * std::cos(g.alpha_t) / std::cos(s.beta);
  path_of_contact(g);
  if (!(g.eps_alpha > 1.0)) {
    // Too wide a centre distance is the usual cause when one is given.
    const bool by_centre = s.a_w > 0.0 && !s.rack;
    throw InvalidRating(by_centre ? "/pair/center_distance_mm" : "/gears",
                        "gives a transverse contact ratio of " + std::to_string(g.eps_alpha) +
                            ", not above 1: the teeth would lose contact between pairs");
  }
  g.eps_beta = s.b * std::sin(s.beta) / (kPi * s.m_n);  // ISO 21771, eq. (86)
  g.eps_gamma = g.eps_alpha + g.eps_beta;
  g.eps_alpha_n = g.eps_alpha / std::pow(std::cos(g.beta_b), 2);
  // Radii of curvature of the flanks at the pitch point, transverse section.
  const double rho1 = 0.5 * g.d_b[0] * std::tan(g.alpha_wt);
  const double rho2 = 0.5 * g.d_b[1] * std::tan(g.alpha_wt);
  g.rho_red = rho1 * rho2 / (rho1 + rho2);
  return g;
}

}  // namespace gearsph::gear::iso6336
