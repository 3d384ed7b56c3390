#include "server/server.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <thread>

#include <boost/asio/ip/address.hpp>

#include "server/attempt_dirs.hpp"
#include "server/log.hpp"
#include "server/metrics.hpp"
#include "server/open_job_store.hpp"
#include "server/slurm_dispatch.hpp"

namespace gearsph::server {

namespace net = boost::asio;

namespace {

int lock_data_dir(const std::filesystem::path& dir) {
  const auto file = dir / "gearsph.lock";
  const int fd = ::open(file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) throw std::runtime_error("cannot create " + file.string());
  if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(fd);
    throw std::runtime_error("another gearsph serve is using " + dir.string() + " (it holds " +
                             file.string() + ")");
  }
  return fd;
}

WorkerPoolOptions worker_options(const ServerConfig& c) {
  WorkerPoolOptions o;
  o.workers = c.local_workers ? c.workers : 0;
  o.threads_per_job = c.threads_per_job;
  o.core_budget = c.core_budget;
  o.jobs_dir = results_dir_of(c);
  o.progress_interval = c.progress_interval;
  o.flush_interval = c.flush_interval;
  o.max_attempts = c.max_attempts;
  if (shared_store(c)) {
    // Other processes claim from the same store: claims need leases, and
    // the flusher renews them well within one.
    o.holder = {process_name(), c.lease_s};
    o.flush_interval = std::min(
        o.flush_interval, std::chrono::milliseconds(static_cast<long long>(c.lease_s * 1000 / 3)));
    o.poll_interval = std::chrono::milliseconds(500);
  }
  return o;
}

std::unique_ptr<Dispatcher> make_dispatcher(const ServerConfig& c, JobStore& store, EventHub& hub) {
  if (c.dispatch != "slurm") {
    return std::make_unique<WorkerPool>(store, hub, worker_options(c));
  }
  SlurmOptions o;
  o.jobs_dir = std::filesystem::absolute(results_dir_of(c));
  o.gearsph = c.gearsph_executable;
  if (o.gearsph.empty()) o.gearsph = std::filesystem::read_symlink("/proc/self/exe");
  o.cpus_per_job = c.threads_per_job;
  o.sbatch_args = c.sbatch_args;
  o.name = process_name();
  return std::make_unique<SlurmDispatcher>(store, o);
}

}  // namespace

Server::Server(ServerConfig config)
    : config_(std::move(config)),
      handler_pool_(static_cast<std::size_t>(std::max(1, config_.handler_threads))),
      store_pool_(static_cast<std::size_t>(std::max(1, config_.store_threads))),
      signals_(ioc_, SIGINT, SIGTERM),
      counts_timer_(ioc_) {
  std::filesystem::create_directories(results_dir_of(config_));
  if (shared_store(config_)) {
    // Many API nodes may share the store; the data directory is theirs alone.
    std::filesystem::create_directories(config_.data_dir);
    store_ = open_job_store(config_.store);
  } else {
    lock_fd_ = lock_data_dir(config_.data_dir);
    store_ = open_sqlite_job_store(config_.data_dir / "gearsph.db");
  }
  const Recovery r = store_->recover(config_.max_attempts);
  for (const std::string& id : r.requeued) {
    log_line(LogLevel::info, "gearsph serve: job %s was interrupted; it is queued again\n",
             id.c_str());
  }
  for (const std::string& id : r.failed) {
    discard_attempts(results_dir_of(config_), id);
    log_line(LogLevel::warning, "gearsph serve: job %s was interrupted %d times; it failed\n",
             id.c_str(), config_.max_attempts);
  }
  workers_ = make_dispatcher(config_, *store_, hub_);
  if (shared_store(config_) || !config_.local_workers || config_.dispatch == "slurm") {
    StoreWatcherOptions wo;
    wo.reclaim = shared_store(config_);
    wo.max_attempts = config_.max_attempts;
    wo.jobs_dir = results_dir_of(config_);
    watcher_ = std::make_unique<StoreWatcher>(*store_, hub_, *workers_, wo);
  }
  services_ = std::make_unique<Services>(config_, *store_, *workers_, hub_);
  services_->refresh_queue_counts();
  router_ = std::make_unique<Router>(*services_);
  boost::system::error_code ec;
  const auto address = net::ip::make_address(config_.bind, ec);
  if (ec) throw std::runtime_error("--bind " + config_.bind + " is not an IP address");
  try {
    listener_ = std::make_shared<Listener>(ioc_, net::ip::tcp::endpoint(address, config_.port),
                                           *router_, HandlerPools{store_pool_, handler_pool_});
  } catch (const boost::system::system_error& e) {
    throw std::runtime_error("cannot listen on " + config_.bind + ":" +
                             std::to_string(config_.port) + ": " + e.code().message());
  }
  services_->port = listener_->port();
}

