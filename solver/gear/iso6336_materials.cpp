#include "solver/gear/iso6336_materials.hpp"

#include <cstdio>
#include <optional>

#include "solver/gear/iso6336_error.hpp"

namespace gearsph::gear::iso6336 {

namespace {

constexpr double kMPa = 1e6;

struct NamedClass {
  const char* name;
  MaterialClass cls;
};
constexpr NamedClass kClasses[] = {
    {"St", MaterialClass::St},   {"V", MaterialClass::V},     {"GJS", MaterialClass::GJS},
    {"GTS", MaterialClass::GTS}, {"GJL", MaterialClass::GJL}, {"Eh", MaterialClass::Eh},
    {"IF", MaterialClass::IF},   {"NT", MaterialClass::NT},   {"NV", MaterialClass::NV}};

// One ISO 6336-5:2016 line: limit = A x + B [MPa], x the hardness (HB or
// HV) between x_min and x_max; A = 0 for the surface-hardened classes,
// whose limits do not rise with hardness within their range.
struct LimitLine {
  double A, B, x_min, x_max;
};
struct ClassLines {
  LimitLine H, F;
  bool vickers;  // hardness in HV (else HB)
};

// The lines this build carries. Nodular cast iron (ISO 6336-5:2016,
// Figures 5 and 6 and Table 7, perlitic and bainitic, 175-300 HB):
// ML and MQ share a line, ME has its own. Case-carburised wrought steel
// (Figures 9 and 10, surface 600-800 HV, MQ with core hardness >= 25 HRC).
std::optional<ClassLines> lines_for(MaterialClass c, const std::string& quality) {
  const bool me = quality == "ME";
  if (c == MaterialClass::GJS) {
    return me ? ClassLines{{1.500, 250, 175, 300}, {0.380, 134, 175, 300}, false}
              : ClassLines{{1.434, 211, 175, 300}, {0.350, 119, 175, 300}, false};
  }
  if (c == MaterialClass::Eh) {
    const double h = quality == "ML" ? 1300 : me ? 1650 : 1500;
    const double f = quality == "ML" ? 312 : me ? 525 : 425;
    return ClassLines{{0.0, h, 600, 800}, {0.0, f, 600, 800}, true};
  }
  return std::nullopt;
}

MaterialClass class_from(const std::string& name, const std::string& pointer) {
  for (const NamedClass& c : kClasses) {
    if (name == c.name) return c.cls;
  }
  throw InvalidRating(pointer, "is not an ISO 6336-5 class this build knows");
}

// sigma_Hlim and sigma_Flim from the class's line at the material's hardness.
void limits_from_line(GearMaterial& g, const nlohmann::json& iso, const std::string& pointer) {
  const std::optional<ClassLines> lines = lines_for(g.cls, g.quality);
  if (!lines) {
    throw InvalidRating(pointer + "/iso6336_5/class",
                        std::string("has no ISO 6336-5 line built in for class ") +
                            class_name(g.cls) + ": give sigma_Hlim_Pa and sigma_Flim_Pa");
  }
  const char* key = lines->vickers ? "hardness_HV" : "hardness_HB";
  double x = lines->vickers ? g.hardness_HV : g.hardness_HB;
  if (x <= 0.0 && lines->H.A == 0.0) x = lines->H.x_min;  // the limit does not depend on it
  if (x <= 0.0) {
    throw InvalidRating(
        pointer + "/iso6336_5",
        std::string("needs ") + key + " to read the ISO 6336-5 line of class " + class_name(g.cls));
  }
  if (x < lines->H.x_min || x > lines->H.x_max) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "is outside the ISO 6336-5 line of class %s (%g to %g %s)",
                  class_name(g.cls), lines->H.x_min, lines->H.x_max, lines->vickers ? "HV" : "HB");
    throw InvalidRating(pointer + "/iso6336_5/" + (iso.contains(key) ? key : "class"), buf);
  }
  if (g.sigma_Hlim_Pa <= 0.0) g.sigma_Hlim_Pa = (lines->H.A * x + lines->H.B) * kMPa;
  if (g.sigma_Flim_Pa <= 0.0) g.sigma_Flim_Pa = (lines->F.A * x + lines->F.B) * kMPa;
  g.limits_from = std::string("ISO 6336-5:2016 line of ") + class_name(g.cls) + " " + g.quality;
}

}  // namespace

bool surface_hardened(MaterialClass c) {
  return c == MaterialClass::Eh || c == MaterialClass::IF || c == MaterialClass::NT ||
         c == MaterialClass::NV;
}

const char* class_name(MaterialClass c) {
  for (const NamedClass& n : kClasses) {
    if (n.cls == c) return n.name;
  }
  return "?";
}

bool has_strength(const nlohmann::json& m) {
  return m.contains("iso6336_5") || (m.contains("sigma_Hlim_Pa") && m.contains("sigma_Flim_Pa"));
}

GearMaterial read_gear_material(const nlohmann::json& m, const std::string& pointer) {
  GearMaterial g;
  g.E_Pa = m.at("E_Pa").get<double>();
  g.nu = m.at("nu").get<double>();
  g.rho_kg_m3 = m.at("rho_kg_m3").get<double>();
  g.sigma_Hlim_Pa = m.value("sigma_Hlim_Pa", 0.0);
  g.sigma_Flim_Pa = m.value("sigma_Flim_Pa", 0.0);
  g.yield_Pa = m.value("yield_Pa", 0.0);
  if (!m.contains("iso6336_5")) {
    throw InvalidRating(pointer + "/iso6336_5",
                        "is needed for a rating: the class chooses the life factors, running-in "
                        "and size factors (give at least {\"class\": ...})");
  }
  const nlohmann::json& iso = m.at("iso6336_5");
  g.cls = class_from(iso.at("class").get<std::string>(), pointer + "/iso6336_5/class");
  g.quality = iso.value("quality", "MQ");
  g.hardness_HB = iso.value("hardness_HB", 0.0);
  g.hardness_HV = iso.value("hardness_HV", 0.0);
  if (g.sigma_Hlim_Pa > 0.0 && g.sigma_Flim_Pa > 0.0) {
    g.limits_from = "given";
  } else {
    limits_from_line(g, iso, pointer);
    if (m.contains("sigma_Hlim_Pa") || m.contains("sigma_Flim_Pa")) g.limits_from += ", one given";
  }
  return g;
}

}  // namespace gearsph::gear::iso6336
