#pragma once
// Answers of POST /preview kept in memory, by job (its canonical form with
// every default filled in): a page that previews as a form is typed asks
// for the same job again and again, and a scene is seconds to build.
// Least recently used answers go first once `capacity_bytes` is reached.
#include <cstddef>
#include <list>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_map>

#include <nlohmann/json.hpp>

namespace gearsph::server {

class PreviewCache {
 public:
  explicit PreviewCache(std::size_t capacity_bytes) : capacity_(capacity_bytes) {}

  std::optional<nlohmann::json> find(const std::string& job_key);
  void put(const std::string& job_key, const nlohmann::json& answer);
  std::size_t size() const;

 private:
  struct Entry {
    std::string key;
    nlohmann::json answer;
    std::size_t bytes = 0;
  };
  mutable std::mutex mutex_;
  std::size_t capacity_;
  std::size_t used_ = 0;
  std::list<Entry> entries_;  // most recently used first
  std::unordered_map<std::string, std::list<Entry>::iterator> index_;
};

}  // namespace gearsph::server
