#pragma once
// Gear materials with strength: the ISO 6336-5:2016 class and quality, the
// allowable stress numbers sigma_Hlim (contact) and sigma_Flim (bending,
// the nominal stress number of the reference test gear), and the yield
// strength for the static check. The class also chooses the material's
// life-factor lines (ISO 6336-2/-3), running-in allowances (ISO 6336-1),
// size and notch-sensitivity factors (ISO 6336-3).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gearsph::gear::iso6336 {

// ISO 6336-1:2006, Table 2 abbreviations: St normalised low-carbon or cast
// steel, V through-hardened steel, GJS nodular cast iron (perlitic,
// bainitic), GTS black malleable iron, GJL grey cast iron, Eh case-
// carburised, IF flame or induction hardened, NT nitrided nitriding steel,
// NV nitrided or nitrocarburised through-hardening steel.
enum class MaterialClass { St, V, GJS, GTS, GJL, Eh, IF, NT, NV };

// Surface-hardened classes (Eh, IF, NT, NV): their own running-in, size and
// work-hardening rules.
bool surface_hardened(MaterialClass c);
const char* class_name(MaterialClass c);

// The names a material's iso6336_5.class takes: ISO 6336-5:2016 Table 8's
// abbreviations, St(cast) and V(cast) for the cast steels of the St and V
// lines, NV(nitr) and NV(nitrocar) for the nitrided and the nitrocarburised
// through-hardening steels (their life lines differ too).
const std::vector<std::string>& class_labels();

struct GearMaterial {
  double E_Pa = 0.0, nu = 0.0, rho_kg_m3 = 0.0;
  MaterialClass cls = MaterialClass::St;
  std::string class_label = "St";  // as given: St, St(cast), V, V(cast), ..., NV(nitrocar)
  bool nitrocarburised = false;    // NV(nitrocar): its own life lines (ISO 6336-2, -3)
  std::string quality = "MQ";      // ML, MQ or ME (ISO 6336-5:2016, clause 4)
  double hardness_HB = 0.0;        // 0: not given
  double hardness_HV = 0.0;
  double sigma_Hlim_Pa = 0.0;
  double sigma_Flim_Pa = 0.0;
  double yield_Pa = 0.0;    // 0: no yield check
  std::string limits_from;  // "ISO 6336-5 line ..." or "given"
};

// Reads a material with strength (the job schema's material definition):
// E_Pa, nu, rho_kg_m3, iso6336_5 {class, quality, hardness_HB|hardness_HV},
// sigma_Hlim_Pa and sigma_Flim_Pa (given, or from the class's ISO 6336-5
// line and the hardness), yield_Pa. Throws InvalidRating at `pointer`/...
// when the limits can be had neither way.
GearMaterial read_gear_material(const nlohmann::json& m, const std::string& pointer);

// Whether a material of the job schema carries strength (the two limits,
// directly or through an ISO 6336-5 class line).
bool has_strength(const nlohmann::json& m);

}  // namespace gearsph::gear::iso6336
