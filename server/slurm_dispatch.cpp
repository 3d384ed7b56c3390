#include "server/slurm_dispatch.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "server/documents.hpp"
#include "server/log.hpp"

namespace gearsph::server {

namespace {

using Clock = std::chrono::steady_clock;

constexpr const char* kRefPrefix = "slurm:";
constexpr const char* kSubmitting = "slurm:submitting:";
// A placeholder this old belongs to a server that is gone (sbatch is given
// 60 s at most; run_command): another API node may then adopt the Slurm
// job it made, or queue the job again. Younger ones are left alone, or two
// nodes would both submit the job.
constexpr double kPlaceholderGoneAfterS = 120;

std::string_view trim(std::string_view s) {
  while (!s.empty() &&
         (s.front() == ' ' || s.front() == '\t' || s.front() == '\r' || s.front() == '\n')) {
    s.remove_prefix(1);
  }
  while (!s.empty() &&
         (s.back() == ' ' || s.back() == '\t' || s.back() == '\r' || s.back() == '\n')) {
    s.remove_suffix(1);
  }
  return s;
}

std::vector<std::string_view> split(std::string_view s, char sep) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  for (;;) {
    const auto at = s.find(sep, start);
    parts.push_back(s.substr(start, at == std::string_view::npos ? at : at - start));
    if (at == std::string_view::npos) return parts;
    start = at + 1;
  }
}

bool all_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s) {
    if (c < '0' || c > '9') return false;
  }
  return true;
}

// Single quotes for /bin/sh: 'it'\''s'.
std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) {
    if (c == '\'') {
      q += "'\\''";
    } else {
      q += c;
    }
  }
  return q + "'";
}

std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string tail_of(const std::filesystem::path& file, std::size_t bytes) {
  std::ifstream in(file, std::ios::binary | std::ios::ate);
  if (!in) return {};
  const std::streamoff size = in.tellg();
  const std::streamoff from =
      size > static_cast<std::streamoff>(bytes) ? size - static_cast<std::streamoff>(bytes) : 0;
  in.seekg(from);
  std::string s(static_cast<std::size_t>(size - from), '\0');
  in.read(s.data(), static_cast<std::streamsize>(s.size()));
  return s;
}

std::string fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string job_name(const std::string& id) {
  return "gearsph-" + id;
}

// Seconds since the file was last written (0 if it cannot be told): the
// FE stage reports after each mesh, and its clock runs in between.
double seconds_since_written(const std::filesystem::path& file) {
  struct stat st {};
  timespec now{};
  if (::stat(file.c_str(), &st) != 0 || ::clock_gettime(CLOCK_REALTIME, &now) != 0) return 0.0;
  const double ago =
      double(now.tv_sec - st.st_mtim.tv_sec) + 1e-9 * double(now.tv_nsec - st.st_mtim.tv_nsec);
  return std::max(0.0, ago);
}

}  // namespace

std::optional<std::string> parse_sbatch_parsable(std::string_view out) {
  // Only the last non-empty line: sbatch may print warnings first.
  std::string_view last;
  for (std::string_view line : split(out, '\n')) {
    if (!trim(line).empty()) last = trim(line);
  }
  const std::string_view id = last.substr(0, last.find(';'));
  if (!all_digits(id)) return std::nullopt;
  return std::string(id);
}

std::vector<SlurmQueueEntry> parse_squeue(std::string_view out) {
  std::vector<SlurmQueueEntry> entries;
  for (std::string_view line : split(out, '\n')) {
    line = trim(line);
    if (line.empty()) continue;
    const auto f = split(line, '|');
    if (f.size() < 3 || !all_digits(trim(f[0]))) continue;
    SlurmQueueEntry e;
    e.job_id = std::string(trim(f[0]));
    e.name = std::string(trim(f[1]));
    e.state = std::string(trim(f[2]));
    if (f.size() > 3) e.reason = std::string(trim(f[3]));
    entries.push_back(std::move(e));
  }
  return entries;
}

