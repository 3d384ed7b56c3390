#pragma once
// The job service put together: data directory (locked against a second
// server), job store (recovered after a crash), worker pool, event hub,
// router, and one io_context with a couple of I/O threads.
#include <condition_variable>
#include <memory>
#include <mutex>

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/thread_pool.hpp>

#include "server/config.hpp"
#include "server/event_hub.hpp"
#include "server/job_store.hpp"
#include "server/listener.hpp"
#include "server/router.hpp"
#include "server/services.hpp"
#include "server/store_watcher.hpp"
#include "server/worker_pool.hpp"

namespace gearsph::server {

class Server {
 public:
  // Opens everything and binds the port; throws with a sentence on failure.
  explicit Server(ServerConfig config);
  ~Server();
  Server(const Server&) = delete;
  Server& operator=(const Server&) = delete;

  unsigned short port() const { return listener_->port(); }

  // Serves until stop() or SIGINT / SIGTERM, then stops gracefully: no new
  // connections, running jobs cancelled and re-queued, event streams ended,
  // in-flight answers given a moment.
  void run();
  void stop();  // thread-safe

  // The retention (ServerConfig::retention_s), once; public for tests.
  void prune();

 private:
  void wait_for_signal();
  void refresh_counts_every_second();

  ServerConfig config_;
  int lock_fd_ = -1;
  std::unique_ptr<JobStore> store_;
  EventHub hub_;
  std::unique_ptr<Dispatcher> workers_;
  std::unique_ptr<StoreWatcher> watcher_;  // jobs run by other processes
  std::unique_ptr<Services> services_;
  std::unique_ptr<Router> router_;
  boost::asio::thread_pool handler_pool_;
  boost::asio::thread_pool store_pool_;
  boost::asio::io_context ioc_;
  std::shared_ptr<Listener> listener_;
  boost::asio::signal_set signals_;
  boost::asio::steady_timer counts_timer_;  // refreshes the queue counts /health shows
  std::mutex mutex_;
  std::condition_variable stop_wake_;
  bool stop_requested_ = false;
  bool hurry_ = false;
  std::uint64_t ticks_ = 0;  // of the counts' refresh, one a second  // a second signal: no more
                             // grace for running jobs
};

}  // namespace gearsph::server
