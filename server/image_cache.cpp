#include "server/image_cache.hpp"

namespace gearsph::server {

std::shared_ptr<const std::string> ImageCache::get(const std::string& key) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = index_.find(key);
  if (it == index_.end()) {
    ++misses_;
    return nullptr;
  }
  ++hits_;
  lru_.splice(lru_.begin(), lru_, it->second);
  return it->second->png;
}

void ImageCache::put(const std::string& key, std::string png) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (png.size() > max_bytes_) return;
  if (const auto it = index_.find(key); it != index_.end()) evict(it->second);
  while (!lru_.empty() && bytes_ + png.size() > max_bytes_) evict(std::prev(lru_.end()));
  bytes_ += png.size();
  lru_.push_front(Entry{key, std::make_shared<const std::string>(std::move(png))});
  index_[key] = lru_.begin();
}

void ImageCache::drop_job(const std::string& job_id) {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::string prefix = job_id + "/";
  for (auto it = lru_.begin(); it != lru_.end();) {
    const auto next = std::next(it);
    if (it->key.compare(0, prefix.size(), prefix) == 0) evict(it);
    it = next;
  }
}

void ImageCache::evict(std::list<Entry>::iterator it) {
  bytes_ -= it->png->size();
  index_.erase(it->key);
  lru_.erase(it);
}

nlohmann::json ImageCache::stats() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {{"entries", lru_.size()},
          {"bytes", bytes_},
          {"max_bytes", max_bytes_},
          {"hits", hits_},
          {"misses", misses_}};
}

}  // namespace gearsph::server
