#pragma once
// The validation cases of validation.md as data: a job, the quantity it
// measures, the reference it is compared with, and the tolerance. The same
// list drives `gearsph validate` (full variants) and the test suite (quick
// variants), so the tests check exactly what the report claims.
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gearsph::validation {

struct Measurement {
  double measured = 0.0;
  double reference = 0.0;
  double error = 0.0;  // as defined by the case (relative unless stated)
  bool pass = false;
  std::string note;
};

struct Case {
  enum class Kind { Relative, Bound };  // |error| <= tol, or measured/scale <= tol
  std::string id;                       // e.g. plate_period/seed_quartic
  std::string section;                  // validation.md section
  std::string quantity;                 // what is compared, with unit
  std::string reference;                // where the reference number comes from
  double tolerance = 0.0;
  nlohmann::json job;
  std::function<Measurement(const nlohmann::json& summary, double tolerance)> measure;
  Kind kind = Kind::Relative;
};

// quick: the variants the test suite runs (small, seconds each).
std::vector<Case> cases(bool quick);

}  // namespace gearsph::validation
