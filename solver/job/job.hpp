#pragma once
// A job from JSON text to a ready-to-run scene: parse, check against
// schemas/job.schema.json (compiled in), fill defaults, build the scene and
// choose the time step. Every refusal names the JSON pointer of the field.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/integrate/time_step.hpp"
#include "solver/scene/scene.hpp"

namespace gearsph {

struct JobIssue {
  std::string pointer;  // RFC 6901 JSON pointer into the job
  std::string message;  // one sentence
};

class InvalidJob : public std::runtime_error {
 public:
  explicit InvalidJob(std::vector<JobIssue> issues);
  std::vector<JobIssue> issues;
};

const nlohmann::json& job_schema();

// Parses JSON text; malformed JSON becomes an InvalidJob at pointer "".
nlohmann::json parse_job_text(const std::string& text);
// Schema check and defaults; throws InvalidJob listing every violation.
nlohmann::json validate_job(const nlohmann::json& job);

// A job that names no output.history_points: this many history samples over
// the run, at least kDefaultHistoryMinSteps steps apart.
inline constexpr std::int64_t kDefaultHistoryPoints = 4000;
inline constexpr std::int64_t kDefaultHistoryMinSteps = 10;

// How often a run chosen by trial repeats it (run/thread_trial.hpp): ~0.5 %
// of the run at ~50 ms a trial.
inline constexpr double kRetrialSeconds = 10.0;

struct PreparedJob {
  nlohmann::json job;  // with defaults
  Scene scene;
  TimeStepChoice time_step;
  double end_s = 0.0;
  std::int64_t steps = 0;
  std::int64_t history_every = 1;
  std::int64_t snapshot_every = 0;  // 0: no snapshots
  std::int64_t frames = 0;          // snapshots the run will write (with frame 0 and the last)
  bool compress_frames = false;     // output.compress: deflate the frames in results.h5
  // Who chose scene.sim.threads: "caller" (--threads), "job" (its "threads"),
  // "size" or "trial". For "trial", run_job times 1 to trial_threads threads
  // on a copy of the scene and runs on the fastest (run/thread_trial.hpp).
  std::string threads_by = "size";
  int trial_threads = 0;
  // For "trial": the trial is repeated on a copy of the running scene every
  // so many seconds of the run, and the run switches to its new choice
  // (run/thread_trial.hpp); <= 0: after every 64 steps.
  double retrial_every_s = kRetrialSeconds;
};

// Validates, builds the scene, chooses dt. `threads` > 0: exactly that many
// OpenMP threads; else the job's "threads", at most `max_threads` (<= 0:
// all cores); else choose_threads().
PreparedJob prepare_job(const nlohmann::json& job, int threads = 0, int max_threads = 0);

// Threads worth giving a scene of `particles`: one per kParticlesPerThread,
// at least one, at most max_threads. On 2 cores two threads beat one from
// ~100 particles up when the second core is free (docs/speed-accuracy-history.md,
// Threads).
inline constexpr std::size_t kParticlesPerThread = 100;
int threads_for(std::size_t particles, int max_threads);

// A scene this large takes threads_for() threads without a trial: its steps
// are long against a thread's hand-over whatever else runs (1.99x at
// 55,878 particles), and a trial would copy it.
inline constexpr std::size_t kThreadsWithoutTrial = 40000;
// A shorter run takes one thread: the trial's ~40 ms would be a large part
// of it (~1.4 s at 1e7 particle-steps on one thread).
inline constexpr double kTrialParticleSteps = 1e7;
// Fills PreparedJob::threads_by, trial_threads and scene.sim.threads for a
// job that names no thread count.
void choose_threads(PreparedJob& job, int max_threads);

}  // namespace gearsph