std::vector<SlurmAccounting> parse_sacct(std::string_view out) {
  std::vector<SlurmAccounting> rows;
  for (std::string_view line : split(out, '\n')) {
    line = trim(line);
    if (line.empty()) continue;
    const auto f = split(line, '|');
    if (f.size() < 3 || !all_digits(trim(f[0]))) continue;  // skips steps (123.batch)
    SlurmAccounting a;
    a.job_id = std::string(trim(f[0]));
    // "CANCELLED by 0": the state is the first word.
    const std::string_view state = trim(f[1]);
    a.state = std::string(state.substr(0, state.find(' ')));
    const std::string_view code = trim(f[2]);
    a.exit_code = std::atoi(std::string(code.substr(0, code.find(':'))).c_str());
    rows.push_back(std::move(a));
  }
  return rows;
}

SlurmPhase slurm_phase(std::string_view state) {
  // squeue(1) and sacct(1), "JOB STATE CODES".
  static const std::set<std::string_view> queued = {"PENDING",     "REQUEUED",      "REQUEUE_HOLD",
                                                    "REQUEUE_FED", "RESV_DEL_HOLD", "SPECIAL_EXIT"};
  static const std::set<std::string_view> running = {"RUNNING",   "CONFIGURING", "COMPLETING",
                                                     "STAGE_OUT", "SUSPENDED",   "STOPPED",
                                                     "SIGNALING", "RESIZING",    "POWER_UP_NODE"};
  static const std::set<std::string_view> ended = {
      "COMPLETED", "FAILED",    "CANCELLED", "TIMEOUT",       "NODE_FAIL",
      "PREEMPTED", "BOOT_FAIL", "DEADLINE",  "OUT_OF_MEMORY", "REVOKED"};
  if (queued.count(state)) return SlurmPhase::queued;
  if (running.count(state)) return SlurmPhase::running;
  if (ended.count(state)) return SlurmPhase::ended;
  return SlurmPhase::unknown;
}

std::optional<RunProgress> parse_run_progress(std::string_view output_tail) {
  std::optional<RunProgress> last;
  for (std::string_view line : split(output_tail, '\n')) {
    line = trim(line);
    if (line.empty() || line.front() != '[') continue;
    const std::string text(line);
    double percent = 0;
    long long step = 0, steps = 0;
    RunProgress p;
    if (std::sscanf(text.c_str(), "[%lf%%] step %lld/%lld t = %lf s wall %lf s ETA %lf s", &percent,
                    &step, &steps, &p.time_s, &p.wall_s, &p.eta_s) == 6) {
      p.step = step;
      p.steps = steps;
      last = p;
    }
  }
  return last;
}

std::optional<StageProgress> parse_stage_progress(std::string_view output_tail) {
  std::optional<StageProgress> last;
  for (std::string_view line : split(output_tail, '\n')) {
    line = trim(line);
    if (line.rfind("[stage ", 0) != 0) continue;
    const std::string text(line);
    char stage[32] = {};
    double percent = 0, elapsed = 0;
    if (std::sscanf(text.c_str(), "[stage %31[a-z_]] %lf %% done, %lf s", stage, &percent,
                    &elapsed) == 3) {
      last = StageProgress{stage, std::clamp(percent / 100.0, 0.0, 1.0), elapsed};
    }
  }
  return last;
}

std::string slurm_batch_script(const std::string& job_id, const std::filesystem::path& dir,
                               const SlurmOptions& o) {
  const std::filesystem::path slurm = dir / ".slurm";
  std::ostringstream s;
  s << "#!/bin/sh\n"
    << "#SBATCH --job-name=" << job_name(job_id) << "\n"
    << "#SBATCH --ntasks=1\n"
    << "#SBATCH --cpus-per-task=" << o.cpus_per_job << "\n"
    << "#SBATCH --chdir=" << dir.string() << "\n"
    << "#SBATCH --output=" << (slurm / "output.txt").string() << "\n"
    << "# GearSPH job " << job_id << ", submitted by gearsph serve --dispatch slurm.\n"
    << "# Threads: the CPUs Slurm allocated to this job.\n"
    << "threads=${SLURM_CPUS_PER_TASK:-${SLURM_CPUS_ON_NODE:-" << o.cpus_per_job << "}}\n"
    << shell_quote(o.gearsph.string()) << " run " << shell_quote((slurm / "job.json").string())
    << " --out " << shell_quote(dir.string()) << " --threads \"$threads\"\n"
    << "status=$?\n"
    << "echo \"$status\" > " << shell_quote((slurm / "exit.tmp").string()) << " && mv "
    << shell_quote((slurm / "exit.tmp").string()) << " " << shell_quote((slurm / "exit").string())
    << "\n"
    << "exit \"$status\"\n";
  return s.str();
}

