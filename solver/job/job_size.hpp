#pragma once
// How big a job is before its particles are built: the particle and step
// counts from the same scene builders run on coarser copies of the job
// (a few thousand particles each), extrapolated to the job's spacing. A
// server decides from it, in milliseconds, whether a request may build the
// scene at all (docs/api.md, Admission).
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

#include "solver/job/job.hpp"

namespace gearsph {

struct JobSize {
  double particles = 0.0;
  double steps = 0.0;
  double end_s = 0.0;  // the simulated time (the scene's default where the job gives none)
  // The job itself was built (it was small enough, or gives no spacing to
  // coarsen): the counts are exact.
  bool exact = false;
  bool body_fitted = false;  // some body's particles are body-fitted (relaxed: costly to build)
  // Two probes at spacing factors k_coarse > k_fine (k_fine = 1 when exact)
  // and their particle counts.
  double k_coarse = 0.0, k_fine = 0.0;
  double probe_particles_coarse = 0.0, probe_particles_fine = 0.0;
  std::shared_ptr<const PreparedJob> built;  // when exact: the job, prepared on one thread
  nlohmann::json to_json() const;
};

// A sizing (or a set-up under a SetupStop) cut short: its deadline passed,
// or the one who asked no longer waits.
class SetupStopped : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// While in scope on this thread, every long set-up stage (particle
// relaxation, pairing, the stable-step search: setup_progress) throws
// SetupStopped once `deadline` has passed or `gone()` says so.
class SetupStop {
 public:
  SetupStop(std::chrono::steady_clock::time_point deadline, std::function<bool()> gone);
  ~SetupStop();
  SetupStop(const SetupStop&) = delete;
  SetupStop& operator=(const SetupStop&) = delete;

 private:
  struct Scope;
  std::unique_ptr<Scope> scope_;
};

struct JobSizeOptions {
  // Particles a probe aims at: its counts then carry the 1/k^2 area term
  // and the 1/k outline (or graded layer) term to about a percent.
  double probe_particles = 8000.0;
};

// `job`: validated, defaults filled (validate_job). Throws InvalidJob when
// even the job itself cannot be built, SetupStopped when a stop in scope
// (SetupStop) ends the probes.
JobSize estimate_job_size(const nlohmann::json& job, const JobSizeOptions& options = {});

}  // namespace gearsph
