// The job service against hostile and demanding use (issue 27): numbers
// beyond double, resumed event streams, the dashboard behind a token, the
// image cache, the Host header, dismissed runs, transfer codings, the
// run-time estimate, HTTP versions, store reads off the network threads and
// the OGC API - Processes document.
#include <atomic>
#include <condition_variable>
#include <fstream>
#include <future>
#include <map>
#include <mutex>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/thread_pool.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>

#include "server/event_hub.hpp"
#include "server/image_cache.hpp"
#include "server/listener.hpp"
#include "server/router.hpp"
#include "server/services.hpp"
#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

// One server for the tests that do not need a fresh one.
class ServerHardening : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = new ServerProcess({"--threads-per-job", "1"}); }
  static void TearDownTestSuite() {
    expect_consistent_store(server_->data());
    delete server_;
    server_ = nullptr;
  }
  static ServerProcess* server_;
};
ServerProcess* ServerHardening::server_ = nullptr;

// 1. A number beyond the range of a double is valid JSON that no double can
// hold: 400 with the pointer to it, on every endpoint that takes a body.
TEST_F(ServerHardening, NumbersOutOfRangeAre400WithThePointer) {
  auto c = server_->client();
  for (const std::string& number :
       {std::string("1e400"), std::string("-1e400"), std::string(400, '9')}) {
    for (const char* path :
         {"/jobs", "/processes/gearsph-simulation/execution", "/preview", "/studies"}) {
      const ClientResponse r =
          c.post_json(path, R"({"name": "x", "time": {"end_s": )" + number + "}}");
      ASSERT_EQ(r.status, 400u) << path << " " << number << ": " << r.body;
      EXPECT_EQ(r.header("Content-Type"), "application/problem+json");
      const json p = r.json();
      EXPECT_EQ(p.at("type"), "urn:gearsph:problem:number-out-of-range") << r.body;
      ASSERT_EQ(p.at("errors").size(), 1u) << r.body;
      EXPECT_EQ(p.at("errors").at(0).at("pointer"), "/time/end_s") << r.body;
      EXPECT_NE(p.at("errors").at(0).at("detail").get<std::string>().find("out of range"),
                std::string::npos)
          << r.body;
    }
  }
  // In arrays, under the OGC wrapper, in a study's axes: the pointer is into the body.
  const ClientResponse wrapped = c.post_json(
      "/processes/gearsph-simulation/execution",
      R"({"inputs": {"job": {"scene": {"type": "rack_pinion", "rack": {"velocity_m_s": [0, -1e999]}}}}})");
  ASSERT_EQ(wrapped.status, 400u) << wrapped.body;
  EXPECT_EQ(wrapped.json().at("errors").at(0).at("pointer"),
            "/inputs/job/scene/rack/velocity_m_s/1");
  const ClientResponse study = c.post_json(
      "/studies",
      R"({"base": {"scene": {"type": "plate"}}, "axes": [{"pointer": "/time/end_s", "values": [0.1, 2e308]}]})");
  ASSERT_EQ(study.status, 400u) << study.body;
  EXPECT_EQ(study.json().at("errors").at(0).at("pointer"), "/axes/0/values/1");
  // Keys with '/' and '~' are escaped in the pointer (RFC 6901).
  const ClientResponse escaped = c.post_json("/preview", R"({"a/b~c": [1, {"d": 1e400}]})");
  ASSERT_EQ(escaped.status, 400u) << escaped.body;
  EXPECT_EQ(escaped.json().at("errors").at(0).at("pointer"), "/a~1b~0c/1/d");
  // Tiny numbers are no problem: they are zero, or close to it.
  EXPECT_EQ(
      c.post_json("/preview", R"({"scene": {"type": "plate"}, "time": {"end_s": 1e-400}})").status,
      200u);
  EXPECT_EQ(c.get("/health").status, 200u);
}

// The status line of a raw exchange.
std::string status_line(const std::string& answer) {
  return answer.substr(0, answer.find("\r\n"));
}

std::string raw(const ServerProcess& server, const std::string& bytes) {
  return raw_exchange(server.host(), server.port(), bytes, std::chrono::seconds(10));
}

// 6. DNS rebinding: a page of another site whose name was made to point at
// 127.0.0.1 sends its own name as Host. Only the server's names are answered.
TEST(ServerHosts, OneHostHeaderNamingThisServer) {
  ServerProcess server(
      {"--allowed-host", "gears.example", "--allowed-host", "pinned.example:8443"});
  const std::string port = server.port();
  // RFC 9112 section 3.2: no Host, or two, in HTTP/1.1: 400.
  EXPECT_EQ(status_line(raw(server, "GET /health HTTP/1.1\r\nConnection: close\r\n\r\n")),
            "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(
      status_line(raw(server, "GET /health HTTP/1.1\r\nHost: 127.0.0.1:" + port +
                                  "\r\nHost: 127.0.0.1:" + port + "\r\nConnection: close\r\n\r\n")),
      "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(status_line(raw(server, "GET /health HTTP/1.1\r\nHost: a b\r\n\r\n")),
            "HTTP/1.1 400 Bad Request");
  auto c = server.client();
  // Another name: 421, and no job is taken.
  const ClientResponse rebound =
      c.post_json("/jobs", tiny_job().dump(), {{"Host", "rebind.attacker.example:" + port}});
  EXPECT_EQ(rebound.status, 421u) << rebound.body;
  EXPECT_EQ(rebound.header("Content-Type"), "application/problem+json");
  EXPECT_NE(rebound.json().at("detail").get<std::string>().find("--allowed-host"),
            std::string::npos);
  EXPECT_EQ(c.get("/health", {{"Host", "rebind.attacker.example"}}).status, 421u);
  EXPECT_EQ(c.get("/", {{"Host", "rebind.attacker.example:" + port}}).status, 421u);
  EXPECT_EQ(c.get("/jobs").json().at("numberMatched"), 0);
  // The loopback names with this server's port, in any case.
  for (const std::string name : {"localhost", "127.0.0.1", "[::1]", "LocalHost"}) {
    EXPECT_EQ(c.get("/health", {{"Host", name + ":" + port}}).status, 200u) << name;
  }
  EXPECT_EQ(c.get("/health", {{"Host", "localhost:1"}}).status, 421u);  // another port
  // Names given with --allowed-host: any port, or the one given.
  EXPECT_EQ(c.get("/health", {{"Host", "gears.example"}}).status, 200u);
  EXPECT_EQ(c.get("/health", {{"Host", "Gears.Example:1234"}}).status, 200u);
  EXPECT_EQ(c.get("/health", {{"Host", "pinned.example:8443"}}).status, 200u);
  EXPECT_EQ(c.get("/health", {{"Host", "pinned.example:8080"}}).status, 421u);
  // HTTP/1.0 needs no Host (browsers always send one).
  EXPECT_EQ(status_line(raw(server, "GET /health HTTP/1.0\r\n\r\n")).substr(9, 3), "200");
}

TEST(ServerHosts, AnyHostWithAStar) {
  ServerProcess server({"--allowed-host", "*"});
  auto c = server.client();
  EXPECT_EQ(c.get("/health", {{"Host", "behind.proxy.example"}}).status, 200u);
}

// 8. RFC 9112 section 6.1: a transfer coding the server does not know is
// 501, not read as if it were absent.
// N10: a raw NUL in a body is an error, not the end of the body.
TEST_F(ServerHardening, ARawNulInABodyIsRefused) {
  auto c = server_->client();
  const std::string body = std::string("{\"scene\": {\"type\": \"plate\"}}") + '\0' + "junk";
  for (const char* target : {"/jobs", "/preview"}) {
    const ClientResponse r = c.post_json(target, body);
    EXPECT_EQ(r.status, 400u) << target << ": " << r.body;
    EXPECT_NE(r.body.find("NUL byte at offset 28"), std::string::npos) << r.body;
  }
}

