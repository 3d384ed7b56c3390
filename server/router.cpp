#include "server/router.hpp"

#include <algorithm>
#include <charconv>
#include <cstdio>

#include <boost/asio/ip/address.hpp>

#include "server/log.hpp"
#include "server/metrics.hpp"
#include "server/problem.hpp"
#include "server/routes.hpp"
#include "server/routes_preview.hpp"
#include "server/routes_rating.hpp"
#include "server/sha256.hpp"
#include "server/static_files.hpp"

namespace gearsph::server {

namespace {

// Seconds a client is asked to wait while the job store is away: about
// what a PostgreSQL restart takes.
constexpr int kStoreRetryAfterS = 5;

}  // namespace

const std::vector<Route>& route_table() {
  using http::verb;
  constexpr Lane store = Lane::store;
  constexpr Lane slow = Lane::slow;
  static const std::vector<Route> table = {
      // method        path                               handler                lane
      {verb::get, "/", routes::landing},
      {verb::get, "/api", routes::api_definition},
      {verb::get, "/conformance", routes::conformance},
      {verb::get, "/health", routes::health},  // queue counts from a cache
      {verb::get, "/metrics", routes::metrics, store},
      {verb::get, "/schema", routes::schema},
      {verb::get, "/processes", routes::processes},
      {verb::get, "/processes/{process}", routes::process},
      {verb::post, "/processes/{process}/execution", routes::execute, slow},
      {verb::get, "/jobs", routes::list_jobs, store},
      {verb::post, "/jobs", routes::execute, slow},
      {verb::get, "/jobs/{id}", routes::job, store},
      {verb::delete_, "/jobs/{id}", routes::dismiss_job, slow},
      {verb::get, "/jobs/{id}/results", routes::results, store},
      {verb::get, "/jobs/{id}/files", routes::files, store},
      {verb::get, "/jobs/{id}/files/{name}", routes::file, store},
      {verb::get, "/jobs/{id}/images/{image}", routes::image, slow},
      {verb::get, "/jobs/{id}/events", routes::job_events, store},  // the status to start with
      {verb::get, "/events", routes::all_events},
      {verb::post, "/studies", routes::create_study, slow},
      {verb::get, "/studies/{id}", routes::study, slow},  // reads every job's summary
      {verb::post, "/preview", routes::preview, slow},    // builds the scene
      {verb::post, "/rating", routes::rating},            // ISO 6336, microseconds
      // Sessions are in the job store.
      {verb::get, "/login", routes::login_state, store},
      {verb::post, "/login", routes::login, store},  // checks the token itself
      {verb::delete_, "/login", routes::logout, store},
  };
  return table;
}

bool token_matches(std::string_view presented, std::string_view expected) {
  // Every byte of the expected token is looked at whatever is presented,
  // so the time taken says nothing about how much of it was right.
  unsigned char diff = presented.size() == expected.size() ? 0 : 1;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const char p = i < presented.size() ? presented[i] : 0;
    diff |= static_cast<unsigned char>(p ^ expected[i]);
  }
  return diff == 0;
}

std::optional<std::string> session_cookie(const http::request_header<>& header) {
  for (const auto& field : header) {
    if (field.name() != http::field::cookie) continue;
    std::string_view rest = field.value();
    while (!rest.empty()) {
      const auto semi = rest.find(';');
      std::string_view pair = rest.substr(0, semi);
      rest = semi == std::string_view::npos ? std::string_view() : rest.substr(semi + 1);
      while (!pair.empty() && pair.front() == ' ') pair.remove_prefix(1);
      const auto eq = pair.find('=');
      if (eq == std::string_view::npos || pair.substr(0, eq) != kSessionCookie) continue;
      if (auto token = percent_decode(pair.substr(eq + 1), false)) return token;
    }
  }
  return std::nullopt;
}