CommandResult run_command(const std::vector<std::string>& argv, std::chrono::milliseconds timeout) {
  CommandResult r;
  int out[2], err[2];
  if (::pipe2(out, O_CLOEXEC) != 0) return r;
  if (::pipe2(err, O_CLOEXEC) != 0) {
    ::close(out[0]);
    ::close(out[1]);
    return r;
  }
  std::vector<std::string> args = argv;
  std::vector<char*> cargv;
  for (std::string& a : args) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    // Only async-signal-safe calls between fork and exec: other threads of
    // the server may hold locks (malloc, stdio) that the child would wait for.
    sigset_t none;
    sigemptyset(&none);
    ::pthread_sigmask(SIG_SETMASK, &none, nullptr);
    ::dup2(out[1], 1);
    ::dup2(err[1], 2);
    ::execvp(cargv[0], cargv.data());
    static const char kCannotRun[] = "cannot run the command\n";
    [[maybe_unused]] const ssize_t n = ::write(2, kCannotRun, sizeof kCannotRun - 1);
    ::_exit(127);
  }
  ::close(out[1]);
  ::close(err[1]);
  if (pid < 0) {
    ::close(out[0]);
    ::close(err[0]);
    return r;
  }
  const auto deadline = Clock::now() + timeout;
  pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  int open_fds = 2;
  char buf[4096];
  while (open_fds > 0) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) {
      ::kill(pid, SIGKILL);
      r.err += "timed out";
      break;
    }
    if (::poll(fds, 2, static_cast<int>(left)) < 0) break;
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t n = ::read(fds[i].fd, buf, sizeof buf);
      if (n > 0) {
        (i == 0 ? r.out : r.err).append(buf, static_cast<std::size_t>(n));
      } else {
        ::close(fds[i].fd);
        fds[i].fd = -1;
        --open_fds;
      }
    }
  }
  for (const pollfd& f : fds) {
    if (f.fd >= 0) ::close(f.fd);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  r.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

SlurmDispatcher::SlurmDispatcher(JobStore& store, SlurmOptions options)
    : store_(store), options_(std::move(options)) {}

SlurmDispatcher::~SlurmDispatcher() {
  stop();
}

void SlurmDispatcher::start() {
  thread_ = std::thread([this] { loop(); });
}

void SlurmDispatcher::notify() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    poked_ = true;
  }
  wake_.notify_all();
}

bool SlurmDispatcher::cancel(const std::string&) {
  // The job is dismissed in the store; the next pass cancels it with scancel.
  notify();
  return false;
}

void SlurmDispatcher::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void SlurmDispatcher::loop() {
  for (;;) {
    try {
      pass();
    } catch (const std::exception& e) {
      log_line(LogLevel::warning, "gearsph serve: slurm: %s\n", e.what());
    }
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait_for(lock, options_.poll_interval, [this] { return stop_ || poked_; });
    poked_ = false;
    if (stop_) return;
  }
}

void SlurmDispatcher::pass() {
  track();
  submit_queued();
}

void SlurmDispatcher::submit_queued() {
  const std::string placeholder = kSubmitting + options_.name;
  while (auto job = store_.claim_for_dispatch(placeholder)) {
    if (!submit(*job)) return;  // Slurm refused: try again at the next pass
    std::lock_guard<std::mutex> lock(mutex_);
    if (stop_) return;
  }
}

