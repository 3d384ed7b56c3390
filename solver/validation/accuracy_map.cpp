// The accuracy map's cases: Halton draws over the pinions users work in,
// kept where the pinion can be cut and its tooth is not pointed.
#include "solver/validation/accuracy_map.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/geometry/gear_profile.hpp"

namespace gearsph::validation {

double radical_inverse(int i, int base) {
  double inv = 1.0 / base, f = inv, r = 0.0;
  for (int n = i; n > 0; n /= base, f *= inv) r += f * (n % base);
  return r;
}

namespace {

double round_to(double v, double step) {
  return std::round(v / step) * step;
}

const char* const kContactPoints[] = {"pitch", "hpstc", "tip"};

AccuracyCase draw_case(int i, const AccuracySpace& s) {
  // Draw 0 of every sequence is 0: start at 1 so no case sits on a corner of the space.
  const int k = i + 1;
  AccuracyCase c;
  c.draw = i;
  c.teeth = static_cast<int>(
      std::lround(s.teeth_min + radical_inverse(k, 2) * (s.teeth_max - s.teeth_min)));
  c.module_mm =
      round_to(s.module_min_mm + radical_inverse(k, 3) * (s.module_max_mm - s.module_min_mm), 0.25);
  c.pressure_angle_deg =
      round_to(s.pressure_angle_min_deg +
                   radical_inverse(k, 5) * (s.pressure_angle_max_deg - s.pressure_angle_min_deg),
               0.5);
  c.profile_shift =
      round_to(s.shift_min + radical_inverse(k, 7) * (s.shift_max - s.shift_min), 0.05);
  c.rim_modules = round_to(
      s.rim_min_modules + radical_inverse(k, 11) * (s.rim_max_modules - s.rim_min_modules), 0.1);
  c.line_load_N_per_mm =
      round_to(s.line_load_min_N_per_mm +
                   radical_inverse(k, 13) * (s.line_load_max_N_per_mm - s.line_load_min_N_per_mm),
               10.0);
  c.contact_point = kContactPoints[i % 3];
  const double face_width_mm = 20.0;
  c.job = {{"name", "accuracy-map-" + std::to_string(i)},
           {"scene",
            {{"type", "rack_pinion"},
             {"quasi_static", true},
             {"contact_point", c.contact_point},
             {"pinion",
              {{"module_mm", c.module_mm},
               {"teeth", c.teeth},
               {"pressure_angle_deg", c.pressure_angle_deg},
               {"profile_shift", c.profile_shift},
               {"backlash_mm", 0.0},
               {"rim_depth_mm", c.rim_modules * c.module_mm},
               {"face_width_mm", face_width_mm},
               {"omega_rad_s", 0.0}}},
             {"rack", {{"velocity_m_s", 0.0}, {"load_N", c.line_load_N_per_mm * face_width_mm}}}}},
           {"output", {{"frames", 0}}}};
  return c;
}

// Why the draw's pinion is left out, or "" when it is admitted.
std::string inadmissible(const AccuracyCase& c) {
  geometry::PinionSpec spec;
  spec.teeth = c.teeth;
  spec.tool.module_m = 1e-3 * c.module_mm;
  spec.tool.pressure_angle_rad = c.pressure_angle_deg * std::numbers::pi / 180.0;
  spec.profile_shift = c.profile_shift;
  try {
    const geometry::PinionGeometry g(spec);
    // s_a = 2 r_a psi_a, psi_a the involute's half angle at the tip (ISO 21771).
    const double tip_thickness = 2.0 * g.tip_radius() * g.involute_half_angle(g.tip_radius());
    if (tip_thickness < kMinTipThickness * spec.tool.module_m) {
      return "tip thickness " + std::to_string(tip_thickness / spec.tool.module_m) +
             " modules, below " + std::to_string(kMinTipThickness);
    }
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

std::vector<AccuracyCase> accuracy_cases(int count, std::vector<SkippedDraw>* skipped,
                                         const AccuracySpace& space) {
  std::vector<AccuracyCase> out;
  // Pointed teeth (high shift on few teeth) are a minority of the space:
  // a bound on the draws only guards against a space with none admissible.
  for (int i = 0; static_cast<int>(out.size()) < count && i < 100 * count + 100; ++i) {
    AccuracyCase c = draw_case(i, space);
    const std::string why = inadmissible(c);
    if (why.empty()) {
      out.push_back(std::move(c));
    } else if (skipped) {
      skipped->push_back({i, why});
    }
  }
  return out;
}

}  // namespace gearsph::validation
