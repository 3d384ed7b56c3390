#pragma once
// Support for the server tests: the real `gearsph serve` process on a free
// port with its own temporary data directory, talked to over real HTTP.
#include <fcntl.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "server/http_client.hpp"

namespace gearsph::server::testing {

namespace fs = std::filesystem;
using nlohmann::json;
using Clock = std::chrono::steady_clock;

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// A job that runs in a fraction of a second; `end_s` makes it longer.
inline json tiny_job(double end_s = 0.005) {
  return {{"scene", {{"type", "plate"}, {"length_m", 0.1}, {"thickness_m", 0.01}}},
          {"discretization", {{"spacing_m", 0.002}}},
          {"time", {{"end_s", end_s}}}};
}

class TempDir {
 public:
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "gearsph-server-test-XXXXXX").string();
    if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

class ServerProcess {
 public:
  explicit ServerProcess(std::vector<std::string> args = {}) : args_(std::move(args)) { start(); }
  ~ServerProcess() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      int status = 0;
      ::waitpid(pid_, &status, 0);
    }
    // Under the sanitizers, what they found in the server ends up in its stderr.
    for (int i = 0; i < starts_; ++i) {
      const std::string err = slurp(dir_.path() / ("stderr." + std::to_string(i)));
      for (const char* finding : {"ERROR: AddressSanitizer", "ERROR: LeakSanitizer",
                                  "runtime error:", "WARNING: ThreadSanitizer"}) {
        EXPECT_EQ(err.find(finding), std::string::npos) << err;
      }
    }
  }
  ServerProcess(const ServerProcess&) = delete;
  ServerProcess& operator=(const ServerProcess&) = delete;

  // Starts `gearsph serve --port 0 --data DIR ARGS...` and waits until it listens.
  void start() {
    if (pid_ > 0) throw std::runtime_error("the server is running already");
    const fs::path out = dir_.path() / ("stdout." + std::to_string(starts_));
    const fs::path err = dir_.path() / ("stderr." + std::to_string(starts_));
    ++starts_;
    std::vector<std::string> argv = {GEARSPH_BINARY, "serve",        "--port", "0",
                                     "--data",       data().string()};
    argv.insert(argv.end(), args_.begin(), args_.end());
    std::vector<char*> cargv;
    for (std::string& a : argv) cargv.push_back(a.data());
    cargv.push_back(nullptr);
    pid_ = ::fork();
    if (pid_ < 0) throw std::runtime_error("fork failed");
    if (pid_ == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGKILL);  // no orphaned server if the test process dies
      const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      ::dup2(o, 1);
      ::dup2(e, 2);
      ::execv(cargv[0], cargv.data());
      ::_exit(127);
    }
    last_stdout_ = out;
    last_stderr_ = err;
    const auto deadline = Clock::now() + std::chrono::seconds(60);
    const std::string marker = "listening on http://";
    while (Clock::now() < deadline) {
      const std::string text = slurp(out);
      const auto at = text.find(marker);
      if (at != std::string::npos) {
        const std::string rest = text.substr(at + marker.size());
        const auto colon = rest.find(':');
        const auto end = rest.find_first_of(" \n", colon);
        if (colon != std::string::npos && end != std::string::npos) {
          host_ = rest.substr(0, colon);
          port_ = rest.substr(colon + 1, end - colon - 1);
          return;
        }
      }
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        throw std::runtime_error("gearsph serve exited at start-up:\n" + slurp(err));
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    throw std::runtime_error("gearsph serve did not start listening:\n" + slurp(err));
  }

  // Sends `sig` and waits for the exit; returns the exit code (128 + signal if killed).
  int stop(int sig, std::chrono::seconds timeout = std::chrono::seconds(30)) {
    if (pid_ <= 0) return -1;
    ::kill(pid_, sig);
    const auto deadline = Clock::now() + timeout;
    int status = 0;
    while (Clock::now() < deadline) {
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return -2;  // did not stop in time
  }

  bool running() const { return pid_ > 0; }
  pid_t pid() const { return pid_; }
  const std::string& host() const { return host_; }
  const std::string& port() const { return port_; }
  std::string url() const { return "http://" + host_ + ":" + port_; }
  fs::path data() const { return dir_.path() / "data"; }
  fs::path dir() const { return dir_.path(); }
  std::string log() const { return slurp(last_stdout_) + slurp(last_stderr_); }
  HttpClient client(std::chrono::milliseconds timeout = std::chrono::seconds(30)) const {
    return HttpClient(host_, port_, timeout);
  }

 private:
  TempDir dir_;
  std::vector<std::string> args_;
  pid_t pid_ = -1;
  int starts_ = 0;
  std::string host_, port_;
  fs::path last_stdout_, last_stderr_;
};

