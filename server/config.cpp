#include "server/config.hpp"

#include "server/job_store.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace gearsph::server {

std::filesystem::path results_dir_of(const ServerConfig& config) {
  return config.results_dir.empty() ? config.data_dir / "jobs" : config.results_dir;
}

bool shared_store(const ServerConfig& config) {
  return !config.store.empty();
}

std::string process_name() {
  char host[256] = {};
  if (::gethostname(host, sizeof host - 1) != 0) std::snprintf(host, sizeof host, "localhost");
  // The random part tells apart processes whose host name and pid agree
  // (containers with host networking, each in its own PID namespace).
  return std::string(host) + ":" + std::to_string(::getpid()) + ":" +
         new_claim_token().substr(0, 8);
}

void resolve_defaults(ServerConfig& config, int cores) {
  cores = std::max(1, cores);
  if (config.workers <= 0 && config.threads_per_job <= 0) {
    config.workers = cores;
    config.threads_per_job = cores;
    config.core_budget = cores;
  } else if (config.workers <= 0) {
    config.workers = std::max(1, cores / config.threads_per_job);
  } else if (config.threads_per_job <= 0) {
    config.threads_per_job = std::max(1, cores / config.workers);
  }
  if (config.web_root.empty()) config.web_root = default_web_root();
}

std::string read_token_file(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error("cannot read the token file " + file.string());
  std::string line;
  std::getline(in, line);
  const auto first = line.find_first_not_of(" \t\r\n");
  const auto last = line.find_last_not_of(" \t\r\n");
  if (first == std::string::npos) {
    throw std::runtime_error("the token file " + file.string() +
                             " holds no token on its first line");
  }
  return line.substr(first, last - first + 1);
}

std::filesystem::path default_web_root() {
  std::error_code ec;
  const std::filesystem::path compiled = GEARSPH_WEB_ROOT;
  if (std::filesystem::is_directory(compiled, ec)) return compiled;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    for (const auto& candidate :
         {exe.parent_path() / "web", exe.parent_path().parent_path() / "web",
          exe.parent_path().parent_path() / "share/gearsph/web"}) {
      if (std::filesystem::is_directory(candidate, ec)) return candidate;
    }
  }
  return {};
}

const char* version() {
  return GEARSPH_VERSION;
}

}  // namespace gearsph::server
