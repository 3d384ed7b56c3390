#include "fe/external_program.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <thread>

extern char** environ;

namespace gearsph::fe {

namespace {

// A program named by an environment variable (a path), else the first
// executable of that name on PATH; empty if there is none.
std::filesystem::path locate(const char* name, const char* override_var, std::string& why) {
  if (const char* given = std::getenv(override_var); given && *given) {
    if (::access(given, X_OK) == 0 && std::filesystem::is_regular_file(given)) return given;
    why = std::string(override_var) + "=" + given + " is not an executable file";
    return {};
  }
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/local/bin:/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / name;
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0) {
      return candidate;
    }
  }
  why = std::string(name) + " is not on PATH";
  return {};
}

// Asked while a tool runs on this thread (ProgramStopScope).
thread_local std::function<bool()> thread_stop;

// SIGTERM to the tool's group, then SIGKILL if it is still there after
// kStopGrace: gmsh and ccx write nothing worth waiting longer for.
constexpr auto kStopGrace = std::chrono::seconds(2);

void stop_group(pid_t pid, int& status) {
  ::kill(-pid, SIGTERM);
  const auto give_up = std::chrono::steady_clock::now() + kStopGrace;
  while (std::chrono::steady_clock::now() < give_up) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      ::kill(-pid, SIGKILL);  // anything it left behind in its group
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ::kill(-pid, SIGKILL);
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
}

// fork + exec rather than posix_spawn, for the parent-death signal: if the
// thread that started the tool dies (the server killed with SIGKILL, say),
// the kernel kills the tool (prctl(2), PR_SET_PDEATHSIG), so no ccx is left
// running under PID 1. Between fork and exec the child calls only
// async-signal-safe functions (signal-safety(7)), as a multi-threaded
// parent requires; exec's errno comes back through a close-on-exec pipe.
pid_t spawn_child(const std::string& program, char* const* argv, char* const* envp,
                  const std::string& dir, const std::string& log) {
  int report[2];
  if (::pipe2(report, O_CLOEXEC) != 0) {
    throw FeFailed("cannot start " + program + ": " + std::strerror(errno));
  }
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) {
    const int e = errno;
    ::close(report[0]);
    ::close(report[1]);
    throw FeFailed("cannot start " + program + ": " + std::strerror(e));
  }
  if (pid == 0) {
    // Its own process group, so that a timeout or a stop ends whatever it
    // started; default signal handling (the service ignores SIGPIPE), no mask.
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);  // the parent died before prctl
    for (int sig : {SIGPIPE, SIGINT, SIGTERM, SIGHUP}) ::signal(sig, SIG_DFL);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    int err = 0;
    const int in = ::open("/dev/null", O_RDONLY);
    const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || out < 0 || ::chdir(dir.c_str()) != 0 || ::dup2(in, 0) < 0 || ::dup2(out, 1) < 0 ||
        ::dup2(out, 2) < 0) {
      err = errno;
    } else {
      ::execve(program.c_str(), argv, envp);
      err = errno;
    }
    [[maybe_unused]] const ssize_t n = ::write(report[1], &err, sizeof err);
    ::_exit(127);
  }
  ::close(report[1]);
  int err = 0;
  ssize_t n = 0;
  while ((n = ::read(report[0], &err, sizeof err)) < 0 && errno == EINTR) {
  }
  ::close(report[0]);
  if (n == sizeof err) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    throw FeFailed("cannot start " + program + ": " + std::strerror(err));
  }
  return pid;
}

}  // namespace

FeTools find_fe_tools() {
  FeTools tools;
  std::string why_gmsh, why_ccx;
  tools.gmsh = locate("gmsh", "GEARSPH_GMSH", why_gmsh);
  tools.ccx = locate("ccx", "GEARSPH_CCX", why_ccx);
  std::string why;
  if (tools.gmsh.empty()) why = why_gmsh;
  if (tools.ccx.empty()) why += (why.empty() ? "" : "; ") + why_ccx;
  if (!why.empty()) {
    throw FeUnavailable(why +
                        " (the finite-element check meshes with gmsh and solves with CalculiX: on "
                        "Debian, apt-get install gmsh calculix-ccx)");
  }
  return tools;
}

