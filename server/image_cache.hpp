#pragma once
// Rendered images of finished jobs, kept in memory up to a byte budget and
// dropped least recently used first: a second look at a frame costs no
// render, and however many zooms and frames are asked for, neither memory
// nor the job's result files grow (images are not results).
#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <string>
#include <unordered_map>

#include <nlohmann/json.hpp>

namespace gearsph::server {

class ImageCache {
 public:
  explicit ImageCache(std::uint64_t max_bytes) : max_bytes_(max_bytes) {}

  // The image under `key` ("{job id}/{what}"), or null.
  std::shared_ptr<const std::string> get(const std::string& key);
  // Keeps `png` unless it alone is over the budget; evicts the least
  // recently used images to make room.
  void put(const std::string& key, std::string png);
  // Drops every image of a job (it was dismissed).
  void drop_job(const std::string& job_id);
  // {"entries", "bytes", "max_bytes", "hits", "misses"}
  nlohmann::json stats() const;

 private:
  struct Entry {
    std::string key;
    std::shared_ptr<const std::string> png;
  };
  void evict(std::list<Entry>::iterator it);

  mutable std::mutex mutex_;
  std::uint64_t max_bytes_;
  std::uint64_t bytes_ = 0;
  std::uint64_t hits_ = 0, misses_ = 0;
  std::list<Entry> lru_;  // most recently used first
  std::unordered_map<std::string, std::list<Entry>::iterator> index_;
};

}  // namespace gearsph::server
