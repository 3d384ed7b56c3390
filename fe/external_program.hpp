#pragma once
// gmsh and CalculiX run as programs, not linked libraries: a crash or a hang
// in either stays outside the calling process (the job service among them),
// and the input files they read are plain text a reviewer can rerun.
//
// The tools are found on PATH, or where GEARSPH_GMSH / GEARSPH_CCX point.
// Each run starts in its own work directory with stdout and stderr in a log
// file, in its own process group with a parent-death signal; it is stopped
// (its whole group: SIGTERM, then SIGKILL) after a timeout or when the
// caller's ProgramStopScope says so.
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace gearsph::fe {

// The FE tools cannot be used on this machine or in this build: the CLI
// answers with exit status 5, the service with 501.
class FeUnavailable : public std::runtime_error {
 public:
  explicit FeUnavailable(const std::string& why) : std::runtime_error("FE unavailable: " + why) {}
};

// A tool ran and failed (exit status, timeout, missing or malformed output);
// the message quotes the end of its log.
class FeFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct FeTools {
  std::filesystem::path gmsh, ccx;
};

// Both tools, or FeUnavailable naming what is missing and how to install it.
FeTools find_fe_tools();
// "" when both tools are found, else the FeUnavailable message.
std::string fe_unavailable_reason();

struct ProgramRun {
  std::filesystem::path program;
  std::vector<std::string> args;
  std::filesystem::path work_dir;
  std::filesystem::path log;                             // stdout and stderr
  std::vector<std::pair<std::string, std::string>> env;  // set for the child only
  double timeout_s = 120.0;
};

struct ProgramResult {
  int exit_status = -1;  // -1 when killed by a signal (or on timeout)
  bool timed_out = false;
  bool stopped = false;
  double wall_s = 0.0;
};

// Stopped on request (ProgramStopScope): a job dismissed, a server stopping.
class ProgramStopped : public FeFailed {
 public:
  using FeFailed::FeFailed;
};

// While in scope on this thread, a running tool is polled against `stop`
// (every 50 ms at most) and stopped within about two seconds once it says so.
class ProgramStopScope {
 public:
  explicit ProgramStopScope(std::function<bool()> stop);
  ~ProgramStopScope();
  ProgramStopScope(const ProgramStopScope&) = delete;
  ProgramStopScope& operator=(const ProgramStopScope&) = delete;

 private:
  std::function<bool()> previous_;
};

// Runs to completion or timeout; throws FeFailed if it cannot be started,
// ProgramStopped when stopped.
ProgramResult run_program(const ProgramRun& run);

// Removes the work directories (WorkDir) under the temporary directory
// named `prefix` whose owning process is gone (a server killed during an
// FE check); returns how many.
int remove_stale_work_dirs(const std::string& prefix);

// The last `max_chars` characters of a text file ("" if unreadable).
std::string file_tail(const std::filesystem::path& file, std::size_t max_chars);

// A fresh directory under the system's temporary directory, removed with
// everything in it when this object goes (unless kept).
class WorkDir {
 public:
  explicit WorkDir(const std::string& prefix);
  ~WorkDir();
  WorkDir(const WorkDir&) = delete;
  WorkDir& operator=(const WorkDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  void keep() { keep_ = true; }

 private:
  std::filesystem::path path_;
  bool keep_ = false;
};

}  // namespace gearsph::fe
