// gearsph serve: the job service (HTTP API, job store, worker pool).
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "apps/gearsph/cli.hpp"
#include "apps/gearsph/serve_images.hpp"
#include "server/client_identity.hpp"
#include "server/log.hpp"
#include "server/router.hpp"
#ifdef GEARSPH_WITH_FE
#include "fe/external_program.hpp"
#endif
#include "server/server.hpp"
#include "server/store_location.hpp"

namespace gearsph::cli {

namespace {

// A positive number of seconds, up to a day.
std::chrono::milliseconds seconds_option(Args& args, const std::string& name,
                                         std::chrono::milliseconds fallback) {
  const double s = args.seconds(name, -1.0, {0.0, true, 86400.0, "> 0"});
  return s < 0 ? fallback : std::chrono::milliseconds(static_cast<long long>(s * 1000.0));
}

double number_option(Args& args, const std::string& name, double fallback) {
  const auto v = args.option(name);
  if (!v) return fallback;
  try {
    std::size_t used = 0;
    const double x = std::stod(*v, &used);
    if (used != v->size() || !(x > 0)) throw std::invalid_argument("");
    return x;
  } catch (const std::exception&) {
    throw std::invalid_argument("--" + name + " takes a positive number, not '" + *v + "'");
  }
}

}  // namespace

int cmd_serve(Args& args) {
  server::ServerConfig c;
  const int port = args.integer("port", c.port);
  if (port < 0 || port > 65535) throw std::invalid_argument("--port is 0 to 65535");
  c.port = static_cast<unsigned short>(port);
  if (auto v = args.option("bind")) c.bind = *v;
  if (auto v = args.option("data")) c.data_dir = *v;
  {
    std::vector<std::string> warnings;
    c.store = server::store_from_options(args.option("store"), args.option("store-file"),
                                         std::getenv("GEARSPH_STORE"), warnings);
    for (const std::string& w : warnings)
      server::log_line(server::LogLevel::warning, "gearsph serve: %s\n", w.c_str());
    if (!c.store.empty()) server::parse_store_location(c.store);  // refused here, before anything
  }
  if (auto v = args.option("results")) c.results_dir = *v;
  c.local_workers = !args.flag("no-local-workers");
  if (auto v = args.option("dispatch")) c.dispatch = *v;
  if (c.dispatch != "local" && c.dispatch != "slurm") {
    throw std::invalid_argument("--dispatch is local or slurm, not '" + c.dispatch + "'");
  }
  if (c.dispatch == "slurm" && !c.local_workers) {
    throw std::invalid_argument("--no-local-workers and --dispatch slurm exclude each other");
  }
  c.lease_s = number_option(args, "lease", c.lease_s);
  if (auto v = args.option("retention-days")) {
    try {
      std::size_t used = 0;
      const double days = std::stod(*v, &used);
      if (used != v->size() || !(days > 0) || days > 36500) throw std::invalid_argument("");
      c.retention_s = days * 86400;
    } catch (const std::exception&) {
      throw std::invalid_argument("--retention-days takes a number of days (> 0), not '" + *v +
                                  "'");
    }
  }
  c.job_grace =
      std::chrono::milliseconds(static_cast<long long>(1000 * args.grace_seconds("job-grace")));
  while (auto v = args.option("sbatch-arg")) c.sbatch_args.push_back(*v);
  if (auto v = args.option("slurm-gearsph")) c.gearsph_executable = *v;
  c.workers = args.integer("workers", 0);
  c.threads_per_job = args.integer("threads-per-job", 0);
  if (c.workers < 0 || c.threads_per_job < 0) {
    throw std::invalid_argument("--workers and --threads-per-job are positive");
  }
  if (auto v = args.option("token-file")) c.token = server::read_token_file(*v);
  if (auto v = args.option("cors-origin")) c.cors_origin = *v;
  while (auto v = args.option("allowed-host")) {
    if (*v != "*" && !server::parse_host(*v)) {
      throw std::invalid_argument("--allowed-host takes a host name, name:port or *, not '" + *v +
                                  "'");
    }
    c.allowed_hosts.push_back(*v);
  }
  while (auto v = args.option("trusted-proxy")) {
    if (!server::is_ip_address(*v)) {
      throw std::invalid_argument(
          "--trusted-proxy takes the IP address of a proxy in front, not '" + *v + "'");
    }
    c.trusted_proxies.push_back(*v);
  }
  if (auto v = args.option("web")) c.web_root = *v;
  c.max_attempts = args.integer("max-attempts", c.max_attempts);
  if (c.max_attempts < 1) throw std::invalid_argument("--max-attempts is 1 or more");

  server::Limits& l = c.limits;
  l.max_body_bytes = static_cast<std::uint64_t>(
      number_option(args, "max-body-bytes", static_cast<double>(l.max_body_bytes)));
  l.max_particles = static_cast<std::int64_t>(
      number_option(args, "max-particles", static_cast<double>(l.max_particles)));
  l.max_steps =
      static_cast<std::int64_t>(number_option(args, "max-steps", static_cast<double>(l.max_steps)));
  l.max_particle_steps = number_option(args, "max-particle-steps", l.max_particle_steps);
  l.max_disk_bytes = static_cast<std::uint64_t>(
      number_option(args, "max-disk-gb", static_cast<double>(l.max_disk_bytes) / 1e9) * 1e9);
  l.max_study_jobs = static_cast<std::int64_t>(
      number_option(args, "max-study-jobs", static_cast<double>(l.max_study_jobs)));
  l.max_connections = args.integer("max-connections", l.max_connections);
  l.max_queued = static_cast<std::int64_t>(
      number_option(args, "max-queued", static_cast<double>(l.max_queued)));
  l.max_queued_per_client = static_cast<std::int64_t>(
      number_option(args, "max-queued-per-client", static_cast<double>(l.max_queued_per_client)));
  l.max_built_particles = static_cast<std::int64_t>(
      number_option(args, "build-budget", static_cast<double>(l.max_built_particles)));
  if (auto v = args.option("image-cache-mb")) {
    std::size_t used = 0;
    double mb = -1;
    try {
      mb = std::stod(*v, &used);
    } catch (const std::exception&) {
    }
    if (used != v->size() || !(mb >= 0) || mb > 1e6) {
      throw std::invalid_argument("--image-cache-mb takes megabytes (0 or more), not '" + *v + "'");
    }
    c.image_cache_bytes = static_cast<std::uint64_t>(mb * 1e6);
  }

  server::Timeouts& t = c.timeouts;
  t.header = seconds_option(args, "header-timeout", t.header);
  t.body = seconds_option(args, "body-timeout", t.body);
  t.idle = seconds_option(args, "idle-timeout", t.idle);
  t.write = seconds_option(args, "write-timeout", t.write);
  t.sse_keepalive = seconds_option(args, "keepalive", t.sse_keepalive);
  t.build = seconds_option(args, "build-timeout", t.build);
  if (!args.positional().empty()) throw std::invalid_argument("serve takes no file arguments");

  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  server::resolve_defaults(c, cores);
  if (c.core_budget == 0 && c.workers * c.threads_per_job > cores) {
    server::log_line(server::LogLevel::warning,
                     "gearsph serve: %d workers x %d threads = %d threads on %d cores; jobs "
                     "will compete for the cores\n",
                     c.workers, c.threads_per_job, c.workers * c.threads_per_job, cores);
  }
  // Without this, writing to a client that left would end the process.
  std::signal(SIGPIPE, SIG_IGN);

  // Images of results (empty, so 501, in a build without the renderer).
  c.image_provider = results_image_provider();
#ifdef GEARSPH_WITH_FE
  // Jobs asking for the FE check are taken only where gmsh and ccx are.
  c.fe_check_unavailable = [] { return fe::fe_unavailable_reason(); };
  // FE work directories of servers that died during a check.
  if (const int stale = fe::remove_stale_work_dirs("gearsph-fe-")) {
    std::fprintf(stderr, "gearsph serve: removed %d FE work folder(s) of stopped processes\n",
                 stale);
  }
#endif
  if (!c.local_workers) c.workers = 0;
  server::Server s(c);
  const std::string runs =
      c.dispatch == "slurm"
          ? "jobs go to Slurm, " + std::to_string(c.threads_per_job) + " CPUs each"
      : c.local_workers && c.core_budget > 0
          ? "jobs share " + std::to_string(c.core_budget) + " cores, threads by each job's size"
      : c.local_workers ? std::to_string(c.workers) + (c.workers == 1 ? " worker" : " workers") +
                              " x " + std::to_string(c.threads_per_job) +
                              (c.threads_per_job == 1 ? " thread" : " threads")
                        : "no local workers";
  std::printf("gearsph serve: listening on http://%s:%u (data %s, %s%s%s%s)\n", c.bind.c_str(),
              static_cast<unsigned>(s.port()),
              c.store.empty() ? c.data_dir.string().c_str() : "in a shared store", runs.c_str(),
              c.token.empty() ? "" : ", token required",
              c.web_root.empty() ? "; no dashboard found" : "; dashboard ",
              c.web_root.string().c_str());
  std::fflush(stdout);
  s.run();
  return 0;
}

}  // namespace gearsph::cli
