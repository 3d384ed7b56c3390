#pragma once
// Support for the scale-out tests: real engines (PostgreSQL, single-node
// Slurm) started and stopped through tests/scaleout/*.sh in a temporary
// directory, and `gearsph worker` processes whose logs say which jobs they
// ran. The API process is the ServerProcess of the server tests.
#include <algorithm>
#include <cstdio>
#include <map>
#include <regex>

#include "server/postgres.hpp"
#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {

// Runs a command through /bin/sh; returns its exit status and output.
inline int shell(const std::string& command, std::string* output = nullptr) {
  std::string text;
  FILE* p = ::popen((command + " 2>&1").c_str(), "r");
  if (!p) return -1;
  char buf[4096];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) text.append(buf, n);
  const int status = ::pclose(p);
  if (output) *output = text;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline std::string script(const std::string& name) {
  return std::string(GEARSPH_SOURCE_DIR) + "/tests/scaleout/" + name;
}

// An engine started by `script start DIR` and stopped by `script stop DIR`.
class Engine {
 public:
  Engine(std::string script_path, std::vector<std::string> extra = {})
      : script_(std::move(script_path)) {
    // The script's watchdog stops the engine should this process die first.
    std::string command = "GEARSPH_ENGINE_OWNER=" + std::to_string(::getpid()) + " " + script_ +
                          " start " + dir_.path().string();
    for (const std::string& a : extra) command += " " + a;
    status_ = shell(command, &output_);
  }
  ~Engine() { shell(script_ + " stop " + dir_.path().string()); }
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;

  bool started() const { return status_ == 0; }
  int status() const { return status_; }
  // The last line the start printed (the store URI, SLURM_CONF=...).
  std::string last_line() const {
    std::string s = output_;
    while (!s.empty() && s.back() == '\n') s.pop_back();
    return s.substr(s.find_last_of('\n') + 1);
  }
  const std::string& output() const { return output_; }
  int run(const std::string& command) {
    return shell(script_ + " " + command + " " + dir_.path().string());
  }
  const fs::path& dir() const { return dir_.path(); }

 private:
  TempDir dir_;
  std::string script_;
  int status_ = -1;
  std::string output_;
};

// `gearsph worker ARGS...`, its output in files of its own.
class WorkerProcess {
 public:
  // `prefix`: a command that runs the worker (e.g. unshare into a PID
  // namespace of its own, as a container would).
  WorkerProcess(std::vector<std::string> args, const fs::path& logs, int number,
                std::vector<std::string> prefix = {})
      : out_(logs / ("worker" + std::to_string(number) + ".out")),
        err_(logs / ("worker" + std::to_string(number) + ".err")) {
    std::vector<std::string> argv = prefix;
    argv.push_back(GEARSPH_BINARY);
    argv.push_back("worker");
    argv.insert(argv.end(), args.begin(), args.end());
    std::vector<char*> cargv;
    for (std::string& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);
      const int o = ::open(out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = ::open(err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(o, 1);
      ::dup2(e, 2);
      ::execvp(cargv[0], cargv.data());
      ::_exit(127);
    }
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    while (Clock::now() < deadline) {
      if (slurp(out_).find(" ready (") != std::string::npos) return;
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        throw std::runtime_error("gearsph worker exited at start-up:\n" + slurp(err_));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    throw std::runtime_error("gearsph worker did not get ready:\n" + slurp(err_));
  }
  ~WorkerProcess() { stop(SIGKILL); }
  WorkerProcess(const WorkerProcess&) = delete;
  WorkerProcess& operator=(const WorkerProcess&) = delete;

  int stop(int sig) {
    if (pid_ <= 0) return -1;
    ::kill(pid_, sig);
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  }
  bool alive() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  // Its name in the store: "host:pid".
  std::string name() const {
    const std::string out = slurp(out_);
    const std::string marker = "gearsph worker: ";
    const auto at = out.find(marker);
    if (at == std::string::npos) return {};
    const auto end = out.find(' ', at + marker.size());
    return out.substr(at + marker.size(), end - at - marker.size());
  }
  std::string log() const { return slurp(err_); }

  // Job ids this worker started ("job ID running") and finished ("job ID successful|failed").
  std::vector<std::string> started() const { return ids_with(" running ("); }
  std::vector<std::string> finished() const {
    auto ok = ids_with(" successful: ");
    auto failed = ids_with(" failed: ");
    ok.insert(ok.end(), failed.begin(), failed.end());
    return ok;
  }

 private:
  std::vector<std::string> ids_with(const std::string& after) const {
    std::vector<std::string> ids;
    std::istringstream in(log());
    std::string line;
    while (std::getline(in, line)) {
      const auto job = line.find(": job ");
      if (job == std::string::npos) continue;
      const std::string id = line.substr(job + 6, 36);
      if (line.compare(job + 6 + 36, after.size(), after) == 0) ids.push_back(id);
    }
    return ids;
  }

  fs::path out_, err_;
  pid_t pid_ = -1;
};

// Reads the PostgreSQL job store directly, as an operator would with psql.
class PgDatabase {
 public:
  explicit PgDatabase(const std::string& uri) : c_(uri) {}
  std::vector<std::vector<std::string>> query(const std::string& sql) {
    const auto r = c_.exec(sql);
    std::vector<std::vector<std::string>> rows;
    for (int i = 0; i < r.rows(); ++i) {
      std::vector<std::string> row;
      for (int j = 0; j < r.columns(); ++j) row.push_back(r.text(i, j));
      rows.push_back(std::move(row));
    }
    return rows;
  }
  std::string value(const std::string& sql) {
    const auto r = c_.exec(sql);
    return r.rows() > 0 ? r.text(0, 0) : std::string();
  }

 private:
  postgres::Connection c_;
};

inline std::map<std::string, int> count(const std::vector<std::string>& ids) {
  std::map<std::string, int> n;
  for (const std::string& id : ids) ++n[id];
  return n;
}

}  // namespace gearsph::server::testing