TEST_F(ServerHardening, UnknownTransferCodingsAre501) {
  auto c = server_->client();
  const auto before = c.get("/jobs").json().at("numberMatched").get<int>();
  const std::string host = "Host: 127.0.0.1:" + server_->port() + "\r\n";
  const std::string head = "POST /jobs HTTP/1.1\r\n" + host + "Content-Type: application/json\r\n";
  const std::string chunks = "\r\n\r\n2\r\n{}\r\n0\r\n\r\n";
  EXPECT_EQ(status_line(raw(*server_, head + "Transfer-Encoding: gzip, chunked" + chunks)),
            "HTTP/1.1 501 Not Implemented");
  EXPECT_EQ(status_line(raw(*server_, head +
                                          "Transfer-Encoding: gzip\r\nTransfer-Encoding: "
                                          "chunked" +
                                          chunks)),
            "HTTP/1.1 501 Not Implemented");
  // chunked not last, twice, with Content-Length, in HTTP/1.0: the length is unknown, 400.
  EXPECT_EQ(status_line(raw(*server_, head + "Transfer-Encoding: chunked, gzip" + chunks)),
            "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(status_line(raw(*server_, head + "Transfer-Encoding: chunked, chunked" + chunks)),
            "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(
      status_line(raw(*server_, head + "Content-Length: 2\r\nTransfer-Encoding: chunked" + chunks)),
      "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(status_line(raw(*server_,
                            "POST /jobs HTTP/1.0\r\nContent-Type: "
                            "application/json\r\nTransfer-Encoding: chunked" +
                                chunks)),
            "HTTP/1.1 400 Bad Request");
  EXPECT_EQ(c.get("/jobs").json().at("numberMatched").get<int>(), before);
  // chunked alone is read (the body is "{}", the default job's preview).
  const std::string preview = raw(*server_, "POST /preview HTTP/1.1\r\n" + host +
                                                "Content-Type: application/json\r\n"
                                                "Connection: close\r\nTransfer-Encoding: Chunked" +
                                                chunks);
  EXPECT_EQ(status_line(preview), "HTTP/1.1 200 OK");
}

// 11. HTTP/1.0 is answered (one request per connection); other versions are
// not; a NUL in a path is named as such.
TEST_F(ServerHardening, HttpVersionsAndControlCharactersInPaths) {
  auto c = server_->client();
  const std::string id = submit(c, tiny_job());
  ASSERT_EQ(wait_final(c, id).at("status"), "successful");
  const std::string health = raw(*server_, "GET /health HTTP/1.0\r\n\r\n");
  EXPECT_EQ(status_line(health), "HTTP/1.1 200 OK");
  EXPECT_NE(health.find("Connection: close"), std::string::npos) << health.substr(0, 300);
  // An event stream to an HTTP/1.0 client is the body itself: no chunks.
  const std::string stream = raw(*server_, "GET /jobs/" + id + "/events HTTP/1.0\r\n\r\n");
  EXPECT_EQ(status_line(stream), "HTTP/1.1 200 OK");
  const std::string body = stream.substr(stream.find("\r\n\r\n") + 4);
  EXPECT_EQ(body.rfind("retry: 3000\n\n", 0), 0u) << body.substr(0, 200);
  EXPECT_NE(body.find("event: status"), std::string::npos);
  EXPECT_EQ(stream.find("Transfer-Encoding"), std::string::npos);
  EXPECT_EQ(status_line(raw(*server_, "GET /health HTTP/2.0\r\nHost: 127.0.0.1:" + server_->port() +
                                          "\r\n\r\n")),
            "HTTP/1.1 505 HTTP Version Not Supported");
  // N5: a request line whose version is not HTTP/d.d is malformed: 400, not 505.
  for (const char* line : {"GET /health HTTP/1.x", "GET /health FOO/1.1", "GET /health HTTP/11"}) {
    EXPECT_EQ(status_line(raw(*server_, std::string(line) +
                                            "\r\nHost: 127.0.0.1:" + server_->port() + "\r\n\r\n")),
              "HTTP/1.1 400 Bad Request")
        << line;
  }
  const ClientResponse nul = c.get("/health%00");
  EXPECT_EQ(nul.status, 400u);
  const std::string detail = nul.json().at("detail");
  EXPECT_NE(detail.find("control character"), std::string::npos) << detail;
  EXPECT_EQ(detail.find("'.'"), std::string::npos) << detail;
  EXPECT_EQ(c.get("/jobs/" + id + "/files/job.json%0a").status, 400u);
}

// 4. The dashboard behind --token-file: its files load without the token;
// the page logs in once and its cookie carries the token on everything a
// browser fetches by itself (images, downloads, event streams).
TEST(ServerToken, DashboardFilesAreOpenAndTheLoginCookieCarriesTheToken) {
  TempDir dir;
  const std::string token = "s3cret token;with,odd=chars";
  std::ofstream(dir.path() / "token") << token << "\n";
  ServerProcess server({"--token-file", (dir.path() / "token").string(), "--threads-per-job", "1"});
  auto c = server.client();
  // The page and its scripts and styles: no token needed.
  const ClientResponse page = c.get("/", {{"Accept", "text/html"}});
  EXPECT_EQ(page.status, 200u);
  EXPECT_EQ(page.header("Content-Type"), "text/html; charset=utf-8");
  for (const char* file :
       {"/index.html", "/js/app.js", "/js/api.js", "/css/app.css", "/favicon.svg"}) {
    EXPECT_EQ(c.get(file).status, 200u) << file;
  }
  EXPECT_EQ(c.request("HEAD", "/js/app.js").status, 200u);
  // Data needs it.
  for (const char* path : {"/", "/jobs", "/schema", "/health", "/no-such-file.js"}) {
    EXPECT_EQ(c.get(path, {{"Accept", "application/json"}}).status, 401u) << path;
  }
  const HttpClient::Headers bearer = {{"Authorization", "Bearer " + token}};
  const ClientResponse submitted = c.post_json("/jobs", tiny_job().dump(), bearer);
  ASSERT_EQ(submitted.status, 201u) << submitted.body;
  const std::string id = submitted.json().at("jobID");

  // ?access_token= is for EventSource: event streams only.
  std::string encoded;
  for (const char ch : token) {
    const auto u = static_cast<unsigned char>(ch);
    char buf[4];
    std::snprintf(buf, sizeof buf, "%%%02X", u);
    encoded += std::isalnum(u) ? std::string(1, ch) : std::string(buf);
  }
  EXPECT_EQ(c.get("/health?access_token=" + encoded).status, 401u);
  EXPECT_EQ(c.get("/jobs/" + id + "?access_token=" + encoded).status, 401u);
  std::vector<SseEvent> events;
  const ClientResponse stream =
      c.events("/jobs/" + id + "/events?access_token=" + encoded, [&](const SseEvent& e) {
        events.push_back(e);
        return false;
      });
  EXPECT_EQ(stream.status, 200u);
  EXPECT_EQ(events.size(), 1u);

  // Whether a token is needed, and whether the request carries it.
  EXPECT_EQ(c.get("/login").json(), json({{"token_required", true}, {"signed_in", false}}));
  EXPECT_EQ(c.get("/login", bearer).json().at("signed_in"), true);
  // The login call: a wrong token is refused, the right one sets the cookie.
  EXPECT_EQ(c.post_json("/login", R"({"token": "guess"})").status, 401u);
  EXPECT_EQ(c.post_json("/login", R"({"tok": "guess"})").status, 400u);
  const ClientResponse login = c.post_json("/login", json{{"token", token}}.dump());
  ASSERT_EQ(login.status, 204u) << login.body;
  const std::string set_cookie = login.header("Set-Cookie");
  EXPECT_NE(set_cookie.find("HttpOnly"), std::string::npos) << set_cookie;
  EXPECT_NE(set_cookie.find("SameSite=Strict"), std::string::npos) << set_cookie;
  EXPECT_NE(set_cookie.find("Path=/"), std::string::npos) << set_cookie;
  const std::string cookie = set_cookie.substr(0, set_cookie.find(';'));
  EXPECT_EQ(cookie.find(' '), std::string::npos) << cookie;
  EXPECT_EQ(cookie.find(','), std::string::npos) << cookie;
  const HttpClient::Headers with_cookie = {{"Cookie", "theme=dark; " + cookie}};
  EXPECT_EQ(c.get("/jobs", with_cookie).status, 200u);
  EXPECT_EQ(c.get("/login", with_cookie).json().at("signed_in"), true);
  auto authed = server.client();
  authed.set_default_header("Authorization", "Bearer " + token);
  EXPECT_EQ(wait_final(authed, id).at("status"), "successful");
  EXPECT_EQ(c.get("/jobs/" + id + "/files/job.json", with_cookie).status, 200u);
  EXPECT_EQ(c.get("/jobs", {{"Cookie", "gearsph_token=wrong"}}).status, 401u);
  // Changes with the cookie only from this server's own pages.
  const std::string self = "http://127.0.0.1:" + server.port();
  HttpClient::Headers same = with_cookie, other = with_cookie, port = with_cookie;
  same.emplace_back("Origin", self);
  other.emplace_back("Origin", "http://evil.example");
  port.emplace_back("Origin", "http://127.0.0.1:1");
  EXPECT_EQ(c.post_json("/preview", tiny_job().dump(), same).status, 200u);
  EXPECT_EQ(c.post_json("/preview", tiny_job().dump(), other).status, 403u);
  EXPECT_EQ(c.post_json("/preview", tiny_job().dump(), port).status, 403u);
  EXPECT_EQ(c.get("/jobs", other).status, 200u);  // reading is harmless: CORS keeps the answer
  // Logging out clears the cookie.
  const ClientResponse logout = c.request("DELETE", "/login");
  EXPECT_EQ(logout.status, 204u);
  EXPECT_NE(logout.header("Set-Cookie").find("Max-Age=0"), std::string::npos);
}

