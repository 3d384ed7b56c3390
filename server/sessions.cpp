#include "server/sessions.hpp"

#include <algorithm>

#include "server/job_store.hpp"
#include "server/sha256.hpp"

namespace gearsph::server {

Sessions::Sessions(JobStore& store, std::string token, std::chrono::seconds lifetime,
                   std::size_t max_sessions)
    : store_(store),
      token_(std::move(token)),
      lifetime_(lifetime),
      max_sessions_(std::max<std::size_t>(1, max_sessions)) {}

std::string Sessions::hash_of(std::string_view id) const {
  // The token first: another token's sessions hash to other rows.
  return sha256_hex(token_ + '\n' + std::string(id));
}

std::string Sessions::open() {
  const std::string id = new_claim_token();
  const std::int64_t evicted =
      store_.open_session(hash_of(id), static_cast<double>(lifetime_.count()),
                          static_cast<std::int64_t>(max_sessions_));
  if (evicted > 0) {
    // Which went is the store's to know: this process asks again for all.
    std::lock_guard<std::mutex> lock(mutex_);
    confirmed_.clear();
  }
  return id;
}

bool Sessions::valid(std::string_view id) const {
  const std::string hash = hash_of(id);
  const auto now = Clock::now();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = confirmed_.find(hash);
    if (it != confirmed_.end() && now - it->second < kSessionRecheck) return true;
  }
  bool open = false;
  try {
    open = store_.session_open(hash);
  } catch (const std::exception&) {
    // The store away: what this process confirmed holds until it answers again.
    std::lock_guard<std::mutex> lock(mutex_);
    return confirmed_.count(hash) > 0;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  if (!open) {
    confirmed_.erase(hash);
    return false;
  }
  if (confirmed_.size() >= max_sessions_) {
    for (auto it = confirmed_.begin(); it != confirmed_.end();) {
      it = now - it->second >= kSessionRecheck ? confirmed_.erase(it) : std::next(it);
    }
  }
  if (confirmed_.size() < max_sessions_) confirmed_[hash] = now;
  return true;
}

bool Sessions::close(std::string_view id) {
  const std::string hash = hash_of(id);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    confirmed_.erase(hash);
  }
  return store_.close_session(hash);
}

std::size_t Sessions::size() const {
  return static_cast<std::size_t>(store_.open_sessions());
}

LoginThrottle::LoginThrottle(int max_failures, std::chrono::seconds window)
    : max_failures_(std::max(1, max_failures)), window_(window) {}

void LoginThrottle::forget_old(Clock::time_point now) {
  for (auto it = failures_.begin(); it != failures_.end();) {
    auto& times = it->second;
    times.erase(std::remove_if(times.begin(), times.end(),
                               [&](Clock::time_point t) { return t + window_ <= now; }),
                times.end());
    it = times.empty() ? failures_.erase(it) : std::next(it);
  }
}

std::chrono::seconds LoginThrottle::wait(const std::string& client, Clock::time_point now) {
  std::lock_guard<std::mutex> lock(mutex_);
  forget_old(now);
  const auto it = failures_.find(client);
  if (it == failures_.end() || static_cast<int>(it->second.size()) < max_failures_) {
    return std::chrono::seconds(0);
  }
  // Until the oldest failure leaves the window, rounded up (Retry-After is whole seconds).
  const auto left = it->second.front() + window_ - now;
  return std::max(std::chrono::seconds(1), std::chrono::ceil<std::chrono::seconds>(left));
}

void LoginThrottle::failed(const std::string& client, Clock::time_point now) {
  std::lock_guard<std::mutex> lock(mutex_);
  failures_[client].push_back(now);
}

void LoginThrottle::succeeded(const std::string& client) {
  std::lock_guard<std::mutex> lock(mutex_);
  failures_.erase(client);
}

}  // namespace gearsph::server
