#pragma once
// The dashboard's sessions behind --token-file (docs/api.md, Tokens and
// sessions): POST /login trades the token for an opaque random session id,
// the cookie holds that id, never the token; DELETE /login revokes it.
// Held in this process's memory: a restart (which is also how the token
// changes) ends every session, and each API node of a shared store has its
// own.
#include <chrono>
#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

namespace gearsph::server {

// Thirty days: a dashboard asks for the token once, not every morning.
inline constexpr std::chrono::seconds kSessionLifetime{30 * 24 * 3600};
// Plenty for the browsers of a team; a flood of logins cannot grow memory.
inline constexpr std::size_t kMaxSessions = 10000;
// Failed logins an address may make per minute before it waits (429).
inline constexpr int kLoginFailuresPerMinute = 5;

class Sessions {
 public:
  using Clock = std::chrono::steady_clock;
  // Sessions live `lifetime` from their login; at most `max_sessions`, the
  // oldest going first beyond it.
  Sessions(std::chrono::seconds lifetime, std::size_t max_sessions);

  std::string open();  // a new session: 128 random bits as hex
  bool valid(std::string_view id) const;
  bool close(std::string_view id);  // false if there was no such session
  std::size_t size() const;
  std::chrono::seconds lifetime() const { return lifetime_; }

 private:
  std::chrono::seconds lifetime_;
  std::size_t max_sessions_;
  mutable std::mutex mutex_;
  std::map<std::string, Clock::time_point, std::less<>> expires_;  // id -> end
};

// Failed logins per client address: after `max_failures` within `window`,
// every login from that address is refused (429) until the oldest failure
// is out of the window, so a token cannot be guessed at network speed.
class LoginThrottle {
 public:
  using Clock = std::chrono::steady_clock;
  LoginThrottle(int max_failures, std::chrono::seconds window);

  // Seconds until `client` may try again; 0 when it may now.
  std::chrono::seconds wait(const std::string& client, Clock::time_point now = Clock::now());
  void failed(const std::string& client, Clock::time_point now = Clock::now());
  void succeeded(const std::string& client);

 private:
  int max_failures_;
  std::chrono::seconds window_;
  std::mutex mutex_;
  std::map<std::string, std::vector<Clock::time_point>> failures_;
  void forget_old(Clock::time_point now);
};

}  // namespace gearsph::server
