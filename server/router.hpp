#pragma once
// Maps requests to handlers with a plain table of (method, path pattern,
// handler); applies what every request shares: the bearer token, CORS,
// 404 / 405 answers, HEAD, caching headers, the dashboard's static files.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "server/http_types.hpp"
#include "server/services.hpp"
#include "server/sessions.hpp"

namespace gearsph::server {

using Handler = Response (*)(Services&, Request&);

// A Host header's name (lower case; IPv6 in brackets) and port, if given;
// nullopt if it is not host[:port].
struct HostName {
  std::string host;
  std::optional<unsigned> port;
};
std::optional<HostName> parse_host(std::string_view value);

// The cookie POST /login sets: an opaque session id (sessions.hpp), never the token.
inline constexpr std::string_view kSessionCookie = "gearsph_session";
std::optional<std::string> session_cookie(const http::request_header<>& header);
// Whether the request presents `token` (the header, or on event streams
// ?access_token=) or the cookie of one of `sessions`.
bool carries_credential(const http::request_header<>& header, std::string_view token,
                        const Sessions& sessions);
// Who the request's credential says it is, for the queue quota: "session
// <hash>" for a valid session cookie (each login its own), "token <hash>"
// for the bearer token (every holder of it the same); "" without `token`
// (no --token-file) or without a valid credential. The hash is the first 16
// hex digits of the secret's SHA-256: the store keeps no usable secret.
std::string credential_identity(const http::request_header<>& header, std::string_view token,
                                const Sessions& sessions);

// Where a handler runs. The I/O threads only move bytes and answer from
// memory; anything that reads the job store or the disk waits elsewhere,
// so that one slow answer never holds up another connection.
enum class Lane {
  io,     // answers from memory: on the connection's I/O thread
  store,  // reads the job store or a job's files: on the store threads
  slow,   // may take seconds (prepares jobs, renders, deletes files): on the handler threads
};

struct Route {
  http::verb method;
  std::string_view pattern;  // "/jobs/{id}/files/{name}": {x} matches one segment
  Handler handler;
  Lane lane = Lane::io;
};

class Router {
 public:
  explicit Router(Services& services);

  // Decides from the header alone whether to refuse before the body is
  // read: 505 for HTTP other than 1.x, 400 without one Host (HTTP/1.1),
  // 421 for a Host this server does not answer to (--allowed-host), 400 /
  // 501 for transfer codings it cannot read, 401 without a valid token. (A
  // declared body over the limit is refused by the session's parser: 413.)
  std::optional<Response> screen(const http::request_header<>& header) const;

  struct Match {
    const Route* route = nullptr;    // the handler to run, or
    std::optional<Response> answer;  // the answer without one (404, 405, OPTIONS, static)
    Lane lane() const { return route ? route->lane : Lane::io; }
  };
  Match match(Request& req) const;

  // Runs the match's handler (never throws: 500 problem) and finishes the
  // response (CORS, HEAD, caching).
  Response respond(Request& req, Match match) const;

  Services& services() const { return services_; }

 private:
  std::optional<Response> cors_preflight(const Request& req) const;
  bool host_allowed(const HostName& h) const;
  // Needs no token: CORS preflights, the login call, the dashboard's files.
  bool is_public(const http::request_header<>& header) const;
  // Origin, if sent, is this server (or the --cors-origin).
  bool same_origin(const http::request_header<>& header) const;
  void decorate(const Request& req, Response& res) const;

  Services& services_;
  const std::vector<Route>& routes_;
};

const std::vector<Route>& route_table();

// Constant-time comparison of the presented token with the configured one.
bool token_matches(std::string_view presented, std::string_view expected);

}  // namespace gearsph::server