bool SlurmDispatcher::submit(const JobRecord& job) {
  const std::filesystem::path dir = dir_of(job.id);
  const std::filesystem::path slurm = dir / ".slurm";
  CommandResult r;
  try {
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(slurm);
    {
      std::ofstream(slurm / "job.json") << job.job_json;
      std::ofstream(slurm / "job.sh") << slurm_batch_script(job.id, dir, options_);
    }
    std::vector<std::string> argv = {"sbatch", "--parsable"};
    argv.insert(argv.end(), options_.sbatch_args.begin(), options_.sbatch_args.end());
    argv.push_back((slurm / "job.sh").string());
    r = run_command(argv);
  } catch (const std::exception& e) {
    r.err = e.what();
  }
  const auto slurm_id = r.status == 0 ? parse_sbatch_parsable(r.out) : std::nullopt;
  if (!slurm_id) {
    const std::string why = std::string(trim(r.err.empty() ? r.out : r.err));
    log_line(LogLevel::warning, "gearsph serve: slurm: sbatch refused job %s: %s\n", job.id.c_str(),
             why.c_str());
    store_.release_dispatch(job.id, job.dispatch_ref,
                            "queued; sbatch failed (" + why + "), trying again");
    return false;
  }
  const std::string ref = kRefPrefix + *slurm_id;
  if (!store_.set_dispatch(job.id, JobStatus::accepted, job.dispatch_ref, ref,
                           "queued in Slurm as job " + *slurm_id)) {
    // Dismissed while sbatch ran: keep the Slurm job's id so that the next
    // pass cancels it instead of leaving it to run unseen.
    if (!store_.set_dispatch(job.id, JobStatus::dismissed, job.dispatch_ref, ref,
                             "dismissed while it was being submitted to Slurm (job " + *slurm_id +
                                 "); cancelling it")) {
      // Another node took the job over (this one was frozen past
      // kPlaceholderGoneAfterS): its Slurm job is the job's; this one goes.
      const CommandResult c = run_command({"scancel", *slurm_id});
      log_line(LogLevel::warning,
               "gearsph serve: job %s: another node took it over while sbatch ran; the Slurm "
               "job %s made here %s\n",
               job.id.c_str(), slurm_id->c_str(),
               c.status == 0 ? "was cancelled" : "could not be cancelled");
      return true;
    }
  }
  log_line(LogLevel::info, "gearsph serve: job %s submitted to Slurm as job %s\n", job.id.c_str(),
           slurm_id->c_str());
  return true;
}