std::optional<HostName> parse_host(std::string_view value) {
  HostName out;
  std::string_view port;
  if (!value.empty() && value.front() == '[') {  // [IPv6]:port
    const auto close = value.find(']');
    if (close == std::string_view::npos) return std::nullopt;
    out.host = std::string(value.substr(0, close + 1));
    const std::string_view rest = value.substr(close + 1);
    if (!rest.empty()) {
      if (rest.front() != ':') return std::nullopt;
      port = rest.substr(1);
      if (port.empty()) return std::nullopt;
    }
  } else {
    const auto colon = value.find(':');
    out.host = std::string(value.substr(0, colon));
    if (colon != std::string_view::npos) {
      port = value.substr(colon + 1);
      if (port.empty()) return std::nullopt;
    }
  }
  if (out.host.empty()) return std::nullopt;
  for (char& c : out.host) {
    const auto u = static_cast<unsigned char>(c);
    const bool ok = std::isalnum(u) || c == '-' || c == '.' || c == '_' || c == ':' || c == '[' ||
                    c == ']' || c == '%' || c == '~';
    if (!ok) return std::nullopt;
    c = static_cast<char>(std::tolower(u));
  }
  if (!port.empty()) {
    unsigned n = 0;
    const auto [end, ec] = std::from_chars(port.data(), port.data() + port.size(), n);
    if (ec != std::errc() || end != port.data() + port.size() || n > 65535) return std::nullopt;
    out.port = n;
  }
  return out;
}

