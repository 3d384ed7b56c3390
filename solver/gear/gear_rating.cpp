#include "solver/gear/gear_rating.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "solver/gear/iso6336_bending.hpp"
#include "solver/gear/iso6336_factors.hpp"

namespace gearsph::gear {

namespace {

constexpr double kPi = std::numbers::pi;

}  // namespace

ContactPath rack_contact_path(const geometry::PinionGeometry& g) {
  const geometry::BasicRack& tool = g.spec().tool;
  const double m = tool.module_m, alpha = tool.pressure_angle_rad;
  const double x = g.spec().profile_shift;
  const double rb = g.base_radius();
  ContactPath c;
  c.base_pitch = kPi * m * std::cos(alpha);
  // The mating rack's tip line is h_aP above its datum line, which sits
  // x m below the pinion's rolling line; it meets the line of action at
  // r sin(alpha) - (h_aP - x m)/sin(alpha) from T.
  const double rack_tip =
      g.pitch_radius() * std::sin(alpha) - (tool.addendum() - x * m) / std::sin(alpha);
  const double form = std::sqrt(std::max(0.0, g.form_radius() * g.form_radius() - rb * rb));
  c.start_from_T = std::max(rack_tip, form);
  c.end_from_T = std::sqrt(g.tip_radius() * g.tip_radius() - rb * rb);
  c.contact_ratio = (c.end_from_T - c.start_from_T) / c.base_pitch;
  const double g_hpstc = std::min(c.start_from_T + c.base_pitch, c.end_from_T);
  c.hpstc_radius = std::sqrt(rb * rb + g_hpstc * g_hpstc);
  return c;
}

double path_point_radius(const geometry::PinionGeometry& g, const ContactPath& c,
                         std::string_view name) {
  const double rb = g.base_radius();
  auto at = [rb](double from_T) { return std::sqrt(rb * rb + from_T * from_T); };
  if (name == "pitch") return g.pitch_radius();
  if (name == "tip") return g.tip_radius();
  if (name == "hpstc") return c.hpstc_radius;
  if (name == "lpstc") return at(std::max(c.start_from_T, c.end_from_T - c.base_pitch));
  throw std::invalid_argument("unknown point of the path of contact: " + std::string(name));
}

double lewis_form_factor(int teeth) {
  // 20-degree full-depth involute, load at the tip (form factor on the module).
  struct Row {
    int z;
    double y;
  };
  static const Row table[] = {{12, 0.245}, {13, 0.261},  {14, 0.277},  {15, 0.290}, {16, 0.296},
                              {17, 0.303}, {18, 0.309},  {19, 0.314},  {20, 0.322}, {21, 0.328},
                              {22, 0.331}, {24, 0.337},  {26, 0.346},  {28, 0.353}, {30, 0.359},
                              {34, 0.371}, {38, 0.384},  {43, 0.397},  {50, 0.409}, {60, 0.422},
                              {75, 0.435}, {100, 0.447}, {150, 0.460}, {300, 0.472}};
  if (teeth < table[0].z) throw std::invalid_argument("Lewis table starts at 12 teeth");
  for (std::size_t k = 1; k < std::size(table); ++k) {
    if (teeth <= table[k].z) {
      const double f = double(teeth - table[k - 1].z) / double(table[k].z - table[k - 1].z);
      return table[k - 1].y + f * (table[k].y - table[k - 1].y);
    }
  }
  return table[std::size(table) - 1].y;
}

IsoToothForm iso_tooth_form(const geometry::PinionGeometry& g, double load_radius) {
  // A spur pinion is its own virtual gear (ISO 6336-3:2006, clause 6.2).
  const geometry::BasicRack& tool = g.spec().tool;
  iso6336::ToothFormInput in;
  in.m_n = tool.module_m;
  in.alpha_n = tool.pressure_angle_rad;
  in.z_n = g.teeth();
  in.x = g.spec().profile_shift;
  in.tool.h_fP = tool.dedendum() / tool.module_m;
  in.tool.rho_fP = tool.root_radius() / tool.module_m;
  in.d_en = 2.0 * load_radius;
  return iso6336::virtual_tooth_form(in);
}

ThirtyDegreePoints thirty_degree_points(const geometry::PinionGeometry& g) {
  // Walk the half tooth from the root (space centre) up the fillet; the
  // tangent turns from horizontal to nearly vertical. The 30-degree point is
  // where it makes 30 degrees with the axis (+y), i.e. 60 degrees with +x.
  const std::vector<geometry::Point>& h = g.half_tooth();
  const double target = kPi / 3.0;
  for (std::size_t k = 1; k + 1 < h.size(); ++k) {
    const geometry::Point a = h[k - 1], b = h[k], c = h[k + 1];
    auto slope = [](geometry::Point p, geometry::Point q) {
      return std::atan2(std::abs(q.y - p.y), std::abs(q.x - p.x));
    };
    const double s0 = slope(a, b), s1 = slope(b, c);
    if (s0 <= target && s1 >= target && std::hypot(b.x, b.y) < g.form_radius() + 1e-9) {
      ThirtyDegreePoints t;
      t.right = b;
      t.left = {-b.x, b.y};
      t.chord = 2.0 * std::abs(b.x);
      return t;
    }
  }
  throw std::runtime_error("no 30-degree tangent point on the fillet");
}

double iso_single_pair_stiffness(const geometry::PinionGeometry& g, double E_pinion_Pa,
                                 double E_rack_Pa) {
  const geometry::BasicRack& tool = g.spec().tool;
  // The rack's terms vanish: 1/z_n2 = 0, x_2 = 0.
  const double c_th =
      iso6336::theoretical_single_stiffness(g.teeth(), 0.0, g.spec().profile_shift, 0.0);
  constexpr double kCR = 1.0;  // solid blank
  const double c_b = iso6336::basic_rack_factor(tool.dedendum_coef, tool.pressure_angle_rad);
  const double e_pair = 2.0 * E_pinion_Pa * E_rack_Pa / (E_pinion_Pa + E_rack_Pa);
  // 1 N/(mm um) = 1e9 N/m per metre of face width.
  return c_th * kIsoMeasuredOverTheoretical * kCR * c_b * (e_pair / iso6336::kSteelModulusPa) * 1e9;
}

double iso_sigma_H0(double ft_N, double d1_m, double b_m, double alpha_rad, double e_star_Pa) {
  const double z_h2 = 2.0 / (std::cos(alpha_rad) * std::sin(alpha_rad));
  const double z_e2 = e_star_Pa / kPi;
  return std::sqrt(z_h2 * z_e2 * ft_N / (d1_m * b_m));
}

}  // namespace gearsph::gear
