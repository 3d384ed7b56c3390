#pragma once
// The accuracy map's cases (docs/validation.md, "The accuracy map"): static
// checks of pinions drawn from the space users work in, each to be compared
// with its FE check. Drawn by a Halton sequence, so the map is the same on
// every machine and a larger map contains a smaller one.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gearsph::validation {

// The space (issue 52): teeth 8-60, module 1-10 mm, pressure angle
// 14.5-25 degrees, profile shift -0.5 to +0.8 where the pinion cuts without
// a pointed tooth (tip thickness at least kMinTipThickness modules), rim
// 0.5-3 modules below the root circle, line load 50-500 N/mm, contact at
// the pitch point, the HPSTC and the tip in turn.
struct AccuracySpace {
  int teeth_min = 8, teeth_max = 60;
  double module_min_mm = 1.0, module_max_mm = 10.0;
  double pressure_angle_min_deg = 14.5, pressure_angle_max_deg = 25.0;
  double shift_min = -0.5, shift_max = 0.8;
  double rim_min_modules = 0.5, rim_max_modules = 3.0;
  double line_load_min_N_per_mm = 50.0, line_load_max_N_per_mm = 500.0;
};

// The smallest tip thickness the map admits, in modules: below it a
// tooth counts as pointed (ISO 21771 designs keep s_a >= 0.2-0.4 m).
constexpr double kMinTipThickness = 0.25;

struct AccuracyCase {
  int draw = 0;  // index in the Halton sequence
  int teeth = 0;
  double module_mm = 0.0, pressure_angle_deg = 0.0, profile_shift = 0.0;
  double rim_modules = 0.0, line_load_N_per_mm = 0.0;
  std::string contact_point;
  nlohmann::json job;  // a quasi-static rack_pinion job, backlash 0 (the FE's geometry)
};

// A draw the map leaves out, and why (a pointed tooth, a profile the cutter
// cannot generate).
struct SkippedDraw {
  int draw = 0;
  std::string reason;
};

// The first `count` admissible cases, and the draws skipped on the way.
std::vector<AccuracyCase> accuracy_cases(int count, std::vector<SkippedDraw>* skipped = nullptr,
                                         const AccuracySpace& space = {});

// The i-th point of the radical-inverse sequence in `base` (Halton 1960), in [0, 1).
double radical_inverse(int i, int base);

}  // namespace gearsph::validation
