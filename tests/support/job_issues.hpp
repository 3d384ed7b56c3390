#pragma once
// What a job's refusal says: the issues prepare_job() raises (none when the
// job is accepted), for the tests of refusals.
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/job/job.hpp"

namespace gearsph::testing_support {

inline std::vector<JobIssue> issues_of(const nlohmann::json& job) {
  try {
    prepare_job(job, 1);
  } catch (const InvalidJob& e) {
    return e.issues;
  }
  return {};
}

}  // namespace gearsph::testing_support