// N12: the cookie is an opaque session id (never the token), revoked by
// DELETE /login; failed logins from one address are limited (429).
TEST(ServerToken, SessionsAreOpaqueRevocableAndFailedLoginsLimited) {
  TempDir dir;
  const std::string token = "the-service-token-0123456789";
  std::ofstream(dir.path() / "token") << token << "\n";
  ServerProcess server({"--token-file", (dir.path() / "token").string(), "--threads-per-job", "1"});
  auto c = server.client();
  auto session = [&] {
    const ClientResponse login = c.post_json("/login", json{{"token", token}}.dump());
    EXPECT_EQ(login.status, 204u) << login.body;
    const std::string set = login.header("Set-Cookie");
    return set.substr(0, set.find(';'));
  };
  const std::string first = session(), second = session();
  EXPECT_EQ(first.rfind("gearsph_session=", 0), 0u) << first;
  EXPECT_EQ(first.find(token), std::string::npos) << "the cookie holds the token: " << first;
  EXPECT_NE(first, second);
  EXPECT_EQ(c.get("/jobs", {{"Cookie", first}}).status, 200u);
  EXPECT_EQ(c.get("/jobs", {{"Cookie", second}}).status, 200u);
  // The token itself is no session.
  EXPECT_EQ(c.get("/jobs", {{"Cookie", "gearsph_session=" + token}}).status, 401u);
  // Logging out revokes the session on the server: the same cookie, sent again, is refused.
  const ClientResponse logout = c.request("DELETE", "/login", "", {{"Cookie", first}});
  EXPECT_EQ(logout.status, 204u);
  EXPECT_EQ(c.get("/jobs", {{"Cookie", first}}).status, 401u);
  EXPECT_EQ(c.get("/login", {{"Cookie", first}}).json().at("signed_in"), false);
  EXPECT_EQ(c.get("/jobs", {{"Cookie", second}}).status, 200u);  // others stay

  // Five wrong tokens a minute from one address, then 429 for any login.
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(c.post_json("/login", R"({"token": "guess"})").status, 401u) << i;
  }
  const ClientResponse limited = c.post_json("/login", R"({"token": "guess"})");
  EXPECT_EQ(limited.status, 429u) << limited.body;
  EXPECT_EQ(limited.header("Content-Type"), "application/problem+json");
  const int retry = std::stoi(limited.header("Retry-After"));
  EXPECT_GE(retry, 1);
  EXPECT_LE(retry, 60);
  EXPECT_EQ(c.post_json("/login", json{{"token", token}}.dump()).status, 429u);
  // The bearer token on requests is not a login: it still works.
  EXPECT_EQ(c.get("/jobs", {{"Authorization", "Bearer " + token}}).status, 200u);
}

// N12: the queue has quotas, overall (503) and per client address (429),
// each with Retry-After and a sentence; a study counts all its jobs.
TEST(ServerQueue, QuotasRefuseJobsBeyondTheQueue) {
  {
    ServerProcess server({"--no-local-workers", "--max-queued-per-client", "2"});
    auto c = server.client();
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump()).status, 201u);
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump()).status, 201u);
    const ClientResponse third = c.post_json("/jobs", tiny_job().dump());
    EXPECT_EQ(third.status, 429u) << third.body;
    EXPECT_EQ(third.json().at("type"), "urn:gearsph:problem:queue-full");
    EXPECT_NE(third.json().at("detail").get<std::string>().find("--max-queued-per-client"),
              std::string::npos);
    EXPECT_FALSE(third.header("Retry-After").empty());
    EXPECT_EQ(c.get("/jobs").json().at("jobs").size(), 2u);  // nothing stored
  }
  {
    ServerProcess server({"--no-local-workers", "--max-queued", "3"});
    auto c = server.client();
    const json study = {{"base", tiny_job()},
                        {"axes", {{{"pointer", "/time/end_s"}, {"values", {1e-3, 2e-3}}}}}};
    EXPECT_EQ(c.post_json("/studies", study.dump()).status, 201u);
    const ClientResponse more = c.post_json("/studies", study.dump());
    EXPECT_EQ(more.status, 503u) << more.body;
    EXPECT_NE(more.json().at("detail").get<std::string>().find("--max-queued"), std::string::npos);
    EXPECT_FALSE(more.header("Retry-After").empty());
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump()).status, 201u);  // the third fits
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump()).status, 503u);
  }
}

// Issue 49: the quota holds exactly under concurrent submissions: the
// count and the insert are one transaction of the store. Twelve clients
// at once, each on its own connection, for a queue of five.
TEST(ServerQueue, ConcurrentSubmissionsNeverOverfillTheQueue) {
  ServerProcess server({"--no-local-workers", "--max-queued", "5"});
  constexpr int kClients = 12, kEach = 2;
  std::atomic<int> created{0}, full{0}, other{0};
  std::vector<std::thread> clients;
  for (int i = 0; i < kClients; ++i) {
    clients.emplace_back([&] {
      auto c = server.client(std::chrono::seconds(60));
      for (int k = 0; k < kEach; ++k) {
        const unsigned status = c.post_json("/jobs", tiny_job().dump()).status;
        if (status == 201u) {
          ++created;
        } else if (status == 503u) {
          ++full;
        } else {
          ++other;
        }
      }
    });
  }
  for (auto& t : clients) t.join();
  EXPECT_EQ(created.load(), 5);
  EXPECT_EQ(full.load(), kClients * kEach - 5);
  EXPECT_EQ(other.load(), 0);
  auto c = server.client();
  EXPECT_EQ(c.get("/jobs?status=accepted").json().at("jobs").size(), 5u);
}

// Issue 49: the per-client quota counts the authenticated identity where
// there is one (each dashboard session its own share, the bearer token
// one), and the address X-Forwarded-For names only from a --trusted-proxy.
TEST(ServerQueue, TheClientQuotaIsPerIdentityAndTrustedProxiesOnly) {
  {
    // The test connects from 127.0.0.1: here a proxy the server trusts.
    ServerProcess server(
        {"--no-local-workers", "--max-queued-per-client", "1", "--trusted-proxy", "127.0.0.1"});
    auto c = server.client();
    auto from = [&](const std::string& address) {
      return c.post_json("/jobs", tiny_job().dump(), {{"X-Forwarded-For", address}});
    };
    EXPECT_EQ(from("203.0.113.1").status, 201u);
    const ClientResponse again = from("203.0.113.1");
    EXPECT_EQ(again.status, 429u) << again.body;
    EXPECT_NE(again.json().at("detail").get<std::string>().find("203.0.113.1"), std::string::npos)
        << again.body;
    EXPECT_EQ(from("203.0.113.2").status, 201u);  // another client behind the same proxy
    // What a client writes left of the proxy's entry changes nothing.
    EXPECT_EQ(from("198.51.100.7, 203.0.113.1").status, 429u);
  }
  {
    // Not trusted (the default): X-Forwarded-For is the client's to invent.
    ServerProcess server({"--no-local-workers", "--max-queued-per-client", "1"});
    auto c = server.client();
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump(), {{"X-Forwarded-For", "203.0.113.1"}}).status,
              201u);
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump(), {{"X-Forwarded-For", "203.0.113.2"}}).status,
              429u);
  }
  {
    TempDir dir;
    const std::string token = "the-service-token-0123456789";
    std::ofstream(dir.path() / "token") << token << "\n";
    ServerProcess server({"--no-local-workers", "--max-queued-per-client", "1", "--token-file",
                          (dir.path() / "token").string()});
    auto c = server.client();
    auto login = [&] {
      const std::string set =
          c.post_json("/login", json{{"token", token}}.dump()).header("Set-Cookie");
      return set.substr(0, set.find(';'));
    };
    const std::string one = login(), two = login();
    // Two dashboards from one address: each session has its own share.
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump(), {{"Cookie", one}}).status, 201u);
    const ClientResponse again = c.post_json("/jobs", tiny_job().dump(), {{"Cookie", one}});
    EXPECT_EQ(again.status, 429u) << again.body;
    EXPECT_NE(again.json().at("detail").get<std::string>().find("session "), std::string::npos);
    EXPECT_EQ(again.json().at("detail").get<std::string>().find(one.substr(16)), std::string::npos)
        << "the answer shows the session id: " << again.body;
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump(), {{"Cookie", two}}).status, 201u);
    // The bearer token is one identity, whoever holds it.
    const HttpClient::Headers bearer = {{"Authorization", "Bearer " + token}};
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump(), bearer).status, 201u);
    EXPECT_EQ(c.post_json("/jobs", tiny_job().dump(), bearer).status, 429u);
  }
}

