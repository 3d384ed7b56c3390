#pragma once
// The validation cases of validation.md as data: a job, the quantity it
// measures, the reference it is compared with, and the tolerance. The same
// list drives `gearsph validate` (full variants) and the test suite (quick
// variants), so the tests check exactly what the report claims. A case
// may also be a rating document answered by the ISO 6336 calculator.
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
  // |error| <= tol; measured/scale <= tol; a yes/no outcome equal to the expected one.
  enum class Kind { Relative, Bound, Outcome };
  // What `job` is: a simulation job to run, or a rating document
  // (schemas/rating.schema.json) for the ISO 6336 calculator, which is
  // arithmetic and takes microseconds (measured on rating_summary()).
  enum class Input { Job, Rating };
  std::string id;         // e.g. plate_period/seed_quartic
  std::string section;    // validation.md section
  std::string quantity;   // what is compared, with unit
  std::string reference;  // where the reference number comes from
  double tolerance = 0.0;
  nlohmann::json job;
  std::function<Measurement(const nlohmann::json& summary, double tolerance)> measure;
  Kind kind = Kind::Relative;
  // Non-empty: a comparison we report but do not claim to pass, and why
  // (docs/gears.md); `gearsph validate` prints it, the tests skip it.
  std::string disagreement = {};
  Input input = Input::Job;
};

// The summary a rating case is measured on: {"status": "completed",
// "analysis": {"rating": the calculator's answer to the document}}.
// Throws gear::iso6336::InvalidRating on a document it refuses.
nlohmann::json rating_summary(const nlohmann::json& document);

// quick: the variants the test suite runs (small, seconds each).
std::vector<Case> cases(bool quick);

}  // namespace gearsph::validation