namespace {

bool segments_match(std::string_view pattern, const std::vector<std::string>& segments,
                    std::map<std::string, std::string>& params) {
  std::size_t i = 0;
  std::size_t start = 1;  // after the leading '/'
  while (start <= pattern.size()) {
    if (pattern.size() == 1) break;  // "/": no segments
    const auto slash = pattern.find('/', start);
    const std::string_view part = pattern.substr(
        start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
    if (i >= segments.size()) return false;
    if (part.size() > 2 && part.front() == '{' && part.back() == '}') {
      if (segments[i].empty()) return false;
      params[std::string(part.substr(1, part.size() - 2))] = segments[i];
    } else if (part != segments[i]) {
      return false;
    }
    ++i;
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  return i == segments.size();
}

std::string allow_list(std::vector<http::verb> methods) {
  std::string out;
  bool get = false;
  for (http::verb m : methods) {
    if (!out.empty()) out += ", ";
    out += std::string(http::to_string(m));
    get = get || m == http::verb::get;
  }
  if (get) out += ", HEAD";
  out += ", OPTIONS";
  return out;
}

http::response_header<>& head_of(Response& res) {
  return std::visit(
      [](auto& m) -> http::response_header<>& {
        if constexpr (std::is_same_v<std::decay_t<decltype(m)>, EventStream>) {
          return m.head;
        } else {
          return m;
        }
      },
      res);
}

bool is_event_stream_path(const std::vector<std::string>& segments) {
  return (segments.size() == 1 && segments[0] == "events") ||
         (segments.size() == 3 && segments[0] == "jobs" && segments[2] == "events");
}

// The token a request presents, and where: the Authorization header, the
// cookie the login call sets (what a browser's images, downloads and event
// streams carry), or, on event streams only, ?access_token= (RFC 6750
// section 2.3: EventSource cannot set headers).
struct Credential {
  enum class From { nothing, header, cookie, query };
  std::string token;
  From from = From::nothing;
};

Credential presented_token(const http::request_header<>& header) {
  const std::string_view auth = header[http::field::authorization];
  constexpr std::string_view scheme = "bearer ";
  if (auth.size() > scheme.size()) {
    bool ok = true;
    for (std::size_t i = 0; i < scheme.size() && ok; ++i) {
      ok = std::tolower(static_cast<unsigned char>(auth[i])) == scheme[i];
    }
    if (ok) return {std::string(auth.substr(scheme.size())), Credential::From::header};
  }
  if (auto t = session_cookie(header)) return {*t, Credential::From::cookie};
  Request r;
  if (parse_target(header.target(), r) && is_event_stream_path(r.segments)) {
    if (auto t = r.query_value("access_token")) return {*t, Credential::From::query};
  }
  return {};
}

// RFC 9112 sections 6.1 and 6.3: chunked is the one transfer coding this
// server reads, and it must come last; anything else would be read as
// something it is not. The status and a sentence, or nothing if fine.
std::optional<std::pair<http::status, std::string>> framing_problem(
    const http::request_header<>& header) {
  if (!header.count(http::field::transfer_encoding)) return std::nullopt;
  if (header.version() < 11) {
    return std::make_pair(http::status::bad_request,
                          std::string("an HTTP/1.0 request cannot use Transfer-Encoding"));
  }
  if (header.count(http::field::content_length)) {
    return std::make_pair(
        http::status::bad_request,
        std::string("a request cannot have both Transfer-Encoding and Content-Length"));
  }
  std::vector<std::string> codings;
  for (const auto& field : header) {
    if (field.name() != http::field::transfer_encoding) continue;
    const std::string_view value = field.value();
    std::size_t start = 0;
    while (start <= value.size()) {
      const auto comma = value.find(',', start);
      std::string_view item = value.substr(
          start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
      item = item.substr(0, item.find(';'));  // parameters
      while (!item.empty() && (item.front() == ' ' || item.front() == '\t')) item.remove_prefix(1);
      while (!item.empty() && (item.back() == ' ' || item.back() == '\t')) item.remove_suffix(1);
      if (!item.empty()) {
        std::string coding(item);
        for (char& c : coding) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        codings.push_back(std::move(coding));
      }
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
  }
  if (codings.empty() || codings.back() != "chunked") {
    return std::make_pair(http::status::bad_request,
                          std::string("Transfer-Encoding must end with chunked"));
  }
  for (std::size_t i = 0; i + 1 < codings.size(); ++i) {
    if (codings[i] == "chunked") {
      return std::make_pair(http::status::bad_request,
                            std::string("Transfer-Encoding names chunked more than once"));
    }
    return std::make_pair(http::status::not_implemented,
                          "the transfer coding \"" + codings[i] +
                              "\" is not supported; send the body as it is, with "
                              "Content-Length or chunked");
  }
  return std::nullopt;
}

}  // namespace

bool carries_credential(const http::request_header<>& header, std::string_view token,
                        const Sessions& sessions) {
  const Credential c = presented_token(header);
  if (c.from == Credential::From::cookie) return sessions.valid(c.token);
  return c.from != Credential::From::nothing && token_matches(c.token, token);
}

std::string credential_identity(const http::request_header<>& header, std::string_view token,
                                const Sessions& sessions) {
  if (token.empty()) return {};
  const Credential c = presented_token(header);
  if (c.from == Credential::From::cookie) {
    return sessions.valid(c.token) ? "session " + sha256_hex(c.token).substr(0, 16) : "";
  }
  if (c.from == Credential::From::nothing || !token_matches(c.token, token)) return {};
  return "token " + sha256_hex(c.token).substr(0, 16);
}

namespace {

bool is_preflight(const http::request_header<>& h) {
  return h.method() == http::verb::options && h.count(http::field::origin) &&
         h.count(http::field::access_control_request_method);
}

}  // namespace

Router::Router(Services& services) : services_(services), routes_(route_table()) {}

std::optional<Response> Router::screen(const http::request_header<>& header) const {
  const ServerConfig& config = services_.config;
  Request req;
  req.path = std::string(header.target().substr(0, header.target().find('?')));
  req.msg.base() = header;
  auto refuse = [&](http::status status, const std::string& detail) -> Response {
    Response res = problem::plain(status, detail, req.path);
    decorate(req, res);
    return res;
  };
  if (header.version() != 10 && header.version() != 11) {
    return refuse(http::status::http_version_not_supported,
                  "this server speaks HTTP/1.1 (and HTTP/1.0)");
  }
  // RFC 9112 section 3.2: exactly one Host in HTTP/1.1. Checked against
  // the names this server answers to, so that a page of another site whose
  // name was made to point here (DNS rebinding) gets nothing.
  const auto hosts = header.count(http::field::host);
  if (hosts > 1) {
    return refuse(http::status::bad_request,
                  "the request has " + std::to_string(hosts) + " Host headers; send one");
  }
  if (hosts == 0 && header.version() == 11) {
    return refuse(http::status::bad_request, "an HTTP/1.1 request needs a Host header");
  }
  if (hosts == 1) {
    const std::string_view host = header[http::field::host];
    const auto parsed = parse_host(host);
    if (!parsed) {
      return refuse(http::status::bad_request,
                    "the Host header \"" + std::string(host) + "\" is not host[:port]");
    }
    if (!host_allowed(*parsed)) {
      return refuse(http::status::misdirected_request,
                    "this server does not answer to the name \"" + std::string(host) +
                        "\"; to allow it, start the server with --allowed-host " + parsed->host);
    }
  }
  if (auto problem = framing_problem(header)) return refuse(problem->first, problem->second);
  if (!config.token.empty() && !is_public(header)) {
    const Credential presented = presented_token(header);
    if (!carries_credential(header, config.token, services_.sessions)) {
      Response res =
          problem::plain(http::status::unauthorized,
                         "this server needs \"Authorization: Bearer <token>\"", req.path);
      head_of(res).set(http::field::www_authenticate, "Bearer realm=\"gearsph\"");
      decorate(req, res);
      return res;
    }
    // A browser sends the cookie with requests that other pages (of this
    // host, on another port, say) make it send: changes need this origin.
    const bool changes = header.method() != http::verb::get &&
                         header.method() != http::verb::head &&
                         header.method() != http::verb::options;
    if (presented.from == Credential::From::cookie && changes && !same_origin(header)) {
      return refuse(http::status::forbidden,
                    "a change sent with the session cookie from another origin (" +
                        std::string(header[http::field::origin]) + ") is refused");
    }
  }
  return std::nullopt;
}

bool Router::is_public(const http::request_header<>& header) const {
  if (is_preflight(header)) return true;
  Request req;
  if (!parse_target(header.target(), req)) return false;  // answered 400 later
  // The login call checks the token itself.
  if (req.segments.size() == 1 && req.segments[0] == "login") return true;
  if (header.method() != http::verb::get && header.method() != http::verb::head) return false;
  req.msg.base() = header;
  // The dashboard's own files hold no data: a browser loads them before it
  // has a token to send.
  if (req.segments.empty()) return wants_html(req);
  for (const Route& r : routes_) {
    std::map<std::string, std::string> params;
    if (segments_match(r.pattern, req.segments, params)) return false;
  }
  return find_static(req, services_.config.web_root).has_value();
}

bool Router::same_origin(const http::request_header<>& header) const {
  if (!header.count(http::field::origin)) return true;  // not sent by a browser's page
  const std::string origin(header[http::field::origin]);
  const std::string& cors = services_.config.cors_origin;
  if (!cors.empty() && (cors == "*" ? false : cors == origin)) return true;
  constexpr std::string_view http_scheme = "http://";
  if (origin.rfind(http_scheme, 0) != 0) return false;  // "null", https behind a proxy, ...
  const auto from = parse_host(std::string_view(origin).substr(http_scheme.size()));
  const auto to = parse_host(header[http::field::host]);
  return from && to && from->host == to->host && from->port.value_or(80) == to->port.value_or(80);
}

bool Router::host_allowed(const HostName& h) const {
  const unsigned short port = services_.port;
  const unsigned asked_port = h.port.value_or(80);
  std::vector<std::string> names = {"localhost", "127.0.0.1", "[::1]"};
  // The bound address, unless it stands for every interface.
  boost::system::error_code ec;
  const auto bound = boost::asio::ip::make_address(services_.config.bind, ec);
  if (!ec && !bound.is_unspecified()) {
    names.push_back(bound.is_v6() ? "[" + bound.to_string() + "]" : bound.to_string());
  }
  for (const std::string& n : names) {
    if (h.host == n && asked_port == port) return true;
  }
  for (const std::string& entry : services_.config.allowed_hosts) {
    if (entry == "*") return true;
    const auto allowed = parse_host(entry);
    if (allowed && allowed->host == h.host && (!allowed->port || *allowed->port == asked_port)) {
      return true;
    }
  }
  return false;
}

Router::Match Router::match(Request& req) const {
  Match m;
  if (!parse_target(req.msg.target(), req)) {
    m.answer = problem::plain(http::status::bad_request,
                              "the request target is not a valid absolute path", req.path);
    return m;
  }
  for (const std::string& s : req.segments) {
    if (s == "." || s == "..") {
      m.answer = problem::plain(http::status::bad_request,
                                "path segments '.' and '..' are not allowed", req.path);
      return m;
    }
    const bool control = std::any_of(s.begin(), s.end(), [](char c) {
      return static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
    });
    if (control) {
      m.answer = problem::plain(http::status::bad_request,
                                "the path holds a control character (such as %00); paths are "
                                "printable text",
                                req.path);
      return m;
    }
  }
  const http::verb method =
      req.msg.method() == http::verb::head ? http::verb::get : req.msg.method();
  std::vector<http::verb> allowed;
  for (const Route& r : routes_) {
    std::map<std::string, std::string> params;
    if (!segments_match(r.pattern, req.segments, params)) continue;
    if (r.method == method) {
      req.params = std::move(params);
      m.route = &r;
      return m;
    }
    allowed.push_back(r.method);
  }
  if (allowed.empty() && method == http::verb::get) {
    if (auto res = serve_static(req, services_.config.web_root)) {
      m.answer = std::move(*res);
      return m;
    }
  }
  if (allowed.empty()) {
    m.answer = problem::plain(http::status::not_found, "no such resource", req.path);
    return m;
  }
  if (method == http::verb::options) {
    if (auto pre = cors_preflight(req)) {
      m.answer = std::move(*pre);
      return m;
    }
    StringResponse res{http::status::no_content, 11};
    res.set(http::field::allow, allow_list(allowed));
    m.answer = std::move(res);
    return m;
  }
  StringResponse res =
      problem::plain(http::status::method_not_allowed,
                     std::string(req.msg.method_string()) + " is not allowed here", req.path);
  res.set(http::field::allow, allow_list(allowed));
  m.answer = std::move(res);
  return m;
}

std::optional<Response> Router::cors_preflight(const Request& req) const {
  if (!is_preflight(req.msg.base())) return std::nullopt;
  StringResponse res{http::status::no_content, 11};
  const std::string& allowed = services_.config.cors_origin;
  const std::string origin = req.header(http::field::origin);
  if (!allowed.empty() && (allowed == "*" || allowed == origin)) {
    res.set(http::field::access_control_allow_methods, "GET, HEAD, POST, DELETE, OPTIONS");
    res.set(http::field::access_control_allow_headers,
            "Authorization, Content-Type, Idempotency-Key, Last-Event-ID, Range, Accept");
    res.set(http::field::access_control_max_age, "600");
  }
  return res;
}

Response Router::respond(Request& req, Match match) const {
  ++services_.requests;
  Response res = [&]() -> Response {
    if (!match.route) return std::move(*match.answer);
    try {
      return match.route->handler(services_, req);
    } catch (const StoreUnavailable& e) {
      // The request may well succeed once the store is back.
      services_.note_store_down(e.what());
      ++counters().store_unavailable;
      log_line(LogLevel::warning, "gearsph serve: %s %s: %s\n",
               std::string(req.msg.method_string()).c_str(), req.path.c_str(), e.what());
      problem::Problem p;
      p.status = http::status::service_unavailable;
      p.type = problem::kStoreUnavailable;
      p.title = "Job store unavailable";
      p.detail =
          "the job store cannot be reached just now; try again shortly (a submission retried "
          "with the same Idempotency-Key is never made twice)";
      p.instance = req.path;
      StringResponse busy = problem::make(p);
      busy.set(http::field::retry_after, std::to_string(kStoreRetryAfterS));
      return busy;
    } catch (const std::exception& e) {
      log_line(LogLevel::error, "gearsph serve: %s %s: %s\n",
               std::string(req.msg.method_string()).c_str(), req.path.c_str(), e.what());
      return problem::plain(http::status::internal_server_error,
                            "the server failed to answer this request", req.path);
    }
  }();
  decorate(req, res);
  if (req.msg.method() == http::verb::head) {
    // HEAD: the headers of GET, no body.
    if (auto* es = std::get_if<EventStream>(&res)) {
      StringResponse head{es->head.result(), 11};
      for (const auto& field : es->head) head.set(field.name_string(), field.value());
      res = std::move(head);
    } else if (auto* f = std::get_if<FileResponse>(&res)) {
      StringResponse head{f->result(), 11};
      for (const auto& field : *f) head.set(field.name_string(), field.value());
      head.content_length(f->body().size());
      res = std::move(head);
    } else if (auto* s = std::get_if<StringResponse>(&res)) {
      const auto n = s->body().size();
      s->body().clear();
      s->content_length(n);
    }
  }
  return res;
}

void Router::decorate(const Request& req, Response& res) const {
  auto& h = head_of(res);
  h.set(http::field::server, std::string("gearsph/") + version());
  if (!h.count(http::field::cache_control)) h.set(http::field::cache_control, "no-store");
  const std::string& allowed = services_.config.cors_origin;
  if (!allowed.empty() && req.msg.count(http::field::origin)) {
    const std::string origin = req.header(http::field::origin);
    if (allowed == "*" || allowed == origin) {
      h.set(http::field::access_control_allow_origin, allowed == "*" ? "*" : origin);
      h.set(http::field::vary, "Origin");
      h.set(http::field::access_control_expose_headers,
            "Location, Content-Range, Content-Length, Accept-Ranges");
    }
  }
}

}  // namespace gearsph::server
