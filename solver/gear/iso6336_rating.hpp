#pragma once
// The rating entry point: a rating document (schemas/rating.schema.json,
// compiled in) to the ISO 6336 verdict. Checked like a job: every refusal
// names the JSON pointer of the field (InvalidRating).
#include <array>
#include <string>

#include <nlohmann/json.hpp>

#include "solver/gear/iso6336_error.hpp"
#include "solver/gear/iso6336_factors.hpp"
#include "solver/gear/iso6336_geometry.hpp"
#include "solver/gear/iso6336_materials.hpp"

namespace gearsph::gear::iso6336 {

const nlohmann::json& rating_schema();

struct RatingInput {
  std::string name;
  PairSpec pair;
  std::array<GearMaterial, 2> mat;
  std::array<double, 2> flank_Rz_um{}, root_Rz_um{}, rim_m{};
  int accuracy_grade = 6;
  Deviations dev;
  double F_t_N = 0.0, F_static_N = 0.0, K_A = 1.0, n1_rpm = 0.0, life_h = 0.0;
  std::array<double, 2> cycles{};
  double nu40_mm2_s = 220.0;
  double K_Hbeta_given = 0.0, F_betax_um = 0.0;
  bool limited_pitting = false, optimum_long_life = false;
  double required_S_H = 1.0, required_S_F = 1.4;
};

// Schema check, defaults, and the checks a schema cannot say (one of two
// load forms, a rack without teeth); throws InvalidRating.
RatingInput read_rating(const nlohmann::json& document);

// The verdict as JSON: pitting, bending, static, factors, life, governing.
nlohmann::json rate(const RatingInput& in);

// read_rating + rate.
nlohmann::json rate_document(const nlohmann::json& document);

}  // namespace gearsph::gear::iso6336
