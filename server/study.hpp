#pragma once
// Parameter studies: a base job and axes ({pointer, values}) expand into
// the cartesian product of jobs; their summaries fold into one table.
//
//   {"name": "spacing", "base": {...job...},
//    "axes": [{"pointer": "/discretization/spacing_m", "values": [0.004, 0.002]}]}
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/job/job.hpp"

namespace gearsph::server {

struct StudyAxis {
  std::string pointer;  // RFC 6901, into the job
  std::vector<nlohmann::json> values;
};

struct StudySpec {
  std::string name;
  nlohmann::json base;
  std::vector<StudyAxis> axes;
};

// Checks the request's shape; throws InvalidJob with pointers into the
// request (e.g. "/axes/1/values") when it is wrong or would make more than
// max_jobs jobs.
StudySpec parse_study(const nlohmann::json& body, std::int64_t max_jobs);

struct StudyPoint {
  nlohmann::json job;                    // the base with this point's values set
  nlohmann::json parameters;             // {pointer: value} of this point
  std::vector<std::size_t> value_index;  // per axis
};
// In row-major order: the last axis varies fastest. Throws InvalidJob when
// a pointer cannot be set in the base (it runs through a non-object).
std::vector<StudyPoint> expand_study(const StudySpec& spec);

// One row per job: jobID, status, the axis values, then every scalar of its
// summary (nested keys joined with '.', array items as [i]).
using StudyRow = std::vector<std::pair<std::string, nlohmann::json>>;  // column, value
struct StudyTable {
  std::vector<std::string> columns;  // every column of any row, in first-seen order
  std::vector<nlohmann::json> rows;  // objects keyed by column
};
StudyTable study_table(const std::vector<StudyRow>& rows);
std::string to_csv(const StudyTable& table);

// Appends the scalars of `j` to `row` (see study_table).
void flatten_scalars(const nlohmann::json& j, const std::string& prefix, StudyRow& row);

}  // namespace gearsph::server