void SlurmDispatcher::track() {
  const std::vector<JobRecord> jobs = store_.dispatched();
  if (jobs.empty()) return;
  const CommandResult q = run_command(
      {"squeue", "--me", "--noheader", "--states=all", std::string("--format=") + kSqueueFormat});
  if (q.status != 0) {
    throw std::runtime_error("squeue failed: " + std::string(trim(q.err)));
  }
  std::map<std::string, SlurmQueueEntry> by_id, by_name;
  for (const SlurmQueueEntry& e : parse_squeue(q.out)) {
    by_id[e.job_id] = e;
    by_name[e.name] = e;
  }
  for (const JobRecord& job : jobs) {
    const std::string& ref = job.dispatch_ref;
    if (ref.rfind(kSubmitting, 0) == 0) {
      if (ref == kSubmitting + options_.name) continue;  // ours, being submitted
      // Left by a server that stopped during sbatch (its placeholder
      // unchanged for longer than any sbatch takes): adopt the Slurm job if
      // it was made, else queue the job again. Each a compare and set: of
      // several nodes that find it, one acts.
      const auto it = by_name.find(job_name(job.id));
      if (it != by_name.end()) {
        store_.set_dispatch(job.id, job.status, ref, kRefPrefix + it->second.job_id,
                            "queued in Slurm as job " + it->second.job_id, kPlaceholderGoneAfterS);
      } else if (job.status == JobStatus::accepted) {
        store_.release_dispatch(job.id, ref, "queued (its submission to Slurm was interrupted)",
                                kPlaceholderGoneAfterS);
      } else {
        store_.forget_dispatch(job.id);
      }
      continue;
    }
    if (ref.rfind(kRefPrefix, 0) != 0) continue;
    const std::string slurm_id = ref.substr(std::string(kRefPrefix).size());
    const auto it = by_id.find(slurm_id);
    const SlurmPhase phase = it == by_id.end() ? SlurmPhase::ended : slurm_phase(it->second.state);
    const std::string state = it == by_id.end() ? "" : it->second.state;

    if (job.status == JobStatus::dismissed) {
      if (phase != SlurmPhase::ended) {
        const CommandResult c = run_command({"scancel", slurm_id});
        if (c.status != 0) {
          log_line(LogLevel::warning, "gearsph serve: slurm: scancel %s: %s\n", slurm_id.c_str(),
                   std::string(trim(c.err)).c_str());
          continue;
        }
        log_line(LogLevel::info, "gearsph serve: job %s dismissed; Slurm job %s cancelled\n",
                 job.id.c_str(), slurm_id.c_str());
      }
      ProgressUpdate last;
      last.id = job.id;
      last.step = job.step;
      last.simulated_s = job.simulated_s;
      last.wall_s = job.wall_s;
      last.progress = job.progress;
      store_.close_dismissed(job.id,
                             "dismissed; its Slurm job " + slurm_id +
                                 (phase == SlurmPhase::ended ? " had ended" : " was cancelled"),
                             last);
      store_.forget_dispatch(job.id);
      fe_estimates_.erase(job.id);
      // What the run wrote goes with it (a DELETE later removes anything a
      // cancelled run still wrote while it stopped).
      std::error_code ec;
      std::filesystem::remove_all(dir_of(job.id), ec);
      continue;
    }
    if (phase == SlurmPhase::queued) {
      const std::string message = "queued in Slurm as job " + slurm_id +
                                  (it->second.reason.empty() || it->second.reason == "None"
                                       ? std::string()
                                       : " (" + it->second.reason + ")");
      if (job.status == JobStatus::running) {
        // Requeued (scontrol requeue, a node failure, preemption): the run
        // it had started is gone, and Slurm will start it again.
        store_.unstart_dispatched(job.id, ref,
                                  "queued again in Slurm as job " + slurm_id + " (" + state +
                                      (it->second.reason.empty() || it->second.reason == "None"
                                           ? std::string()
                                           : ", " + it->second.reason) +
                                      "); it starts again from the beginning");
      } else if (job.status == JobStatus::accepted && job.message != message &&
                 job.message.rfind("queued again", 0) != 0) {
        store_.set_dispatch(job.id, JobStatus::accepted, ref, ref, message);
      }
      continue;
    }
    if (phase == SlurmPhase::running || phase == SlurmPhase::unknown) {
      if (job.status == JobStatus::accepted) {
        store_.start_dispatched(job.id, ref, "running in Slurm as job " + slurm_id);
      }
      follow_running(job);
      continue;
    }
    conclude(job, slurm_id, state);
  }
}

const FeStageEstimate& SlurmDispatcher::fe_estimate_of(const std::string& id) {
  auto it = fe_estimates_.find(id);
  if (it == fe_estimates_.end()) {
    FeStageEstimate e;
    try {
      e = estimate_fe_stage(store_);
    } catch (const std::exception&) {
      // The store away: the fallback figure will do for an estimate.
    }
    it = fe_estimates_.emplace(id, e).first;
  }
  return it->second;
}

void SlurmDispatcher::follow_running(const JobRecord& job) {
  const std::filesystem::path output = dir_of(job.id) / ".slurm" / "output.txt";
  const std::string tail = tail_of(output, 8192);
  const auto p = parse_run_progress(tail);
  const bool fe = runs_fe_check(nlohmann::json::parse(job.job_json, nullptr, false));
  if (!fe) {
    if (p && p->step != job.step) {
      store_.save_progress(
          {{job.id, p->step, p->time_s, p->wall_s, p->eta_s, percent(p->step, p->steps)}});
    }
    return;
  }
  // The FE stage's clock runs between its reports: saved at every pass.
  ProgressUpdate u{job.id, job.step, job.simulated_s, 0.0, 0.0, 0, "sph", ""};
  if (p) {
    u.step = p->step;
    u.simulated_s = p->time_s;
    u.wall_s = p->wall_s;
    u.eta_s = p->eta_s;
    u.progress = percent(p->step, p->steps);
  }
  const auto stage = parse_stage_progress(tail);
  if (stage && stage->stage == "fe_check") {
    const FeStageNow now{stage->fraction, stage->elapsed_s, seconds_since_written(output),
                         u.wall_s};
    count_fe_stage(u, fe_estimate_of(job.id), &now);
  } else {
    count_fe_stage(u, fe_estimate_of(job.id), nullptr);
  }
  store_.save_progress({u});
}

