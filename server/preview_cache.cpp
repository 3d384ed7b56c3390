#include "server/preview_cache.hpp"

namespace gearsph::server {

std::optional<nlohmann::json> PreviewCache::find(const std::string& job_key) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = index_.find(job_key);
  if (it == index_.end()) return std::nullopt;
  entries_.splice(entries_.begin(), entries_, it->second);
  return it->second->answer;
}

void PreviewCache::put(const std::string& job_key, const nlohmann::json& answer) {
  // Its text, twice over for the tree nlohmann keeps, and the key.
  const std::size_t bytes = 2 * answer.dump().size() + job_key.size();
  if (bytes > capacity_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (const auto it = index_.find(job_key); it != index_.end()) {
    used_ -= it->second->bytes;
    entries_.erase(it->second);
    index_.erase(it);
  }
  entries_.push_front({job_key, answer, bytes});
  index_[job_key] = entries_.begin();
  used_ += bytes;
  while (used_ > capacity_ && !entries_.empty()) {
    used_ -= entries_.back().bytes;
    index_.erase(entries_.back().key);
    entries_.pop_back();
  }
}

std::size_t PreviewCache::size() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return entries_.size();
}

}  // namespace gearsph::server