// Issue 49: sessions are in the job store, so two API nodes on one store
// (here SQLite, `--store sqlite:PATH`) know each other's logins, and a
// DELETE /login on one revokes the session on the other.
TEST(ServerToken, SessionsHoldOnEveryApiNodeOfAStore) {
  TempDir dir;
  const std::string token = "the-service-token-0123456789";
  std::ofstream(dir.path() / "token") << token << "\n";
  const std::vector<std::string> args = {"--store",
                                         "sqlite:" + (dir.path() / "jobs.db").string(),
                                         "--results",
                                         (dir.path() / "results").string(),
                                         "--no-local-workers",
                                         "--token-file",
                                         (dir.path() / "token").string()};
  ServerProcess one(args), two(args);
  auto c1 = one.client();
  auto c2 = two.client();
  const ClientResponse login = c1.post_json("/login", json{{"token", token}}.dump());
  ASSERT_EQ(login.status, 204u) << login.body;
  const std::string set = login.header("Set-Cookie");
  const std::string cookie = set.substr(0, set.find(';'));
  EXPECT_EQ(c2.get("/jobs", {{"Cookie", cookie}}).status, 200u) << two.log();
  EXPECT_EQ(c2.get("/login", {{"Cookie", cookie}}).json().at("signed_in"), true);
  // Revoked on the first node: refused on the second within kSessionRecheck (2 s).
  EXPECT_EQ(c1.request("DELETE", "/login", "", {{"Cookie", cookie}}).status, 204u);
  EXPECT_EQ(c1.get("/jobs", {{"Cookie", cookie}}).status, 401u);
  unsigned status = 0;
  const auto until = Clock::now() + std::chrono::seconds(10);
  while (Clock::now() < until && (status = c2.get("/jobs", {{"Cookie", cookie}}).status) != 401u) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(status, 401u);
  // A login on the second node, after the first restarted: still known.
  const std::string set2 =
      c2.post_json("/login", json{{"token", token}}.dump()).header("Set-Cookie");
  const std::string cookie2 = set2.substr(0, set2.find(';'));
  one.stop(SIGTERM);
  one.start();
  auto c1again = one.client();
  EXPECT_EQ(c1again.get("/jobs", {{"Cookie", cookie2}}).status, 200u);
}

int status_rank(const std::string& s) {
  if (s == "accepted") return 0;
  if (s == "running") return 1;
  return 2;  // final
}

// 2 and 3. A finished job's stream, resumed: at its final event it ends at
// once (204: a browser's EventSource stops reconnecting); from a stale id
// it sends the current status once and ends; a status never goes back.
TEST_F(ServerHardening, ResumedStreamsOfFinishedJobsEnd) {
  auto c = server_->client(std::chrono::seconds(10));
  const std::string id = submit(c, tiny_job(0.05));
  ASSERT_EQ(wait_final(c, id).at("status"), "successful");
  const std::string path = "/jobs/" + id + "/events";
  auto read = [&](const HttpClient::Headers& headers, std::vector<SseEvent>& out) {
    return c.events(
        path,
        [&](const SseEvent& e) {
          out.push_back(e);
          return out.size() < 1000;
        },
        headers);
  };
  std::vector<SseEvent> whole;
  ASSERT_EQ(read({}, whole).status, 200u);
  ASSERT_EQ(whole.size(), 1u);  // the job had finished: its final status, then the end
  EXPECT_EQ(json::parse(whole[0].data).at("status"), "successful");

  // Resumed at its final event: nothing more will come.
  std::vector<SseEvent> after_final;
  ClientResponse head;
  ASSERT_NO_THROW(head = read({{"Last-Event-ID", whole[0].id}}, after_final));
  EXPECT_EQ(head.status, 204u);
  EXPECT_TRUE(after_final.empty());

  // A stale id: the status once, under a new id, then the end.
  std::vector<SseEvent> stale;
  ASSERT_NO_THROW(head = read({{"Last-Event-ID", "1"}}, stale));
  EXPECT_EQ(head.status, 200u);
  ASSERT_EQ(stale.size(), 1u);
  EXPECT_EQ(stale[0].event, "status");
  EXPECT_NE(stale[0].id, "1");
  EXPECT_EQ(json::parse(stale[0].data).at("status"), "successful");
  std::vector<SseEvent> again;
  ASSERT_NO_THROW(head = read({{"Last-Event-ID", stale[0].id}}, again));
  EXPECT_EQ(head.status, 204u);

  // An id from the future (another server's clock): the same as a stale one.
  std::vector<SseEvent> future;
  ASSERT_NO_THROW(read({{"Last-Event-ID", "18446744073709551615"}}, future));
  ASSERT_EQ(future.size(), 1u);
  EXPECT_EQ(json::parse(future[0].data).at("status"), "successful");

  // The stream of all jobs resumed from a stale id starts with a reset, and
  // replays nothing older.
  std::vector<SseEvent> all;
  ASSERT_NO_THROW(c.events("/events",
                           [&](const SseEvent& e) {
                             all.push_back(e);
                             return false;
                           },
                           {{"Last-Event-ID", "1"}}));
  ASSERT_EQ(all.size(), 1u);
  EXPECT_EQ(all[0].event, "reset");
  EXPECT_GT(std::stoull(all[0].id), 1u);
}

// 3. A job followed from its start and resumed in the middle: the statuses
// a client sees only move forward.
TEST_F(ServerHardening, StatusNeverGoesBackOnAStream) {
  auto c = server_->client(std::chrono::seconds(30));
  const std::string id = submit(c, tiny_job(0.1));
  std::vector<SseEvent> events;
  c.events("/jobs/" + id + "/events", [&](const SseEvent& e) {
    events.push_back(e);
    return true;
  });
  ASSERT_GE(events.size(), 2u);
  for (std::size_t from = 0; from < events.size(); ++from) {
    std::vector<SseEvent> seen(events.begin(), events.begin() + static_cast<long>(from) + 1);
    c.events("/jobs/" + id + "/events",
             [&](const SseEvent& e) {
               seen.push_back(e);
               return true;
             },
             {{"Last-Event-ID", events[from].id}});
    int rank = 0;
    for (const SseEvent& e : seen) {
      const int r = status_rank(json::parse(e.data).at("status"));
      EXPECT_GE(r, rank) << "resumed after event " << from << ": " << e.data;
      rank = std::max(rank, r);
    }
    EXPECT_EQ(json::parse(seen.back().data).at("status"), "successful");
  }
}

// 5. The image cache on its own: a byte budget, least recently used out first.
TEST(ImageCache, KeepsTheRecentlyUsedWithinItsBudget) {
  ImageCache cache(250);
  cache.put("a/1", std::string(100, 'a'));
  cache.put("a/2", std::string(100, 'b'));
  ASSERT_TRUE(cache.get("a/1"));            // a/1 is now the most recent
  cache.put("b/1", std::string(100, 'c'));  // a/2 makes room
  EXPECT_FALSE(cache.get("a/2"));
  EXPECT_EQ(*cache.get("a/1"), std::string(100, 'a'));
  EXPECT_TRUE(cache.get("b/1"));
  EXPECT_EQ(cache.stats().at("bytes"), 200);
  cache.put("b/2", std::string(300, 'd'));  // over the whole budget: not kept
  EXPECT_FALSE(cache.get("b/2"));
  cache.put("a/1", std::string(50, 'e'));  // replaced, not counted twice
  EXPECT_EQ(cache.stats().at("bytes"), 150);
  cache.drop_job("a");  // a dismissed job's images go
  EXPECT_FALSE(cache.get("a/1"));
  EXPECT_TRUE(cache.get("b/1"));
  EXPECT_EQ(cache.stats().at("entries"), 1);
  ImageCache none(0);
  none.put("a/1", "x");
  EXPECT_FALSE(none.get("a/1"));
}

