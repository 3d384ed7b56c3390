#pragma once
// The static check on the seed paper's pinion and rack at the default
// particles: 1 kN on the rack, tooth 0 loaded alone at `point` (a named
// point such as "pitch" or "tip", or a radius in mm).
#include <nlohmann/json.hpp>

namespace gearsph::testing_support {

inline nlohmann::json paper_static_check(const nlohmann::json& point) {
  return {{"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"contact_point", point},
            {"pinion", {{"omega_rad_s", 0.0}}},
            {"rack", {{"load_N", 1000.0}, {"velocity_m_s", 0.0}}}}}};
}

}  // namespace gearsph::testing_support
