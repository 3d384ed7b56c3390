// gearsph worker: runs jobs from a shared job store on this machine, into a
// results directory every node (and the API) can read. As many worker
// processes as there are machines (or cores) may share one store; each claims
// the oldest queued job, holds it under a lease its heartbeat renews, and
// records the outcome. SIGTERM / SIGINT: running jobs stop at their next
// check and go back to the queue.
#include <signal.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <thread>

#include "apps/gearsph/cli.hpp"
#include "server/config.hpp"
#include "server/event_hub.hpp"
#include "server/job_store.hpp"
#include "server/log.hpp"
#include "server/open_job_store.hpp"
#include "server/store_location.hpp"
#include "server/worker_pool.hpp"

namespace gearsph::cli {

namespace {

// A positive number of seconds, up to a day.
constexpr SecondsRange kPositiveSeconds{0.0, true, 86400.0, "> 0"};

}  // namespace

int cmd_worker(Args& args) {
  std::vector<std::string> warnings;
  const std::string store_location = server::store_from_options(
      args.option("store"), args.option("store-file"), std::getenv("GEARSPH_STORE"), warnings);
  const auto results = args.option("results");
  if (store_location.empty() || !results) {
    throw std::invalid_argument(
        "usage: gearsph worker --store URL|--store-file FILE --results DIR (or the store in "
        "GEARSPH_STORE)");
  }
  for (const std::string& w : warnings) {
    server::log_line(server::LogLevel::warning, "gearsph worker: %s\n", w.c_str());
  }
  server::parse_store_location(store_location);  // refused here, before anything
  server::WorkerPoolOptions o;
  o.workers = args.integer("workers", 1);
  o.threads_per_job = args.integer("threads-per-job", 0);
  o.max_attempts = args.integer("max-attempts", o.max_attempts);
  const double lease_s = args.seconds("lease", 30.0, kPositiveSeconds);
  const double poll_s = args.seconds("poll", 0.5, kPositiveSeconds);
  const double grace_s = args.grace_seconds("job-grace");
  if (!args.positional().empty()) throw std::invalid_argument("worker takes no file arguments");
  if (o.workers < 1 || o.threads_per_job < 0 || o.max_attempts < 1) {
    throw std::invalid_argument("--workers, --threads-per-job and --max-attempts are positive");
  }
  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (o.threads_per_job == 0) o.threads_per_job = std::max(1, cores / o.workers);
  o.jobs_dir = *results;
  o.holder = {server::process_name(), lease_s};
  o.poll_interval = std::chrono::milliseconds(static_cast<long long>(poll_s * 1000));
  // The heartbeat renews the leases three times per lease.
  o.flush_interval =
      std::min(std::chrono::milliseconds(1000),
               std::chrono::milliseconds(static_cast<long long>(lease_s * 1000 / 3)));
  o.log_name = "gearsph worker " + o.holder.worker;

  // SIGINT / SIGTERM are taken by sigwait below, in no other thread.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  std::filesystem::create_directories(o.jobs_dir);
  auto store = server::open_job_store(store_location);
  server::EventHub hub;  // nobody listens here: the API reads progress from the store
  server::WorkerPool pool(*store, hub, o);
  pool.start();
  std::printf("gearsph worker: %s ready (%d worker%s x %d thread%s, lease %.3g s, results %s)\n",
              o.holder.worker.c_str(), o.workers, o.workers == 1 ? "" : "s", o.threads_per_job,
              o.threads_per_job == 1 ? "" : "s", lease_s, o.jobs_dir.string().c_str());
  std::fflush(stdout);
  int sig = 0;
  sigwait(&signals, &sig);
  server::log_line(server::LogLevel::info, "%s: %s: stopping\n", o.log_name.c_str(),
                   sig == SIGINT ? "SIGINT" : "SIGTERM");
  if (grace_s > 0 && pool.running() > 0) {
    // A warm shutdown: no new claims; the running jobs may finish (their
    // heartbeat goes on) until the grace runs out or a second signal.
    server::log_line(server::LogLevel::info,
                     "%s: letting %d running job(s) finish, for up to %.3g s\n", o.log_name.c_str(),
                     pool.running(), grace_s);
    pool.drain();
    const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(grace_s);
    const timespec tick{0, 100'000'000};
    while (pool.running() > 0 && std::chrono::steady_clock::now() < end) {
      if (sigtimedwait(&signals, nullptr, &tick) > 0) {
        server::log_line(server::LogLevel::info, "%s: stopping the running jobs now\n",
                         o.log_name.c_str());
        break;
      }
    }
  }
  pool.stop();
  server::log_line(server::LogLevel::info, "%s: stopped\n", o.log_name.c_str());
  return 0;
}

}  // namespace gearsph::cli
