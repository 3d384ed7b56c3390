#include "solver/gear/iso6336_materials.hpp"

#include <cstdio>
#include <vector>

#include "solver/gear/iso6336_error.hpp"

namespace gearsph::gear::iso6336 {

namespace {

constexpr double kMPa = 1e6;

struct NamedClass {
  const char* name;
  MaterialClass cls;
  bool nitrocarburised;
};
constexpr NamedClass kClasses[] = {
    {"St", MaterialClass::St, false},       {"St(cast)", MaterialClass::St, false},
    {"GTS", MaterialClass::GTS, false},     {"GJS", MaterialClass::GJS, false},
    {"GJL", MaterialClass::GJL, false},     {"V", MaterialClass::V, false},
    {"V(cast)", MaterialClass::V, false},   {"Eh", MaterialClass::Eh, false},
    {"IF", MaterialClass::IF, false},       {"NT", MaterialClass::NT, false},
    {"NV(nitr)", MaterialClass::NV, false}, {"NV(nitrocar)", MaterialClass::NV, true}};

// One segment of an ISO 6336-5:2016 line: limit = A x + B [MPa] for the
// hardness x (HBW or HV) from x_min to x_max. A = 0 where the limit does not
// rise with the hardness within its range.
struct Segment {
  double A, B, x_min, x_max;
};
// A line: one segment, or two that meet (IF MQ bending, NV(nitrocar) MQ/ME).
using Line = std::vector<Segment>;
struct ClassLines {
  Line H, F;
  bool vickers;  // hardness in HV (else HBW)
};

// ISO 6336-5:2016, Table 8 (the lines of Figures 1-16; the same as
// ISO 6336-5:2003, Table 1), keyed by class label, the V steels' kind
// (carbon or alloy) and the quality. ML and MQ share a line where the
// standard draws one for both. docs/rating.md gives the source and what in
// it was ambiguous.
ClassLines lines_for(const std::string& label, bool alloy, const std::string& q) {
  const bool ML = q == "ML", ME = q == "ME";
  // Normalised low-carbon wrought steel and cast steel (Figures 1, 2).
  if (label == "St") {
    return ME ? ClassLines{{{1.520, 250, 110, 210}}, {{0.386, 147, 110, 210}}, false}
              : ClassLines{{{1.000, 190, 110, 210}}, {{0.455, 69, 110, 210}}, false};
  }
  if (label == "St(cast)") {
    return ME ? ClassLines{{{1.143, 237, 140, 210}}, {{0.254, 137, 140, 210}}, false}
              : ClassLines{{{0.986, 131, 140, 210}}, {{0.313, 62, 140, 210}}, false};
  }
  // Cast irons (Figures 3, 4): black malleable, nodular, grey.
  if (label == "GTS") {
    return ME ? ClassLines{{{1.333, 267, 175, 250}}, {{0.403, 128, 175, 250}}, false}
              : ClassLines{{{1.371, 143, 135, 250}}, {{0.345, 77, 135, 250}}, false};
  }
  if (label == "GJS") {
    return ME ? ClassLines{{{1.500, 250, 200, 300}}, {{0.380, 134, 200, 300}}, false}
              : ClassLines{{{1.434, 211, 175, 300}}, {{0.350, 119, 175, 300}}, false};
  }
  if (label == "GJL") {
    return ME ? ClassLines{{{1.465, 122, 175, 275}}, {{0.200, 53, 175, 275}}, false}
              : ClassLines{{{1.033, 132, 150, 240}}, {{0.256, 8, 150, 240}}, false};
  }
  // Through-hardened wrought steels (Figures 5, 6), carbon and alloy.
  if (label == "V" && !alloy) {
    if (ML) return {{{0.963, 283, 135, 210}}, {{0.250, 108, 115, 215}}, true};
    if (ME) return {{{0.838, 432, 135, 210}}, {{0.283, 202, 115, 215}}, true};
    return {{{0.925, 360, 135, 210}}, {{0.240, 163, 115, 215}}, true};
  }
  if (label == "V") {
    if (ML) return {{{1.313, 188, 200, 360}}, {{0.423, 104, 200, 360}}, true};
    if (ME) return {{{2.213, 260, 200, 390}}, {{0.358, 231, 200, 390}}, true};
    return {{{1.313, 373, 200, 360}}, {{0.425, 187, 200, 360}}, true};
  }
  // Through-hardened cast steels (Figures 7, 8), carbon and alloy.
  if (label == "V(cast)" && !alloy) {
    return ME ? ClassLines{{{0.951, 345, 130, 215}}, {{0.286, 167, 130, 215}}, true}
              : ClassLines{{{0.831, 300, 130, 215}}, {{0.224, 117, 130, 215}}, true};
  }
  if (label == "V(cast)") {
    return ME ? ClassLines{{{1.350, 356, 200, 360}}, {{0.356, 186, 200, 360}}, true}
              : ClassLines{{{1.276, 298, 200, 360}}, {{0.364, 161, 200, 360}}, true};
  }
  // Case-carburised wrought steels (Figures 9, 10; MQ with a core hardness
  // of at least 25 HRC).
  if (label == "Eh") {
    if (ML) return {{{0.0, 1300, 600, 800}}, {{0.0, 312, 600, 800}}, true};
    if (ME) return {{{0.0, 1650, 660, 800}}, {{0.0, 525, 660, 800}}, true};
    return {{{0.0, 1500, 660, 800}}, {{0.0, 425, 660, 800}}, true};
  }
  // Flame or induction hardened wrought and cast steels (Figures 11, 12).
  if (label == "IF") {
    if (ML) return {{{0.740, 602, 485, 615}}, {{0.305, 76, 485, 615}}, true};
    if (ME) return {{{0.505, 1013, 500, 615}}, {{0.271, 237, 500, 615}}, true};
    return {{{0.541, 882, 500, 615}}, {{0.138, 290, 500, 570}, {0.0, 369, 570, 615}}, true};
  }
  // Nitrided nitriding steels and nitrided through-hardening steels
  // (Figures 13, 14).
  if (label == "NT") {
    if (ML) return {{{0.0, 1125, 650, 900}}, {{0.0, 270, 650, 900}}, true};
    if (ME) return {{{0.0, 1450, 650, 900}}, {{0.0, 468, 650, 900}}, true};
    return {{{0.0, 1250, 650, 900}}, {{0.0, 420, 650, 900}}, true};
  }
  if (label == "NV(nitr)") {
    if (ML) return {{{0.0, 788, 450, 650}}, {{0.0, 258, 450, 650}}, true};
    if (ME) return {{{0.0, 1217, 450, 650}}, {{0.0, 432, 450, 650}}, true};
    return {{{0.0, 998, 450, 650}}, {{0.0, 363, 450, 650}}, true};
  }
  // Nitrocarburised through-hardening wrought steels (Figures 15, 16): ME
  // as MQ.
  if (ML) return {{{0.0, 650, 300, 650}}, {{0.0, 224, 300, 650}}, true};
  return {{{1.167, 425, 300, 450}, {0.0, 950, 450, 650}},
          {{0.653, 94, 300, 450}, {0.0, 388, 450, 650}},
          true};
}

bool needs_kind(const std::string& label) {
  return label == "V" || label == "V(cast)";
}

bool flat(const Line& line) {
  for (const Segment& s : line) {
    if (s.A != 0.0) return false;
  }
  return true;
}

// The line's value at x, or nothing outside its range.
bool evaluate(const Line& line, double x, double& out) {
  for (const Segment& s : line) {
    if (x >= s.x_min && x <= s.x_max) {
      out = s.A * x + s.B;
      return true;
    }
  }
  return false;
}

const NamedClass& class_from(const std::string& name, const std::string& pointer) {
  for (const NamedClass& c : kClasses) {
    if (name == c.name) return c;
  }
  if (name == "NV") {
    throw InvalidRating(pointer,
                        "\"NV\" is ambiguous: \"NV(nitr)\" (nitrided) or \"NV(nitrocar)\" "
                        "(nitrocarburised) through-hardening steel; their lines and life factors "
                        "differ");
  }
  std::string known;
  for (const NamedClass& c : kClasses) known += std::string(known.empty() ? "" : ", ") + c.name;
  throw InvalidRating(pointer, "is not an ISO 6336-5 class: " + known);
}

// sigma_Hlim and sigma_Flim (those not given) from the class's lines at the
// material's hardness. A hardness outside a line's range is refused: ISO
// 6336-5 draws its lines over those ranges only and gives no values beyond.
void limits_from_line(GearMaterial& g, const nlohmann::json& iso, const std::string& pointer) {
  const std::string at = pointer + "/iso6336_5";
  const bool need_H = g.sigma_Hlim_Pa <= 0.0, need_F = g.sigma_Flim_Pa <= 0.0;
  bool alloy = false;
  if (needs_kind(g.class_label)) {
    if (!iso.contains("steel")) {
      throw InvalidRating(at,
                          "needs \"steel\": \"carbon\" or \"alloy\" to read the ISO 6336-5 "
                          "line of class " +
                              g.class_label);
    }
    alloy = iso.at("steel").get<std::string>() == "alloy";
  }
  const ClassLines lines = lines_for(g.class_label, alloy, g.quality);
  const char* key = lines.vickers ? "hardness_HV" : "hardness_HB";
  const char* other = lines.vickers ? "hardness_HB" : "hardness_HV";
  const char* unit = lines.vickers ? "HV" : "HB";
  const double x = iso.value(key, 0.0);
  const bool used_flat = (!need_H || flat(lines.H)) && (!need_F || flat(lines.F));
  if (x <= 0.0 && !used_flat) {
    std::string why = std::string("needs ") + key + " to read the ISO 6336-5 line of class " +
                      g.class_label + " (its lines are in " + unit + ")";
    if (iso.contains(other)) why += std::string("; ") + other + " is not converted";
    throw InvalidRating(at, why);
  }
  auto read = [&](const Line& line, const char* what) {
    const double xx = x > 0.0 ? x : line.front().x_min;  // flat: any point of it
    double v = 0.0;
    if (!evaluate(line, xx, v)) {
      char buf[240];
      std::snprintf(buf, sizeof buf,
                    "%g %s is outside the ISO 6336-5 %s line of class %s %s%s: %g to %g %s", x,
                    unit, what, g.class_label.c_str(), g.quality.c_str(),
                    needs_kind(g.class_label) ? (alloy ? " (alloy)" : " (carbon)") : "",
                    line.front().x_min, line.back().x_max, unit);
      throw InvalidRating(at + "/" + key, buf);
    }
    return v * kMPa;
  };
  // A given hardness must lie on every line read, flat ones included.
  if (need_H) g.sigma_Hlim_Pa = read(lines.H, "sigma_Hlim");
  if (need_F) g.sigma_Flim_Pa = read(lines.F, "sigma_Flim");
  g.limits_from = "ISO 6336-5:2016 line of " + g.class_label +
                  (needs_kind(g.class_label) ? (alloy ? " alloy" : " carbon") : "") + " " +
                  g.quality;
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

const std::vector<std::string>& class_labels() {
  static const std::vector<std::string> labels = [] {
    std::vector<std::string> v;
    for (const NamedClass& c : kClasses) v.emplace_back(c.name);
    return v;
  }();
  return labels;
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
  const NamedClass& c =
      class_from(iso.at("class").get<std::string>(), pointer + "/iso6336_5/class");
  g.cls = c.cls;
  g.class_label = c.name;
  g.nitrocarburised = c.nitrocarburised;
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