// 7. A job dismissed while it runs: its files are neither listed nor served,
// and they are deleted once the run has stopped; a second DELETE removes
// whatever is left (a crash, say).
TEST(ServerDismiss, ARunningJobsFilesGoOnceItStops) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  json long_job = tiny_job(20.0);
  long_job["output"] = {{"frames", 400}};
  const std::string id = submit(c, long_job);
  wait_for(c, id, [](const json& s) { return s.at("step").get<int>() > 0; });
  const fs::path dir = server.data() / "jobs" / id;
  // A run writes in its claim's own directory until its outcome is recorded.
  fs::path attempt;
  for (const auto& e : fs::directory_iterator(server.data() / "jobs" / ".attempts")) {
    if (e.path().filename().string().rfind(id + ".", 0) == 0) attempt = e.path();
  }
  ASSERT_TRUE(fs::exists(attempt / "job.json"));
  EXPECT_FALSE(fs::exists(dir));
  ASSERT_EQ(c.get("/jobs/" + id + "/files/job.json").status, 200u);

  ASSERT_EQ(c.request("DELETE", "/jobs/" + id).json().at("status"), "dismissed");
  EXPECT_EQ(c.get("/jobs/" + id + "/files").status, 404u);
  EXPECT_EQ(c.get("/jobs/" + id + "/files/job.json").status, 404u);
  wait_for(c, id, [](const json& s) {
    return s.at("message").get<std::string>().find("stopped at step") != std::string::npos;
  });
  EXPECT_FALSE(fs::exists(dir));
  EXPECT_FALSE(fs::exists(attempt));

  // Left behind by a run that could not clean up: the next DELETE does.
  fs::create_directories(dir);
  std::ofstream(dir / "history.csv") << "time_s\n0\n";
  ASSERT_EQ(c.request("DELETE", "/jobs/" + id).status, 200u);
  EXPECT_FALSE(fs::exists(dir));
  expect_consistent_store(server.data());
}

// 9. The run-time estimate counts writing the output: a tiny job asked for
// 10,000 frames and a million history points ran for minutes, not seconds.
TEST_F(ServerHardening, RunTimeEstimateCountsTheOutput) {
  auto c = server_->client();
  json plain = tiny_job(0.05);
  json heavy = plain;
  heavy["output"] = {{"frames", 10000}, {"history_points", 1000000}};
  const json a = c.post_json("/preview", plain.dump()).json();
  const json b = c.post_json("/preview", heavy.dump()).json();
  ASSERT_TRUE(a.contains("run_time")) << a.dump().substr(0, 300);
  ASSERT_TRUE(b.contains("run_time")) << b.dump().substr(0, 300);
  const json& ra = a.at("run_time");
  const json& rb = b.at("run_time");
  // The same computing, far more writing.
  EXPECT_DOUBLE_EQ(ra.at("compute_s").get<double>(), rb.at("compute_s").get<double>());
  EXPECT_GT(rb.at("output_s").get<double>(), 10 * ra.at("output_s").get<double>());
  EXPECT_GT(rb.at("output_s").get<double>(), rb.at("compute_s").get<double>());
  // Such a run took about three minutes (3,974 frames of 315 particles);
  // the estimate was 2 s.
  EXPECT_GT(rb.at("output_s").get<double>(), 30.0);
  for (const json* r : {&ra, &rb}) {
    EXPECT_DOUBLE_EQ(r->at("wall_s").get<double>(),
                     r->at("compute_s").get<double>() + r->at("output_s").get<double>());
  }
  EXPECT_NE(rb.at("note").get<std::string>().find("frames"), std::string::npos);
}

// 10. A stand-in for a proxy that serves the API below /api: it answers a
// submission, the job's event stream (one final status), its results and a
// file, and records every target asked for.
class ApiBelowAPath {
 public:
  explicit ApiBelowAPath(std::string id)
      : id_(std::move(id)), acceptor_(ioc_, {boost::asio::ip::make_address("127.0.0.1"), 0}) {
    thread_ = std::thread([this] { serve(); });
  }
  ~ApiBelowAPath() {
    // A connection of its own wakes the accepting thread, which then stops.
    stopping_ = true;
    boost::system::error_code ec;
    boost::asio::ip::tcp::socket wake(ioc_);
    wake.connect(acceptor_.local_endpoint(), ec);
    thread_.join();
  }
  std::string url() const {
    return "http://127.0.0.1:" + std::to_string(acceptor_.local_endpoint().port());
  }
  std::vector<std::string> targets() {
    std::lock_guard<std::mutex> lock(mutex_);
    return targets_;
  }

 private:
  void serve() {
    namespace http = boost::beast::http;
    for (;;) {
      boost::system::error_code ec;
      boost::asio::ip::tcp::socket socket(ioc_);
      acceptor_.accept(socket, ec);
      if (ec || stopping_) return;
      boost::beast::flat_buffer buffer;
      for (;;) {
        http::request<http::string_body> req;
        http::read(socket, buffer, req, ec);
        if (ec) break;
        const std::string target(req.target());
        {
          std::lock_guard<std::mutex> lock(mutex_);
          targets_.push_back(target);
        }
        http::response<http::string_body> res{http::status::ok, 11};
        const std::string job = "/api/jobs/" + id_;
        const json status = {{"jobID", id_}, {"status", "successful"}, {"message", "done"}};
        if (req.method() == http::verb::post && target == "/api/jobs") {
          res.result(http::status::created);
          res.set(http::field::location, "/jobs/" + id_);
          res.set(http::field::content_type, "application/json");
          res.body() = json{{"jobID", id_}, {"status", "accepted"}}.dump();
        } else if (target == job + "/events") {
          res.set(http::field::content_type, "text/event-stream");
          res.body() = "id: 7\nevent: status\ndata: " + status.dump() + "\n\n";
          res.keep_alive(false);
        } else if (target == job) {
          res.set(http::field::content_type, "application/json");
          res.body() = status.dump();
        } else if (target == job + "/results") {
          res.set(http::field::content_type, "application/json");
          res.body() =
              json{{"jobID", id_},
                   {"files",
                    {{{"name", "history.csv"}, {"href", "/jobs/" + id_ + "/files/history.csv"}}}}}
                  .dump();
        } else if (target == job + "/files/history.csv") {
          res.set(http::field::content_type, "text/csv");
          res.body() = "time_s\n0\n";
        } else {
          res.result(http::status::not_found);
        }
        res.prepare_payload();
        http::write(socket, res, ec);
        if (ec || !res.keep_alive() || !req.keep_alive()) break;
      }
    }
  }

  std::string id_;
  std::atomic<bool> stopping_{false};
  boost::asio::io_context ioc_;
  boost::asio::ip::tcp::acceptor acceptor_;
  std::thread thread_;
  std::mutex mutex_;
  std::vector<std::string> targets_;
};

