#include "server/event_hub.hpp"

#include <chrono>

namespace gearsph::server {

std::string sse_text(const Event& e) {
  return "id: " + std::to_string(e.id) + "\nevent: " + e.type + "\ndata: " + e.data + "\n\n";
}

EventHub::EventHub(std::size_t capacity) : capacity_(capacity) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(
                      std::chrono::system_clock::now().time_since_epoch())
                      .count();
  next_id_ = static_cast<std::uint64_t>(us);
}

std::uint64_t EventHub::publish(std::string job_id, std::string type, std::string data,
                                bool terminal) {
  std::vector<std::function<void()>> wakes;
  std::uint64_t id = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    id = next_id_++;
    for (const auto& [token, s] : subscribers_) {
      if (s.job_id.empty() || s.job_id == job_id) wakes.push_back(s.wake);
    }
    ring_.push_back(Event{id, std::move(job_id), std::move(type), std::move(data), terminal});
    while (ring_.size() > capacity_) ring_.pop_front();
  }
  for (const auto& w : wakes) w();
  return id;
}

EventHub::Subscription::~Subscription() {
  hub_.unsubscribe(token_);
}

std::unique_ptr<EventHub::Subscription> EventHub::subscribe(std::string job_id,
                                                            std::function<void()> wake) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::uint64_t token = next_token_++;
  subscribers_[token] = Subscriber{std::move(job_id), std::move(wake)};
  return std::make_unique<Subscription>(*this, token);
}

void EventHub::unsubscribe(std::uint64_t token) {
  std::lock_guard<std::mutex> lock(mutex_);
  subscribers_.erase(token);
}

EventHub::Batch EventHub::after(std::uint64_t after, const std::string& job_id,
                                std::size_t max) const {
  Batch b;
  b.seen = after;
  std::lock_guard<std::mutex> lock(mutex_);
  const std::uint64_t oldest = ring_.empty() ? next_id_ : ring_.front().id;
  // The subscriber has seen ids up to `after`; anything in (after, oldest)
  // is lost (or was published by an earlier server).
  b.gap = after + 1 < oldest;
  // Ids in the ring are consecutive: jump straight to the first unseen one.
  std::size_t start = 0;
  if (after + 1 > oldest) start = static_cast<std::size_t>(after + 1 - oldest);
  for (std::size_t i = start; i < ring_.size() && b.events.size() < max; ++i) {
    const Event& e = ring_[i];
    b.seen = e.id;
    if (job_id.empty() || e.job_id == job_id) b.events.push_back(e);
  }
  return b;
}

EventHub::Resume EventHub::resume(std::uint64_t after, const std::string& job_id) const {
  Resume r;
  std::lock_guard<std::mutex> lock(mutex_);
  const std::uint64_t oldest = ring_.empty() ? next_id_ : ring_.front().id;
  r.complete = after < next_id_ && after + 1 >= oldest;
  if (!r.complete) return r;
  for (auto it = ring_.rbegin(); it != ring_.rend() && it->id > after; ++it) {
    if (it->terminal && (job_id.empty() || it->job_id == job_id)) {
      r.final_status_ahead = true;
      break;
    }
  }
  return r;
}

std::uint64_t EventHub::last_id() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return next_id_ - 1;
}

void EventHub::close() {
  std::vector<std::function<void()>> wakes;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    for (const auto& [token, s] : subscribers_) wakes.push_back(s.wake);
  }
  for (const auto& w : wakes) w();
}

bool EventHub::closed() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return closed_;
}

std::size_t EventHub::subscribers() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return subscribers_.size();
}

}  // namespace gearsph::server
