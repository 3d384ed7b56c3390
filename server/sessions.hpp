#pragma once
// The dashboard's sessions behind --token-file (docs/api.md, Tokens and
// sessions): POST /login trades the token for an opaque random session id,
// the cookie holds that id, never the token; DELETE /login revokes it.
// Kept in the job store (the SHA-256 of the token and the id, never the
// id), so that every API node sharing a store knows every login and a
// revocation holds on all of them, and a restart keeps them; a server
// started with another token (it is read at start-up) finds none of the
// old token's sessions.
#include <chrono>
#include <cstddef>
#include <map>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "server/job_store.hpp"

namespace gearsph::server {

// Thirty days: a dashboard asks for the token once, not every morning.
inline constexpr std::chrono::seconds kSessionLifetime{30 * 24 * 3600};
// Plenty for the browsers of a team; a flood of logins cannot grow the store.
inline constexpr std::size_t kMaxSessions = 10000;
// Failed logins an address may make per minute before it waits (429).
inline constexpr int kLoginFailuresPerMinute = 5;
// A session the store confirmed is taken as open for this long without
// asking again: the check runs on the I/O threads for every request a
// browser makes (images, downloads). A revocation on another node holds
// within this time; on this node at once.
inline constexpr std::chrono::seconds kSessionRecheck{2};

class Sessions {
 public:
  using Clock = std::chrono::steady_clock;
  // Sessions live `lifetime` from their login; at most `max_sessions`, the
  // first to end going first beyond it.
  // `token`: the server's (--token-file); its sessions are its own.
  Sessions(JobStore& store, std::string token, std::chrono::seconds lifetime,
           std::size_t max_sessions);

  std::string open();  // a new session: 128 random bits as hex
  // Open now. With the store away, a session this process confirmed before
  // is still taken; others are not.
  bool valid(std::string_view id) const;
  bool close(std::string_view id);  // false if there was no such session
  std::size_t size() const;
  std::chrono::seconds lifetime() const { return lifetime_; }

 private:
  std::string hash_of(std::string_view id) const;

  JobStore& store_;
  std::string token_;
  std::chrono::seconds lifetime_;
  std::size_t max_sessions_;
  mutable std::mutex mutex_;
  // Hashes the store confirmed open, and when (kSessionRecheck).
  mutable std::map<std::string, Clock::time_point, std::less<>> confirmed_;
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