int run_command(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// gearsph submit --server http://host:port/api: every request below /api,
// the job's URL printed as it is, links of the server's followed below it.
TEST(ServerSubmitCli, KeepsThePathOfTheServerUrl) {
  TempDir dir;
  const std::string id = "0b5e8d3c-6c1f-4f57-9a3e-1f0c2a9d4e71";
  ApiBelowAPath proxy(id);
  std::ofstream(dir.path() / "job.json") << tiny_job().dump();
  const int status = run_command(
      std::string(GEARSPH_BINARY) + " submit " + (dir.path() / "job.json").string() + " --server " +
      proxy.url() + "/api/ --wait --out " + (dir.path() / "out").string() + " > " +
      (dir.path() / "stdout").string() + " 2> " + (dir.path() / "stderr").string());
  const std::string err = slurp(dir.path() / "stderr");
  EXPECT_EQ(status, 0) << err;
  EXPECT_EQ(slurp(dir.path() / "stdout"), id + "\n");
  EXPECT_NE(err.find(proxy.url() + "/api/jobs/" + id), std::string::npos) << err;
  EXPECT_EQ(slurp(dir.path() / "out" / "history.csv"), "time_s\n0\n") << err;
  const auto targets = proxy.targets();
  EXPECT_GE(targets.size(), 4u);
  for (const std::string& t : targets) EXPECT_EQ(t.rfind("/api/", 0), 0u) << t;
}

// --wait with the server gone: it tries for --retry-for seconds, then says so.
TEST(ServerSubmitCli, GivesUpAfterRetryFor) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  std::ofstream(server.dir() / "job.json") << tiny_job(20.0).dump();
  auto submitting = std::async(std::launch::async, [&] {
    return run_command(std::string(GEARSPH_BINARY) + " submit " +
                       (server.dir() / "job.json").string() + " --server " + server.url() +
                       " --wait --retry-for 2 > " + (server.dir() / "submit.out").string() +
                       " 2> " + (server.dir() / "submit.err").string());
  });
  auto c = server.client();
  std::string id;
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (id.empty() && Clock::now() < deadline) {
    const json running = c.get("/jobs?status=running").json();
    if (!running.at("jobs").empty()) id = running.at("jobs").at(0).at("jobID");
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_FALSE(id.empty());
  server.stop(SIGKILL);
  ASSERT_EQ(submitting.wait_for(std::chrono::seconds(120)), std::future_status::ready);
  const std::string err = slurp(server.dir() / "submit.err");
  EXPECT_EQ(submitting.get(), 1) << err;
  EXPECT_NE(err.find("--retry-for 2"), std::string::npos) << err;
}

TEST(ServerSubmitCli, ServerUrls) {
  const Url plain = Url::parse("http://127.0.0.1:8080");
  EXPECT_EQ(plain.base, "");
  EXPECT_EQ(plain.root(), "http://127.0.0.1:8080");
  const Url proxied = Url::parse("http://gears.example/sph/api/");
  EXPECT_EQ(proxied.host, "gears.example");
  EXPECT_EQ(proxied.port, "80");
  EXPECT_EQ(proxied.base, "/sph/api");
  EXPECT_EQ(Url::parse("http://[::1]:9000/x").root(), "http://[::1]:9000/x");
  EXPECT_THROW(Url::parse("https://gears.example"), std::invalid_argument);
  EXPECT_THROW(Url::parse("http://gears.example/api?x=1"), std::invalid_argument);
}

// Every option a command reads is in its --help.
TEST(CliHelp, ListsEveryOptionOfEveryCommand) {
  const std::map<std::string, std::vector<std::string>> commands_of = {
      {"cmd_run.cpp", {"run"}},
      {"cmd_validate.cpp", {"validate"}},
      {"cmd_study.cpp", {"study"}},
      {"cmd_bench.cpp", {"bench"}},
      {"cmd_geometry.cpp", {"geometry"}},
      {"cmd_render.cpp", {"render", "plot"}},
      {"cmd_serve.cpp", {"serve"}},
      {"cmd_submit.cpp", {"submit"}},
      {"cmd_worker.cpp", {"worker"}},
      {"cmd_fe.cpp", {"fe"}},
      {"cmd_rate.cpp", {"rate"}},
      {"cmd_speed_sweep.cpp", {"study"}},
      {"cmd_fe_accuracy_map.cpp", {"validate"}}};
  const std::regex read_option(
      R"re((?:option|flag|integer)\("([a-z0-9-]+)"|args, "([a-z0-9-]+)")re");
  int files = 0;
  for (const auto& e : fs::directory_iterator(fs::path(GEARSPH_SOURCE_DIR) / "apps" / "gearsph")) {
    const std::string file = e.path().filename().string();
    if (file.rfind("cmd_", 0) != 0 || e.path().extension() != ".cpp") continue;
    const auto it = commands_of.find(file);
    if (file == "cmd_serve_images.cpp") continue;  // no command of its own
    ASSERT_NE(it, commands_of.end()) << file << ": which command is it?";
    ++files;
    std::string help;
    for (const std::string& cmd : it->second) {
      FILE* pipe = popen((std::string(GEARSPH_BINARY) + " " + cmd + " --help").c_str(), "r");
      ASSERT_NE(pipe, nullptr);
      char buf[4096];
      for (std::size_t got; (got = std::fread(buf, 1, sizeof buf, pipe)) > 0;)
        help.append(buf, got);
      pclose(pipe);
    }
    const std::string source = slurp(e.path());
    for (std::sregex_iterator m(source.begin(), source.end(), read_option), end; m != end; ++m) {
      const std::string name = (*m)[1].matched ? (*m)[1].str() : (*m)[2].str();
      const std::regex listed("--" + name + "([^a-z0-9-]|$)");
      EXPECT_TRUE(std::regex_search(help, listed))
          << "gearsph " << it->second.front() << " reads --" << name
          << " but its --help does not list it:\n"
          << help;
    }
  }
  EXPECT_EQ(files, static_cast<int>(commands_of.size()));
}

// 14. OGC API - Processes where the service claims it: qualified inputs,
// results by output id, the job list's parameters honoured or refused.
TEST_F(ServerHardening, OgcQualifiedInputsResultsAndJobListParameters) {
  auto c = server_->client();
  const std::string execute = "/processes/gearsph-simulation/execution";
  const ClientResponse qualified = c.post_json(
      execute,
      json{{"inputs", {{"job", {{"value", tiny_job()}, {"mediaType", "application/json"}}}}},
           {"outputs", {{"summary", json::object()}}},
           {"response", "document"}}
          .dump());
  ASSERT_EQ(qualified.status, 201u) << qualified.body;
  const std::string id = qualified.json().at("jobID");
  json bad = tiny_job();
  bad["time"]["end_s"] = -1;
  const ClientResponse invalid =
      c.post_json(execute, json{{"inputs", {{"job", {{"value", bad}}}}}}.dump());
  ASSERT_EQ(invalid.status, 400u);
  EXPECT_EQ(invalid.json().at("errors").at(0).at("pointer"), "/inputs/job/value/time/end_s");
  const auto refused = [&](const json& request) {
    const ClientResponse r = c.post_json(execute, request.dump());
    EXPECT_EQ(r.status, 400u) << request.dump() << ": " << r.body;
    return r.status == 400u ? r.json().at("errors").at(0).at("pointer").get<std::string>()
                            : std::string();
  };
  EXPECT_EQ(refused({{"inputs", {{"job", {{"value", tiny_job()}, {"mediaType", "text/csv"}}}}}}),
            "/inputs/job/mediaType");
  EXPECT_EQ(refused({{"inputs", {{"job", {{"href", "http://example.com/job.json"}}}}}}),
            "/inputs/job/href");
  EXPECT_EQ(refused({{"inputs", {{"job", tiny_job()}, {"mesh", 1}}}}), "/inputs/mesh");
  EXPECT_EQ(refused({{"inputs", {{"job", tiny_job()}}}, {"response", "raw"}}), "/response");
  EXPECT_EQ(refused({{"inputs", {{"job", tiny_job()}}}, {"subscriber", json::object()}}),
            "/subscriber");
  EXPECT_EQ(refused({{"inputs", {{"job", tiny_job()}}}, {"outputs", {{"mesh", json::object()}}}}),
            "/outputs/mesh");

  // Results by the declared output ids.
  ASSERT_EQ(wait_final(c, id).at("status"), "successful");
  const json results = c.get("/jobs/" + id + "/results").json();
  EXPECT_TRUE(results.at("summary").contains("max_von_mises_Pa"));
  EXPECT_EQ(results.at("history").at("href"), "/jobs/" + id + "/files/history.csv");
  EXPECT_EQ(results.at("history").at("type"), "text/csv; charset=utf-8");
  EXPECT_EQ(c.get(results.at("history").at("href")).status, 200u);
#ifdef GEARSPH_WITH_RENDER
  EXPECT_EQ(results.at("results").at("href"), "/jobs/" + id + "/files/results.h5");
#endif
  const json outputs = c.get("/processes/gearsph-simulation").json().at("outputs");
  for (const char* output : {"summary", "history", "results"}) {
    EXPECT_TRUE(outputs.contains(output)) << output;
  }

  // The job list: every OGC parameter honoured, anything else refused.
  const auto matched = [&](const std::string& query) {
    const ClientResponse r = c.get("/jobs?" + query);
    EXPECT_EQ(r.status, 200u) << query << ": " << r.body;
    return r.status == 200u ? r.json().at("numberMatched").get<int>() : -1;
  };
  const int all = matched("limit=1");
  ASSERT_GE(all, 1);
  EXPECT_EQ(matched("processID=gearsph-simulation"), all);
  EXPECT_EQ(matched("processID=other"), 0);
  EXPECT_EQ(matched("type=process"), all);
  EXPECT_EQ(matched("type=other"), 0);
  EXPECT_EQ(matched("datetime=2000-01-01T00:00:00Z/.."), all);
  EXPECT_EQ(matched("datetime=../2000-01-01"), 0);
  EXPECT_EQ(matched("datetime=2000-01-01T00:00:00%2B02:00/2999-12-31"), all);
  const std::string created =
      results.contains("jobID") ? c.get("/jobs/" + id).json().at("created").get<std::string>() : "";
  EXPECT_EQ(matched("datetime=" + created.substr(0, 10)), all);  // today, as a date
  EXPECT_GE(matched("datetime=" + created), 1);                  // the instant
  EXPECT_EQ(matched("minDuration=0"), all);
  EXPECT_EQ(matched("minDuration=100000"), 0);
  EXPECT_EQ(matched("maxDuration=100000"), all);
  EXPECT_EQ(matched("maxDuration=0&status=successful"), 0);
  for (const std::string query :
       {"datetime=yesterday", "datetime=2024-13-01", "datetime=2024-05-02/2024-05-01",
        "minDuration=-1", "maxDuration=x", "sort=created", "f=html", "statuss=running"}) {
    const ClientResponse r = c.get("/jobs?" + query);
    EXPECT_EQ(r.status, 400u) << query;
    EXPECT_EQ(r.header("Content-Type"), "application/problem+json") << query;
  }
  // The pages' links keep the filters.
  const json page = c.get("/jobs?limit=1&processID=gearsph-simulation").json();
  for (const json& l : page.at("links")) {
    EXPECT_NE(l.at("href").get<std::string>().find("processID=gearsph-simulation"),
              std::string::npos)
        << l.dump();
  }
}

// 14. The API definition (OpenAPI 3.0 at /api, linked as service-desc)
// describes exactly the routes the router has: each path and method, each
// path parameter declared. (Paths compare with their parameters' names
// blanked: the document uses OGC's names, the router its own.)
std::string blank_parameters(std::string path) {
  for (auto open = path.find('{'); open != std::string::npos; open = path.find('{', open + 2)) {
    path.erase(open + 1, path.find('}', open) - open - 1);
  }
  return path;
}

TEST_F(ServerHardening, ApiDefinitionDescribesExactlyTheRoutes) {
  auto c = server_->client();
  const ClientResponse r = c.get("/api");
  ASSERT_EQ(r.status, 200u);
  EXPECT_EQ(r.header("Content-Type"), "application/vnd.oai.openapi+json;version=3.0");
  const json doc = r.json();
  EXPECT_EQ(doc.at("openapi").get<std::string>().rfind("3.0.", 0), 0u);
  EXPECT_FALSE(doc.at("info").at("title").get<std::string>().empty());

  std::set<std::string> routed, described;
  for (const Route& route : route_table()) {
    std::string method(http::to_string(route.method));
    std::transform(method.begin(), method.end(), method.begin(),
                   [](unsigned char ch) { return std::tolower(ch); });
    routed.insert(method + " " + blank_parameters(std::string(route.pattern)));
  }
  for (const auto& [path, item] : doc.at("paths").items()) {
    for (const auto& [method, operation] : item.items()) {
      if (method == "parameters") continue;
      described.insert(method + " " + blank_parameters(path));
      EXPECT_FALSE(operation.at("summary").get<std::string>().empty()) << method << " " << path;
      EXPECT_FALSE(operation.at("responses").empty()) << method << " " << path;
      // Every {parameter} of the path is declared.
      std::set<std::string> declared;
      for (const json* list : {&operation, &item}) {
        for (const json& p : list->value("parameters", json::array())) {
          if (p.contains("in") && p.at("in") == "path") declared.insert(p.at("name"));
        }
      }
      for (auto open = path.find('{'); open != std::string::npos; open = path.find('{', open + 1)) {
        const std::string name = path.substr(open + 1, path.find('}', open) - open - 1);
        EXPECT_TRUE(declared.count(name)) << method << " " << path << ": {" << name << "}";
      }
    }
  }
  for (const std::string& route : routed) {
    EXPECT_TRUE(described.count(route)) << route << " is routed but not in the API definition";
  }
  for (const std::string& operation : described) {
    EXPECT_TRUE(routed.count(operation)) << operation << " is described but not routed";
  }
  // Every $ref points at a component that exists.
  std::function<void(const json&)> refs = [&](const json& j) {
    if (j.is_object()) {
      for (const auto& [key, value] : j.items()) {
        if (key == "$ref") {
          EXPECT_NO_THROW((void)doc.at(json::json_pointer(value.get<std::string>().substr(1))))
              << value;
        } else {
          refs(value);
        }
      }
    } else if (j.is_array()) {
      for (const json& v : j) refs(v);
    }
  };
  refs(doc);
  // Linked from the landing page, and claimed among the conformance classes.
  bool linked = false;
  const json landing = c.get("/", {{"Accept", "application/json"}}).json();
  for (const json& l : landing.at("links")) {
    linked = linked || (l.at("rel") == "service-desc" && l.at("href") == "/api");
  }
  EXPECT_TRUE(linked) << landing.dump();
  const json classes = c.get("/conformance").json().at("conformsTo");
  EXPECT_NE(std::find(classes.begin(), classes.end(),
                      "http://www.opengis.net/spec/ogcapi-processes-1/1.0/conf/oas30"),
            classes.end());
}

// Whether an OpenAPI path template ("/jobs/{jobId}") matches a path.
bool template_matches(const std::string& tpl, const std::string& path) {
  auto split = [](const std::string& p) {
    std::vector<std::string> out;
    std::stringstream in(p);
    for (std::string part; std::getline(in, part, '/');) out.push_back(part);
    return out;
  };
  const auto t = split(tpl), p = split(path);
  if (t.size() != p.size()) return false;
  for (std::size_t i = 0; i < t.size(); ++i) {
    const bool parameter = !t[i].empty() && t[i].front() == '{';
    if (parameter ? p[i].empty() : t[i] != p[i]) return false;
  }
  return true;
}

// N13: every status the service answers an operation with is among that
// operation's responses in the API definition (no "default" catch-all),
// the conditional, quota and screening answers included.
TEST(ServerApiDefinition, EveryStatusAnsweredIsDocumented) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1", "--max-queued-per-client", "1",
                        "--max-body-bytes", "200000"});
  auto c = server.client();
  const json doc = c.get("/api").json();
  std::vector<std::string> undocumented;
  std::set<std::string> seen;
  auto check = [&](const std::string& method, const std::string& target, unsigned status) {
    const std::string path = target.substr(0, target.find('?'));
    for (const auto& [tpl, item] : doc.at("paths").items()) {
      if (!template_matches(tpl, path) || !item.contains(method)) continue;
      const std::string code = std::to_string(status);
      seen.insert(code);
      if (!item.at(method).at("responses").contains(code)) {
        undocumented.push_back(method + " " + tpl + " answered " + code);
      }
      return;
    }
    undocumented.push_back(method + " " + path + " is not described");
  };
  auto get = [&](const std::string& target, const HttpClient::Headers& h = {}) {
    const ClientResponse r = c.get(target, h);
    check("get", target, r.status);
    return r;
  };
  auto post = [&](const std::string& target, const std::string& body,
                  const HttpClient::Headers& h = {}) {
    const ClientResponse r = c.post_json(target, body, h);
    check("post", target, r.status);
    return r;
  };

  const std::string done = post("/jobs", tiny_job().dump()).json().at("jobID");
  ASSERT_EQ(wait_final(c, done).at("status"), "successful");
  const std::string file = "/jobs/" + done + "/files/history.csv";
  const std::string etag = get(file).header("ETag");
  get(file, {{"Range", "bytes=2-9"}});
  get(file, {{"If-None-Match", etag}});
  get(file, {{"Range", "bytes=99999999-"}});
  get("/jobs/" + done + "/files/none.csv");
  get("/jobs/" + done);
  get("/jobs/" + done + "/results");
  get("/jobs?bogus=1");
  get("/jobs/00000000-0000-4000-8000-000000000000");
  get("/jobs", {{"Host", "rebind.attacker.example:" + server.port()}});
  post("/preview", "{");
  post("/preview", tiny_job().dump());
  post("/login", "{}");
  {
    const ClientResponse r = c.request("POST", "/jobs", "{}", {{"Content-Type", "text/plain"}});
    check("post", "/jobs", r.status);
  }
  post("/jobs", "[" + std::string(300000, ' ') + "]");
  const std::string answer =
      raw(server, "POST /jobs HTTP/1.1\r\nHost: 127.0.0.1:" + server.port() +
                      "\r\nContent-Type: application/json\r\nTransfer-Encoding: gzip, "
                      "chunked\r\n\r\n2\r\n{}\r\n0\r\n\r\n");
  check("post", "/jobs", static_cast<unsigned>(std::stoi(answer.substr(9, 3))));

  // Prefer: respond-async is applied, and said so (RFC 7240).
  const ClientResponse running = post("/processes/gearsph-simulation/execution",
                                      tiny_job(20.0).dump(), {{"Prefer", "respond-async"}});
  EXPECT_EQ(running.header("Preference-Applied"), "respond-async");
  const std::string long_run = running.json().at("jobID");
  wait_for(c, long_run, [](const json& st) { return st.at("status") == "running"; });
  // One queued is this client's quota: the next job and any study get 429.
  const std::string queued = post("/jobs", tiny_job(20.0).dump()).json().at("jobID");
  post("/jobs", tiny_job().dump());
  post("/studies", json({{"base", tiny_job()},
                         {"axes", {{{"pointer", "/time/end_s"}, {"values", {1e-3, 2e-3}}}}}})
                       .dump());
  for (const std::string& id : {queued, long_run}) {
    check("delete", "/jobs/" + id, c.request("DELETE", "/jobs/" + id).status);
  }
  for (const char* code :
       {"200", "201", "206", "304", "400", "404", "413", "415", "416", "421", "429", "501"}) {
    EXPECT_TRUE(seen.count(code)) << "no request of this test was answered " << code;
  }
  std::string list;
  for (const std::string& u : undocumented) list += "\n  " + u;
  EXPECT_TRUE(undocumented.empty()) << "answers not in the API definition:" << list;
}

