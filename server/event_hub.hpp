#pragma once
// Job events for Server-Sent Events streams: workers and handlers publish,
// each stream pulls what it has not sent yet. Publishing never waits for a
// client: events go into a bounded ring, and a subscriber that fell further
// behind than the ring learns of the gap and resends a status snapshot.
//
// Event ids grow across restarts (they start at the start-up time in
// microseconds), so a Last-Event-ID from an earlier server is simply older
// than everything kept.
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

namespace gearsph::server {

struct Event {
  std::uint64_t id = 0;
  std::string job_id;
  std::string type;       // "status" or "progress"
  std::string data;       // one line of JSON
  bool terminal = false;  // a status event with a final status
};

// The event as Server-Sent Events text: id, event, data, blank line.
std::string sse_text(const Event& e);

class EventHub {
 public:
  explicit EventHub(std::size_t capacity = 4096);

  std::uint64_t publish(std::string job_id, std::string type, std::string data,
                        bool terminal = false);

  // Unsubscribes when destroyed. `wake` is called (from the publishing
  // thread, without locks held) after each matching event and on close();
  // it must only schedule work.
  class Subscription {
   public:
    Subscription(EventHub& hub, std::uint64_t token) : hub_(hub), token_(token) {}
    ~Subscription();
    Subscription(const Subscription&) = delete;
    Subscription& operator=(const Subscription&) = delete;

   private:
    EventHub& hub_;
    std::uint64_t token_;
  };
  // job_id empty: every job.
  std::unique_ptr<Subscription> subscribe(std::string job_id, std::function<void()> wake);

  struct Batch {
    std::vector<Event> events;  // id > after, matching, oldest first
    bool gap = false;           // events after `after` were dropped from the ring
    std::uint64_t seen = 0;     // the last id looked at: continue after this one
  };
  Batch after(std::uint64_t after, const std::string& job_id, std::size_t max) const;

  std::uint64_t last_id() const;

  // What a client that has seen everything up to `after` can get: whether
  // the ring still holds every event since (else it needs a snapshot), and
  // whether one of them is a final status of `job_id`.
  struct Resume {
    bool complete = false;
    bool final_status_ahead = false;
  };
  Resume resume(std::uint64_t after, const std::string& job_id) const;
  // Shutting down: streams end after what they have not sent yet.
  void close();
  bool closed() const;
  std::size_t subscribers() const;

 private:
  struct Subscriber {
    std::string job_id;
    std::function<void()> wake;
  };
  void unsubscribe(std::uint64_t token);

  mutable std::mutex mutex_;
  std::size_t capacity_;
  std::deque<Event> ring_;
  std::uint64_t next_id_;
  std::uint64_t next_token_ = 1;
  std::map<std::uint64_t, Subscriber> subscribers_;
  bool closed_ = false;
};

}  // namespace gearsph::server
