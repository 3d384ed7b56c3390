#pragma once
// Executing a job into a directory: the one path shared by `gearsph run`,
// the job service and its workers. Writes, atomically (temporary file +
// rename), each when it is complete:
//   job.json      the job with every default filled in
//   summary.json  the numbers (status, peak stress, analysis, ...)
//   history.csv   time histories
// plus whatever the registered output observers write (results.h5,
// results.xmf, images).
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "solver/run/runner.hpp"

namespace gearsph {

// Creates the extra observers (writers) for one run in `dir`; registered by
// the layers that link them (results, render), so the solver library itself
// needs neither HDF5 nor GL.
using OutputFactory =
    std::function<std::unique_ptr<RunObserver>(const PreparedJob&, const std::filesystem::path&)>;
void register_output(OutputFactory factory);

struct ExecuteOptions {
  int threads = 0;                  // 0: the job's, or all cores
  RunObserver* observer = nullptr;  // progress / cancellation from the caller
};

// Adds to a finished run's summary before summary.json is written, and may
// write files of its own into the run's directory: work that follows a run
// but needs what the solver must not depend on (the finite-element check of
// fe/ runs gmsh and CalculiX). Registered by the layers that provide it;
// an exception it throws is recorded in the summary's `warnings`.
using SummaryAddition =
    std::function<void(const PreparedJob&, const RunResult&, const std::filesystem::path& dir,
                       const ExecuteOptions&, nlohmann::json& summary)>;
void register_summary_addition(SummaryAddition addition);

struct Execution {
  RunResult run;
  std::vector<std::string> files;  // written, relative to dir
};

// Writes job.json then runs. Throws InvalidJob before anything is written if
// the job is invalid.
Execution execute_job(const nlohmann::json& job, const std::filesystem::path& dir,
                      const ExecuteOptions& options);
Execution execute_prepared(PreparedJob& job, const std::filesystem::path& dir,
                           const ExecuteOptions& options);

void write_file_atomic(const std::filesystem::path& path, const std::string& content);

}  // namespace gearsph