// 13. A job store that holds every reader at a gate, as a store under a
// heavy query or a lost database would.
class GatedStore : public JobStore {
 public:
  void open_gate() {
    std::lock_guard<std::mutex> lock(mutex_);
    open_ = true;
    wake_.notify_all();
  }
  // Blocks until a reader waits at the gate.
  void wait_for_reader() {
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait(lock, [&] { return waiting_ > 0; });
  }

  SubmitResult submit(const NewJob& j, const std::optional<Idempotency>&,
                      const QueueQuota&) override {
    return {SubmitResult::Kind::created, j.id};
  }
  SubmitResult submit_study(const NewStudy& s, const std::vector<NewJob>&,
                            const std::optional<Idempotency>&, const QueueQuota&) override {
    return {SubmitResult::Kind::created, s.id};
  }
  std::optional<JobRecord> job(const std::string&) override {
    gate();
    return std::nullopt;
  }
  JobPage jobs(const JobQuery&) override {
    gate();
    return {};
  }
  std::optional<StudyRecord> study(const std::string&) override {
    gate();
    return std::nullopt;
  }
  std::map<std::string, std::int64_t> count_by_status() override {
    if (!primed_) {  // the server's first count, before it listens
      primed_ = true;
      return {{"accepted", 0}};
    }
    gate();
    return {{"accepted", 0}};
  }
  std::int64_t queued_from(const std::string&) override { return 0; }
  std::optional<JobRecord> claim(const Holder&) override { return std::nullopt; }
  std::vector<std::string> renew(const Holder&, const std::vector<HeldJob>&) override { return {}; }
  Recovery reclaim_expired(int) override { return {}; }
  std::vector<std::string> save_progress(const std::vector<ProgressUpdate>&) override { return {}; }
  bool finish(const std::string&, JobStatus, const std::string&, const ProgressUpdate&,
              const std::string&) override {
    return false;
  }
  bool close_dismissed(const std::string&, const std::string&, const ProgressUpdate&) override {
    return false;
  }
  bool requeue(const std::string&, const std::string&, const std::string&) override {
    return false;
  }
  std::optional<JobRecord> dismiss(const std::string&) override { return std::nullopt; }
  Recovery recover(int) override { return {}; }
  std::optional<JobRecord> claim_for_dispatch(const std::string&) override { return std::nullopt; }
  std::vector<JobRecord> dispatched() override { return {}; }
  bool set_dispatch(const std::string&, JobStatus, const std::string&, const std::string&,
                    const std::string&, double) override {
    return false;
  }
  bool release_dispatch(const std::string&, const std::string&, const std::string&,
                        double) override {
    return false;
  }
  bool start_dispatched(const std::string&, const std::string&, const std::string&) override {
    return false;
  }
  bool unstart_dispatched(const std::string&, const std::string&, const std::string&) override {
    return false;
  }
  void forget_dispatch(const std::string&) override {}
  void worker_seen(const std::string&, int) override {}
  std::vector<WorkerSeen> workers_seen(double) override { return {}; }
  std::int64_t open_session(const std::string&, double, std::int64_t) override { return 0; }
  bool session_open(const std::string&) override { return false; }
  bool close_session(const std::string&) override { return false; }
  std::int64_t open_sessions() override { return 0; }
  Durations durations(const std::vector<double>&) override { return {}; }
  std::vector<std::string> prune(double) override { return {}; }
  std::vector<JobRecord> changed_within(double) override { return {}; }
  std::vector<JobRecord> active_or_changed_within(double) override { return {}; }

