#include "fe/external_program.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <stdlib.h>
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
  posix_spawn_file_actions_t actions;
  posix_spawnattr_t attr;
  posix_spawn_file_actions_init(&actions);
  posix_spawnattr_init(&attr);
  posix_spawn_file_actions_addchdir_np(&actions, dir.c_str());
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  // Its own process group, so that a timeout stops whatever it started;
  // default signal handling (the service ignores SIGPIPE) and no mask.
  sigset_t none, defaults;
  sigemptyset(&none);
  sigemptyset(&defaults);
  for (int s : {SIGPIPE, SIGINT, SIGTERM, SIGHUP}) sigaddset(&defaults, s);
  posix_spawnattr_setsigmask(&attr, &none);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setpgroup(&attr, 0);
  posix_spawnattr_setflags(&attr,
                           POSIX_SPAWN_SETPGROUP | POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF);
  pid_t pid = 0;
  const auto start = Clock::now();
  const int rc = posix_spawn(&pid, run.program.c_str(), &actions, &attr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  posix_spawnattr_destroy(&attr);
  if (rc != 0) {
    throw FeFailed("cannot start " + run.program.string() + ": " + std::strerror(rc));
  }

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
    if (Clock::now() >= deadline) {
      ::kill(-pid, SIGKILL);
      while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      result.timed_out = true;
      break;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::milliseconds(50));
  }
  result.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  result.exit_status =
      !result.timed_out && status >= 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
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
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "XXXXXX")).string();
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
