#pragma once
// Slurm as the engine that runs the jobs (`gearsph serve --dispatch slurm`).
// Each queued job becomes one Slurm job: a batch script in the job's
// directory runs `gearsph run` with as many threads as the allocation has
// CPUs, then leaves its exit status next to the results. A thread of the
// server submits queued jobs with sbatch, follows them with squeue (and
// sacct where accounting is on), maps Slurm's states to ours, cancels
// dismissed ones with scancel and records the outcome. Everything it needs
// to know is in the job store (each job's Slurm job id) and the job
// directories, so a restarted server picks up where the last one stopped.
//
// The job directories must be on a file system the Slurm nodes share.
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "server/dispatcher.hpp"
#include "server/fe_stage_estimate.hpp"
#include "server/job_store.hpp"

namespace gearsph::server {

// ---- Slurm's command-line interface, as data ---------------------------

// `sbatch --parsable` prints "JOBID" or "JOBID;CLUSTER".
std::optional<std::string> parse_sbatch_parsable(std::string_view out);

// One line of `squeue --noheader --states=all --format=%i|%j|%T|%r`.
struct SlurmQueueEntry {
  std::string job_id, name, state, reason;
};
inline constexpr const char* kSqueueFormat = "%i|%j|%T|%r";
std::vector<SlurmQueueEntry> parse_squeue(std::string_view out);

// One line of `sacct --noheader --parsable2 --allocations --format=JobID,State,ExitCode`
// ("123|COMPLETED|0:0", "124|CANCELLED by 0|0:0").
struct SlurmAccounting {
  std::string job_id, state;
  int exit_code = 0;
};
std::vector<SlurmAccounting> parse_sacct(std::string_view out);

// Where a Slurm job state (squeue %T / sacct State, long form) leaves ours.
enum class SlurmPhase { queued, running, ended, unknown };
SlurmPhase slurm_phase(std::string_view state);

// The last progress line `gearsph run` printed ("[ 42.0%] step 420/1000  t = ...").
struct RunProgress {
  std::int64_t step = 0, steps = 0;
  double time_s = 0, wall_s = 0, eta_s = 0;
};
std::optional<RunProgress> parse_run_progress(std::string_view output_tail);

// The last stage line `gearsph run` printed after its time loop
// ("[stage fe_check] 50.0 % done, 3.21 s"; apps/gearsph/progress.hpp).
std::optional<StageProgress> parse_stage_progress(std::string_view output_tail);

struct SlurmOptions {
  std::filesystem::path jobs_dir;        // each job runs in jobs_dir / id (shared by the nodes)
  std::filesystem::path gearsph;         // the executable the batch script runs
  int cpus_per_job = 1;                  // --cpus-per-task of each Slurm job
  std::vector<std::string> sbatch_args;  // more sbatch options (--partition=..., --time=...)
  std::chrono::milliseconds poll_interval{1000};
  // An ended job whose exit status file has not appeared (a network file
  // system lagging) is waited for this long before it counts as failed.
  std::chrono::milliseconds exit_grace{30'000};
  std::string name;  // this server, for the placeholder while sbatch runs
};

// The batch script of one job: #SBATCH lines, then `gearsph run`, then the exit status.
std::string slurm_batch_script(const std::string& job_id, const std::filesystem::path& dir,
                               const SlurmOptions& options);

// A command's result (stdout, stderr, exit status; -1 if it could not run).
struct CommandResult {
  int status = -1;
  std::string out, err;
};
CommandResult run_command(const std::vector<std::string>& argv,
                          std::chrono::milliseconds timeout = std::chrono::seconds(60));

class SlurmDispatcher : public Dispatcher {
 public:
  SlurmDispatcher(JobStore& store, SlurmOptions options);
  ~SlurmDispatcher() override;

  void start() override;
  void notify() override;
  void stop() override;
  std::optional<ProgressUpdate> live(const std::string&) const override { return std::nullopt; }
  bool cancel(const std::string& id) override;
  int running() const override { return 0; }

  // One pass: submit what is queued, follow what was submitted (public for tests).
  void pass();

 private:
  void loop();
  void submit_queued();
  bool submit(const JobRecord& job);
  void track();
  void conclude(const JobRecord& job, const std::string& slurm_id, const std::string& state);
  // A running job's progress from its output; for a job with the FE check,
  // both stages counted as the server's own workers count them.
  void follow_running(const JobRecord& job);
  // The FE stage's estimate of a job that runs the check, made once per job.
  const FeStageEstimate& fe_estimate_of(const std::string& id);
  std::filesystem::path dir_of(const std::string& id) const { return options_.jobs_dir / id; }

  JobStore& store_;
  SlurmOptions options_;
  std::map<std::string, std::chrono::steady_clock::time_point> ended_without_status_;
  std::map<std::string, FeStageEstimate> fe_estimates_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  bool poked_ = false;
  std::thread thread_;
};

}  // namespace gearsph::server