Server::~Server() {
  handler_pool_.join();
  store_pool_.join();
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

void Server::refresh_counts_every_second() {
  counts_timer_.expires_after(std::chrono::seconds(1));
  counts_timer_.async_wait([this](boost::system::error_code ec) {
    if (ec) return;
    net::post(store_pool_, [this] { services_->refresh_queue_counts(); });
    // The retention: five seconds after the start, then hourly.
    if (config_.retention_s > 0 && ++ticks_ % 3600 == 5) {
      net::post(store_pool_, [this] { prune(); });
    }
    refresh_counts_every_second();
  });
}

void Server::prune() {
  try {
    const std::vector<std::string> gone = store_->prune(config_.retention_s);
    const std::filesystem::path jobs_dir = results_dir_of(config_);
    for (const std::string& id : gone) {
      std::error_code ec;
      std::filesystem::remove_all(jobs_dir / id, ec);
      discard_attempts(jobs_dir, id);
      services_->images.drop_job(id);
    }
    counters().jobs_pruned += static_cast<std::int64_t>(gone.size());
    if (!gone.empty()) {
      log_line(LogLevel::info, "gearsph serve: deleted %zu job(s) that ended over %.3g days ago\n",
               gone.size(), config_.retention_s / 86400);
    }
  } catch (const std::exception& e) {
    log_line(LogLevel::warning, "gearsph serve: pruning old jobs failed: %s\n", e.what());
  }
}

void Server::stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_requested_ = true;
  }
  stop_wake_.notify_all();
}

void Server::wait_for_signal() {
  signals_.async_wait([this](boost::system::error_code ec, int signal) {
    if (ec) return;
    const char* name = signal == SIGINT ? "SIGINT" : "SIGTERM";
    bool again = false, force = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      again = stop_requested_;
      // A signal once the running jobs are already being stopped (no warm
      // shutdown, or a second signal cut it short): exit now. The store is
      // as safe as after a SIGKILL (every change a transaction; interrupted
      // jobs go back to the queue at the next start), and the FE tools die
      // with their parent (fe/external_program.hpp).
      force = again && (hurry_ || config_.job_grace.count() == 0);
      if (again) hurry_ = true;
    }
    if (force) {
      log_line(LogLevel::warning, "gearsph serve: %s again: exiting without waiting\n", name);
      std::_Exit(128 + signal);
    }
    log_line(LogLevel::info, "gearsph serve: %s: %s\n", name,
             again ? "stopping the running jobs now" : "stopping");
    stop();
    wait_for_signal();  // a second signal cuts the warm shutdown short
  });
}

void Server::run() {
  wait_for_signal();
  workers_->start();
  if (watcher_) watcher_->start();
  listener_->run();
  refresh_counts_every_second();
  std::vector<std::thread> io;
  for (int i = 0; i < std::max(1, config_.io_threads); ++i) io.emplace_back([this] { ioc_.run(); });

  {
    std::unique_lock<std::mutex> lock(mutex_);
    stop_wake_.wait(lock, [this] { return stop_requested_; });
  }
  // A warm shutdown: no new jobs start; the running ones may finish while
  // the API goes on answering about them, until the grace runs out or a
  // second signal.
  if (config_.job_grace.count() > 0 && workers_->running() > 0) {
    log_line(LogLevel::info, "gearsph serve: letting %d running job(s) finish, for up to %.3g s\n",
             workers_->running(), config_.job_grace.count() / 1000.0);
    workers_->drain();
    const auto end = std::chrono::steady_clock::now() + config_.job_grace;
    std::unique_lock<std::mutex> lock(mutex_);
    while (workers_->running() > 0 && !hurry_ && std::chrono::steady_clock::now() < end) {
      stop_wake_.wait_for(lock, std::chrono::milliseconds(100));
    }
  }
  services_->stopping = true;
  listener_->stop();
  // Running jobs stop at their next check and go back to the queue.
  workers_->stop();
  if (watcher_) watcher_->stop();
  hub_.close();
  const auto deadline = std::chrono::steady_clock::now() + config_.shutdown_grace;
  while (services_->connections > 0 && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  boost::system::error_code ignored;
  signals_.cancel(ignored);
  counts_timer_.cancel();
  ioc_.stop();
  for (std::thread& t : io) t.join();
  handler_pool_.join();
  store_pool_.join();
  log_line(LogLevel::info, "gearsph serve: stopped\n");
}

}  // namespace gearsph::server