void SlurmDispatcher::conclude(const JobRecord& job, const std::string& slurm_id,
                               const std::string& state) {
  const std::filesystem::path dir = dir_of(job.id);
  std::optional<int> exit_code;
  {
    const std::string text = std::string(trim(read_text(dir / ".slurm" / "exit")));
    if (all_digits(text)) exit_code = std::atoi(text.c_str());
  }
  std::string ended_as = state;
  if (!exit_code) {
    // Accounting, where it is on, knows how the job ended.
    const CommandResult a = run_command({"sacct", "--noheader", "--parsable2", "--allocations",
                                         "--jobs=" + slurm_id, "--format=JobID,State,ExitCode"});
    if (a.status == 0) {
      for (const SlurmAccounting& row : parse_sacct(a.out)) {
        if (row.job_id == slurm_id) ended_as = row.state;
      }
    }
    // A batch script that ran to its end always leaves its exit status; a
    // shared file system may show it late.
    if (ended_as.empty() || ended_as == "COMPLETED" || ended_as == "FAILED") {
      const auto now = Clock::now();
      const auto first = ended_without_status_.emplace(job.id, now).first->second;
      if (now - first < options_.exit_grace) return;
    }
  }
  ended_without_status_.erase(job.id);

  ProgressUpdate last;
  last.id = job.id;
  last.step = job.step;
  last.simulated_s = job.simulated_s;
  last.wall_s = job.wall_s;
  last.progress = job.progress;
  JobStatus outcome = JobStatus::failed;
  std::string message, fe_sentence;
  const std::string where = " (Slurm job " + slurm_id + ")";
  const auto summary = nlohmann::json::parse(read_text(dir / "summary.json"), nullptr, false);
  if (summary.is_object()) {
    last.step = summary.value("steps", last.step);
    last.wall_s = summary.value("wall_s", last.wall_s);
    last.simulated_s = summary.value("simulated_s", last.simulated_s);
  }
  const double sph_wall_s = last.wall_s;
  if (runs_fe_check(nlohmann::json::parse(job.job_json, nullptr, false))) {
    // The FE stage's record, as the server's own workers make it (worker_pool.cpp).
    const std::string run_status = !exit_code        ? "ended"
                                   : *exit_code == 0 ? "completed"
                                   : *exit_code == 3 ? "diverged"
                                   : *exit_code == 4 ? "cancelled"
                                                     : "failed";
    const FeOutcome fe = fe_outcome(summary.is_object() ? summary : nlohmann::json::object(),
                                    run_status, fe_estimate_of(job.id));
    fe_sentence = "; " + fe.sentence;
    last.wall_s += fe.wall_s;
    last.fe_check_json = fe.document.dump();
  }
  fe_estimates_.erase(job.id);
  if (exit_code && *exit_code == 0) {
    outcome = JobStatus::successful;
    last.progress = 100;
    message = "completed " + std::to_string(last.step) + " steps in " + fixed(sph_wall_s, 2) +
              " s" + fe_sentence + where;
  } else if (exit_code && *exit_code == 3) {
    message = "the run diverged" + where + "; see summary.json";
  } else if (exit_code && *exit_code == 2) {
    message = "the job cannot run" + where + ": gearsph run refused it";
  } else if (exit_code) {
    message = "gearsph run exited with status " + std::to_string(*exit_code) + where;
  } else if (!ended_as.empty()) {
    message = "the Slurm job " + slurm_id + " ended " + ended_as + " before gearsph run finished";
  } else {
    message = "the Slurm job " + slurm_id + " ended without leaving an exit status";
  }
  if (job.status == JobStatus::accepted) store_.start_dispatched(job.id, job.dispatch_ref, message);
  if (store_.finish(job.id, outcome, message, last)) {
    log_line(LogLevel::info, "gearsph serve: job %s %s: %s\n", job.id.c_str(),
             std::string(to_string(outcome)).c_str(), message.c_str());
  }
  store_.forget_dispatch(job.id);
}

}  // namespace gearsph::server
