#include "server/sessions.hpp"

#include <algorithm>

#include "server/job_store.hpp"

namespace gearsph::server {

Sessions::Sessions(std::chrono::seconds lifetime, std::size_t max_sessions)
    : lifetime_(lifetime), max_sessions_(std::max<std::size_t>(1, max_sessions)) {}

std::string Sessions::open() {
  const std::string id = new_claim_token();
  const auto now = Clock::now();
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = expires_.begin(); it != expires_.end();) {
    it = it->second <= now ? expires_.erase(it) : std::next(it);
  }
  while (expires_.size() >= max_sessions_) {
    expires_.erase(
        std::min_element(expires_.begin(), expires_.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; }));
  }
  expires_[id] = now + lifetime_;
  return id;
}

bool Sessions::valid(std::string_view id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = expires_.find(id);
  return it != expires_.end() && it->second > Clock::now();
}

bool Sessions::close(std::string_view id) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = expires_.find(id);
  if (it == expires_.end()) return false;
  expires_.erase(it);
  return true;
}

std::size_t Sessions::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return expires_.size();
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