std::string fe_unavailable_reason() {
  try {
    find_fe_tools();
    return "";
  } catch (const FeUnavailable& e) {
    return e.what();
  }
}

ProgramResult run_program(const ProgramRun& run) {
  using Clock = std::chrono::steady_clock;
  // Everything the child needs is built before it is started.
  std::vector<std::string> argv_text{run.program.string()};
  argv_text.insert(argv_text.end(), run.args.begin(), run.args.end());
  std::vector<char*> argv;
  for (std::string& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::map<std::string, std::string> env_map;
  for (char** e = environ; e && *e; ++e) {
    const std::string kv = *e;
    const auto eq = kv.find('=');
    if (eq != std::string::npos) env_map[kv.substr(0, eq)] = kv.substr(eq + 1);
  }
  for (const auto& [k, v] : run.env) env_map[k] = v;
  std::vector<std::string> env_text;
  for (const auto& [k, v] : env_map) env_text.push_back(k + "=" + v);
  std::vector<char*> envp;
  for (std::string& e : env_text) envp.push_back(e.data());
  envp.push_back(nullptr);

  const std::string dir = std::filesystem::absolute(run.work_dir).string();
  const std::string log = std::filesystem::absolute(run.log).string();
  const auto start = Clock::now();
  const pid_t pid = spawn_child(run.program.string(), argv.data(), envp.data(), dir, log);
  ProgramResult result;
  const auto deadline = start + std::chrono::duration<double>(run.timeout_s);
  int status = 0;
  auto pause = std::chrono::milliseconds(2);
  for (;;) {
    const pid_t done = ::waitpid(pid, &status, WNOHANG);
    if (done == pid) break;
    if (done < 0 && errno != EINTR) {
      status = -1;
      break;
    }
    const bool stop = thread_stop && thread_stop();
    if (stop || Clock::now() >= deadline) {
      // The whole group: whatever the tool started goes with it.
      stop_group(pid, status);
      result.timed_out = !stop;
      result.stopped = stop;
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
  result.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  result.exit_status = !result.timed_out && !result.stopped && status >= 0 && WIFEXITED(status)
                           ? WEXITSTATUS(status)
                           : -1;
  if (result.stopped) throw ProgramStopped(run.program.filename().string() + " was stopped");
  return result;
}

ProgramStopScope::ProgramStopScope(std::function<bool()> stop) : previous_(std::move(thread_stop)) {
  thread_stop = std::move(stop);
}

ProgramStopScope::~ProgramStopScope() {
  thread_stop = std::move(previous_);
}

std::string file_tail(const std::filesystem::path& file, std::size_t max_chars) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return "";
  std::ostringstream s;
  s << in.rdbuf();
  const std::string text = s.str();
  return text.size() > max_chars ? text.substr(text.size() - max_chars) : text;
}

WorkDir::WorkDir(const std::string& prefix) {
  // The owner's process id in the name: remove_stale_work_dirs knows whose it is.
  std::string pattern =
      (std::filesystem::temp_directory_path() / (prefix + std::to_string(::getpid()) + "-XXXXXX"))
          .string();
  if (!::mkdtemp(pattern.data())) {
    throw FeFailed("cannot create a work directory " + pattern + ": " + std::strerror(errno));
  }
  path_ = pattern;
}

WorkDir::~WorkDir() {
  if (keep_) return;
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

}  // namespace gearsph::fe

namespace gearsph::fe {

int remove_stale_work_dirs(const std::string& prefix) {
  int removed = 0;
  std::error_code ec;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::filesystem::temp_directory_path(), ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !entry.is_directory(ec)) continue;
    const std::string rest = name.substr(prefix.size());
    const auto dash = rest.find('-');
    if (dash == std::string::npos || dash == 0) continue;
    pid_t owner = 0;
    try {
      owner = static_cast<pid_t>(std::stol(rest.substr(0, dash)));
    } catch (const std::exception&) {
      continue;
    }
    // Alive (or another user's: EPERM) keeps its folder.
    if (owner <= 0 || ::kill(owner, 0) == 0 || errno != ESRCH) continue;
    std::error_code rm;
    std::filesystem::remove_all(entry.path(), rm);
    removed += rm ? 0 : 1;
  }
  return removed;
}

}  // namespace gearsph::fe