 private:
  void gate() {
    std::unique_lock<std::mutex> lock(mutex_);
    ++waiting_;
    wake_.notify_all();
    wake_.wait(lock, [&] { return open_; });
    --waiting_;
  }
  std::mutex mutex_;
  std::condition_variable wake_;
  bool open_ = false;
  int waiting_ = 0;
  bool primed_ = false;
};

class NoWorkers : public Dispatcher {
 public:
  void start() override {}
  void notify() override {}
  void stop() override {}
  std::optional<ProgressUpdate> live(const std::string&) const override { return std::nullopt; }
  bool cancel(const std::string&) override { return false; }
  int running() const override { return 0; }
};

TEST(ServerLanes, HealthAnswersWhileTheStoreHoldsEveryReader) {
  namespace net = boost::asio;
  ServerConfig config;
  TempDir data;  // the results directory /health checks
  config.data_dir = data.path();
  fs::create_directories(results_dir_of(config));
  GatedStore store;
  NoWorkers workers;
  EventHub hub;
  Services services(config, store, workers, hub);
  services.refresh_queue_counts();
  Router router(services);
  net::io_context ioc;
  net::thread_pool store_pool(1), slow_pool(1);
  auto listener =
      std::make_shared<Listener>(ioc, net::ip::tcp::endpoint(net::ip::make_address("127.0.0.1"), 0),
                                 router, HandlerPools{store_pool, slow_pool});
  services.port = listener->port();
  listener->run();
  std::thread io([&] { ioc.run(); });  // one I/O thread: a blocked handler would block it all
  const std::string port = std::to_string(listener->port());

  // A job list that waits at the store's gate...
  auto listing = std::async(std::launch::async, [&] {
    HttpClient c("127.0.0.1", port, std::chrono::seconds(60));
    return c.get("/jobs?limit=1000").status;
  });
  store.wait_for_reader();
  // ...does not hold up the health check, the schema or the events of all jobs.
  HttpClient c("127.0.0.1", port, std::chrono::seconds(10));
  ClientResponse health;
  EXPECT_NO_THROW(health = c.get("/health"));
  EXPECT_EQ(health.status, 200u);
  EXPECT_EQ(health.json().at("queue").at("accepted"), 0) << health.body;
  ClientResponse schema;
  EXPECT_NO_THROW(schema = c.get("/schema"));
  EXPECT_EQ(schema.status, 200u);
  store.open_gate();
  EXPECT_EQ(listing.get(), 200u);

  listener->stop();
  ioc.stop();
  io.join();
  store_pool.join();
  slow_pool.join();
}

}  // namespace
}  // namespace gearsph::server::testing
