#pragma once
// Life factors Z_NT (ISO 6336-2:2006, Table 2) and Y_NT (ISO 6336-3:2006,
// Table 4) over the number of load cycles, the permissible stress between
// its static and reference values, and its inverse: the number of cycles
// at which a stress leaves a required safety.
#include <vector>

#include "solver/gear/iso6336_materials.hpp"

namespace gearsph::gear::iso6336 {

// A life line: factors at given cycle counts, log-log between them. The
// first point is the static limit (the factor stays there below it), the
// point with factor 1 the reference (the knee); past it the line falls to
// kLongLifeFactor at kLongLifeCycles, or stays at 1 where materials,
// lubrication, manufacture and experience are optimal (ISO 6336-2:2006,
// Figure 6 and note; ISO 6336-3:2006, Figure 10).
struct LifeLine {
  std::vector<double> cycles;
  std::vector<double> factors;
};
inline constexpr double kLongLifeCycles = 1e10;
inline constexpr double kLongLifeFactor = 0.85;

// The material's line by its class (NV(nitr) and NV(nitrocar) apart).
// limited_pitting: the St/V/GJS/GTS/Eh/IF line with limited pitting
// permitted (ISO 6336-2:2006, Table 2, first row).
LifeLine pitting_life_line(const GearMaterial& m, bool limited_pitting);
LifeLine bending_life_line(const GearMaterial& m);

double life_factor(const LifeLine& line, double cycles, bool optimum);
double static_factor(const LifeLine& line);
double reference_cycles(const LifeLine& line);

// The permissible (limit) stress sigma_G at `cycles` (ISO 6336-2:2006,
// 5.2; ISO 6336-3:2006, 5.2): the static value below the static limit,
// sigma_ref times the life factor past the reference, and log-log between,
// so that influence factors which apply in the long-life range only (Z_L,
// Z_v, Z_R, Y_deltarelT, Y_RrelT, Y_X) fade out toward the static value.
double permissible_stress(const LifeLine& line, double sigma_static, double sigma_ref,
                          double cycles, bool optimum);
// Cycles at which permissible_stress() falls to sigma_needed: 0 if it is
// above the static value, infinity if the line never falls to it (the
// optimum line, or beyond kLongLifeCycles).
double cycles_to_stress(const LifeLine& line, double sigma_static, double sigma_ref,
                        double sigma_needed, bool optimum);

}  // namespace gearsph::gear::iso6336