inline bool is_final(const std::string& s) {
  return s == "successful" || s == "failed" || s == "dismissed";
}

// Polls GET /jobs/{id} until `done` holds for its status document.
template <class Pred>
json wait_for(HttpClient& c, const std::string& id, Pred done,
              std::chrono::seconds timeout = std::chrono::seconds(120)) {
  const auto deadline = Clock::now() + timeout;
  json last;
  while (Clock::now() < deadline) {
    const ClientResponse r = c.get("/jobs/" + id);
    if (r.status == 200) {
      last = r.json();
      if (done(last)) return last;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  ADD_FAILURE() << "timed out waiting for job " << id << "; last status: " << last.dump();
  return last;
}

inline json wait_final(HttpClient& c, const std::string& id,
                       std::chrono::seconds timeout = std::chrono::seconds(120)) {
  return wait_for(
      c, id, [](const json& s) { return is_final(s.value("status", std::string())); }, timeout);
}

inline std::string submit(HttpClient& c, const json& job, const HttpClient::Headers& h = {}) {
  const ClientResponse r = c.post_json("/jobs", job.dump(), h);
  if (r.status != 201 && r.status != 200) {
    ADD_FAILURE() << "submit answered " << r.status << ": " << r.body;
    return {};
  }
  return r.json().at("jobID").get<std::string>();
}

// Reads the job store directly (as an operator would with sqlite3).
class Database {
 public:
  explicit Database(const fs::path& file) {
    if (sqlite3_open_v2(file.c_str(), &db_, SQLITE_OPEN_READONLY, nullptr) != SQLITE_OK) {
      throw std::runtime_error("cannot open " + file.string());
    }
    sqlite3_busy_timeout(db_, 5000);
  }
  ~Database() { sqlite3_close(db_); }
  Database(const Database&) = delete;
  Database& operator=(const Database&) = delete;

  std::vector<std::vector<std::string>> query(const std::string& sql) {
    sqlite3_stmt* s = nullptr;
    if (sqlite3_prepare_v2(db_, sql.c_str(), -1, &s, nullptr) != SQLITE_OK) {
      throw std::runtime_error(sqlite3_errmsg(db_));
    }
    std::vector<std::vector<std::string>> rows;
    while (sqlite3_step(s) == SQLITE_ROW) {
      std::vector<std::string> row;
      for (int i = 0; i < sqlite3_column_count(s); ++i) {
        const auto* t = sqlite3_column_text(s, i);
        row.emplace_back(t ? reinterpret_cast<const char*>(t) : "");
      }
      rows.push_back(std::move(row));
    }
    sqlite3_finalize(s);
    return rows;
  }

 private:
  sqlite3* db_ = nullptr;
};

// The store's invariants: the file is sound and every job is in a state of
// the life cycle, with the timestamps that state implies.
inline void expect_consistent_store(const fs::path& data) {
  Database db(data / "gearsph.db");
  EXPECT_EQ(db.query("PRAGMA integrity_check").at(0).at(0), "ok");
  EXPECT_TRUE(db.query("PRAGMA foreign_key_check").empty());
  EXPECT_EQ(db.query("SELECT COUNT(*) FROM jobs WHERE status NOT IN "
                     "('accepted','running','successful','failed','dismissed')")
                .at(0)
                .at(0),
            "0");
  EXPECT_EQ(db.query("SELECT COUNT(*) FROM jobs WHERE progress < 0 OR progress > 100 OR "
                     "attempts < 0 OR created IS NULL OR (status = 'running' AND started IS NULL) "
                     "OR (status IN ('successful','failed') AND finished IS NULL)")
                .at(0)
                .at(0),
            "0");
  // A successful job's results are published (jobs/ID) or, if the server
  // stopped between recording the finish and the rename, still in its
  // claim's attempt directory, which the API publishes when first asked
  // (server/attempt_dirs.hpp).
  for (const auto& row :
       db.query("SELECT id, COALESCE(claim, '') FROM jobs WHERE status = 'successful'")) {
    const bool published = fs::exists(data / "jobs" / row[0] / "summary.json");
    const bool pending = !row[1].empty() && fs::exists(data / "jobs" / ".attempts" /
                                                       (row[0] + "." + row[1]) / "summary.json");
    EXPECT_TRUE(published || pending) << row[0];
  }
}

}  // namespace gearsph::server::testing
