#pragma once
// Connections opened on demand and reused, for the job store's engines
// (sqlite.hpp, postgres.hpp): one thread holds a connection at a time, and
// a lease hands it back when it ends, unless it broke (a Connection with
// ok() false, as libpq's after the database restarted, is dropped).
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

namespace gearsph::server {

template <class Connection, class Target>
class ConnectionPool {
 public:
  explicit ConnectionPool(Target target) : target_(std::move(target)) {}

  class Lease {
   public:
    Lease(ConnectionPool& pool, std::unique_ptr<Connection> c) : pool_(&pool), c_(std::move(c)) {}
    Lease(Lease&&) = default;
    Lease& operator=(Lease&&) = delete;
    ~Lease() {
      if (c_ && usable(*c_)) {
        std::lock_guard<std::mutex> lock(pool_->mutex_);
        pool_->idle_.push_back(std::move(c_));
      }
    }
    Connection& operator*() { return *c_; }
    Connection* operator->() { return c_.get(); }

   private:
    ConnectionPool* pool_;
    std::unique_ptr<Connection> c_;
  };

  Lease acquire() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      while (!idle_.empty()) {
        auto c = std::move(idle_.back());
        idle_.pop_back();
        if (usable(*c)) return Lease(*this, std::move(c));
      }
    }
    return Lease(*this, std::make_unique<Connection>(target_));
  }

 private:
  static bool usable(const Connection& c) {
    if constexpr (requires { c.ok(); }) {
      return c.ok();
    } else {
      return true;
    }
  }

  Target target_;
  std::mutex mutex_;
  std::vector<std::unique_ptr<Connection>> idle_;
};

}  // namespace gearsph::server
