#pragma once
// A speed sweep as a study (docs/dynamics.md, docs/api.md "Speed sweeps"):
//
//   {"name": "paper-pair", "speed_sweep": {"job": {...}, "ratios": [0.2, ...],
//    "steady_periods": 20, "stiffness": "iso"}}
//
// is planned as `gearsph study speed-sweep` plans it (solver/study/
// speed_sweep.hpp): one job per speed, each ending once its mesh has been
// steady for the periods asked for. The plan is kept with the study; once
// every job has finished, the study's document carries the sweep's report
// (speed_sweep.json's keys) under "speed_sweep".
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "server/config.hpp"
#include "server/study.hpp"

namespace gearsph::server {

bool is_speed_sweep(const nlohmann::json& body);

struct SpeedSweepStudy {
  std::string name;
  std::vector<StudyPoint> points;  // parameters: {"ratio", "mesh_frequency_Hz"}
  nlohmann::json plan;             // study::plan_document
};

// Checks the request and plans the sweep before any job is stored: throws
// InvalidJob with pointers into the request (/speed_sweep/job/..., a
// ratio at /speed_sweep/ratios/k, a speed whose job the limits refuse).
// The measured stiffness is refused here: its quasi-static checks take
// minutes, longer than a request may (the CLI runs them); the table they
// give may be posted as the stiffness.
SpeedSweepStudy plan_speed_sweep_study(const nlohmann::json& body, const Limits& limits);

// The sweep's report from the stored plan and each speed's summary in the
// plan's order (null: that job did not succeed).
nlohmann::json speed_sweep_report(const nlohmann::json& plan,
                                  const std::vector<nlohmann::json>& summaries);

}  // namespace gearsph::server
