#pragma once
// The stability study (docs/stability.md): cases where SPH for solids is
// known to fail, each run with several methods, each cell measured.
//
// A cell is an ordinary job (so anyone can re-run it with `gearsph run`),
// run with the health check on (diagnostics/health.hpp, on_failure = stop),
// so "when it failed" is the step at which a detector or the divergence
// guard stopped it. Each cell states what the study expects of it (fails or
// stable); a cell whose outcome differs is reported, never hidden.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/job/job.hpp"

namespace gearsph::study {

struct Cell {
  std::string case_id;     // row of the table, e.g. "tension_strip"
  std::string case_label;  // for people, e.g. "strip in tension"
  std::string method_id;   // column, e.g. "ul_paper"
  std::string method_label;
  nlohmann::json job;  // a complete job, runnable with `gearsph run`
  std::string expect;  // "fails" or "stable": what the method literature predicts
  // What our measurement showed, as documented in docs/stability.md: the
  // same as `expect` unless `deviation` explains why not. Tests hold the
  // cells to it, so a change in either direction is noticed.
  std::string documented;
  std::string deviation;
  std::string purpose;  // one line: what the cell shows
  bool quick = true;    // part of the default (quick) matrix
  // Time-step cells: run at this multiple of the measured stable limit
  // (0: the job's own step).
  double dt_over_limit = 0.0;
  // A failure criterion on the scene's own analysis, beyond the detectors:
  // "stuck" (bar impact: bodies do not separate) or "spurious_stress"
  // (spinning disk: von Mises over the centrifugal scale above 0.1).
  std::string criterion;
};

// The matrix: quick cells only, or every cell (full = true).
std::vector<Cell> stability_cells(bool full);

struct CellResult {
  std::string outcome;    // "stable", "warning" or "failed"
  std::string failed_by;  // detector or guard quantity; "stuck", "spurious_stress", "wedged"
  double failed_at_s = -1.0;
  std::int64_t failed_at_step = -1;
  std::string message;
  double energy_drift = 0.0;   // final, relative (summary energy.drift_relative)
  double energy_growth = 0.0;  // max growth seen by the monitor
  double zigzag = 0.0;         // max hourglass indicator
  double min_spacing_over_dx = 0.0;
  double max_penetration_over_dx = 0.0;
  std::optional<bool> stuck;                       // bodies did not separate (contact cases)
  std::optional<double> spurious_stress;           // spinning disk: von Mises / scale
  std::optional<double> contact_force_over_bound;  // gear: peak contact force / impact bound
  std::size_t particles = 0;
  std::int64_t steps = 0, steps_planned = 0;
  double dt_s = 0.0, dt_limit_s = 0.0;
  double end_s = 0.0;
  double wall_s = 0.0;
  bool as_expected = false;    // outcome agrees with Cell::expect
  bool as_documented = false;  // outcome agrees with Cell::documented
};

struct CellRun {
  CellResult result;
  PreparedJob job;  // its final (or failed) state, for pictures
  nlohmann::json summary;
};

// Prepares and runs one cell. `threads` <= 0: the job's or all cores.
CellRun run_cell(const Cell& cell, int threads);

// CSV header and one row per cell.
std::string csv_header();
std::string csv_row(const Cell& cell, const CellResult& r);
nlohmann::json to_json(const Cell& cell, const CellResult& r);

}  // namespace gearsph::study
