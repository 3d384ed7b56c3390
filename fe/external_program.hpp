#pragma once
// gmsh and CalculiX run as programs, not linked libraries: a crash or a hang
// in either stays outside the calling process (the job service among them),
// and the input files they read are plain text a reviewer can rerun.
//
// The tools are found on PATH, or where GEARSPH_GMSH / GEARSPH_CCX point.
// Each run starts in its own work directory with stdout and stderr in a log
// file, and is killed (its whole process group) after a timeout. Started
// with posix_spawn, which is safe from a multi-threaded process.
#include <filesystem>
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
  double wall_s = 0.0;
};

// Runs to completion or timeout; throws FeFailed if it cannot be started.
ProgramResult run_program(const ProgramRun& run);

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
