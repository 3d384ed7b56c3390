// The job service's promises under stress: SIGKILL mid-run loses nothing,
// SIGTERM stops gracefully, tokens and CORS, slow clients time out.
#include <fstream>
#include <thread>

#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

TEST(ServerLifecycle, SigkillMidRunRequeuesAndCompletes) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  const std::string finished = submit(c, tiny_job());
  ASSERT_EQ(wait_final(c, finished).at("status"), "successful");
  const std::string interrupted = submit(c, tiny_job(0.5));  // running when the kill lands
  const std::string queued = submit(c, tiny_job());
  wait_for(c, interrupted, [](const json& s) { return s.at("step").get<int>() > 0; });
  ASSERT_EQ(c.get("/jobs/" + queued).json().at("status"), "accepted");

  EXPECT_EQ(server.stop(SIGKILL), 128 + SIGKILL);
  {
    Database db(server.data() / "gearsph.db");
    EXPECT_EQ(db.query("SELECT status FROM jobs WHERE id = '" + interrupted + "'").at(0).at(0),
              "running");
  }
  server.start();
  auto c2 = server.client();
  const json again = wait_final(c2, interrupted);
  EXPECT_EQ(again.at("status"), "successful") << again.dump();
  EXPECT_EQ(again.at("attempts"), 2);
  EXPECT_EQ(wait_final(c2, queued).at("status"), "successful");
  EXPECT_NE(server.log().find("was interrupted; it is queued again"), std::string::npos)
      << server.log();
  // What had finished before the kill is still served.
  const ClientResponse r = c2.get("/jobs/" + finished + "/results");
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(c2.get("/jobs/" + finished + "/files/history.csv").status, 200u);
  expect_consistent_store(server.data());
}

TEST(ServerLifecycle, SigkillAfterMaxAttemptsFails) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1", "--max-attempts", "1"});
  auto c = server.client();
  const std::string id = submit(c, tiny_job(20.0));
  wait_for(c, id, [](const json& s) { return s.at("step").get<int>() > 0; });
  server.stop(SIGKILL);
  server.start();
  auto c2 = server.client();
  const json s = c2.get("/jobs/" + id).json();
  EXPECT_EQ(s.at("status"), "failed");
  EXPECT_NE(s.at("message").get<std::string>().find("interrupted 1 time"), std::string::npos)
      << s.dump();
  EXPECT_EQ(c2.get("/jobs/" + id + "/results").status, 500u);
  expect_consistent_store(server.data());
}

// N2: a second SIGTERM while the first is still waiting (here for an idle
// kept-alive connection, up to the 3 s shutdown grace) exits at once.
TEST(ServerLifecycle, ASecondSigtermForcesTheExit) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  ASSERT_EQ(c.get("/health").status, 200u);  // the connection stays open
  ::kill(server.pid(), SIGTERM);
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(server.stop(SIGTERM), 128 + SIGTERM) << server.log();
  EXPECT_NE(server.log().find("SIGTERM again: exiting without waiting"), std::string::npos)
      << server.log();
}

// N11: idle event streams take at most half the connections: the rest
// still answer requests.
TEST(ServerLifecycle, EventStreamsCannotTakeEveryConnection) {
  ServerProcess server({"--max-connections", "4", "--no-local-workers"});
  auto c = server.client();
  // A queued job's stream starts with its status.
  const std::string id = submit(c, tiny_job());
  std::vector<std::jthread> streams;
  std::atomic<int> opened{0};
  for (int i = 0; i < 2; ++i) {
    streams.emplace_back([&] {
      try {
        auto wc = server.client(std::chrono::seconds(60));
        wc.events("/jobs/" + id + "/events", [&](const SseEvent&) {
          ++opened;
          return true;
        });
      } catch (const std::exception&) {
        // Ended by the server's stop.
      }
    });
  }
  for (int i = 0; i < 400 && opened < 2; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_GE(opened.load(), 2) << "the two streams did not start";
  const ClientResponse third = server.client().get("/jobs/" + id + "/events");
  EXPECT_EQ(third.status, 503u) << third.body;
  EXPECT_FALSE(third.header("Retry-After").empty());
  EXPECT_EQ(c.get("/health").status, 200u);
  server.stop(SIGTERM);
}

TEST(ServerLifecycle, SigtermStopsGracefullyAndRequeues) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  // Long enough to be running whenever SIGTERM lands (0.12 s of simulated
  // time finished in 0.7 s on an idle machine); the stop ends it anyway.
  const std::string id = submit(c, tiny_job(20.0));
  wait_for(c, id, [](const json& s) { return s.at("step").get<int>() > 0; });
  // An open event stream ends when the server stops.
  std::jthread watcher([&] {  // joins even if the test body throws
    try {
      auto wc = server.client(std::chrono::seconds(60));
      wc.events("/events", [](const SseEvent&) { return true; });
    } catch (const std::exception&) {
      // The server going away mid-stream is what this test does.
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  const auto t0 = Clock::now();
  EXPECT_EQ(server.stop(SIGTERM), 0) << server.log();
  EXPECT_LT(Clock::now() - t0, std::chrono::seconds(10));
  watcher.join();
  {
    Database db(server.data() / "gearsph.db");
    const auto row = db.query("SELECT status, attempts, message FROM jobs WHERE id = '" + id + "'");
    EXPECT_EQ(row.at(0).at(0), "accepted");
    EXPECT_EQ(row.at(0).at(1), "0");  // a graceful stop costs the job no attempt
    EXPECT_NE(row.at(0).at(2).find("the server was stopped"), std::string::npos) << row.at(0).at(2);
  }
  expect_consistent_store(server.data());
  // The restarted server runs the re-queued job again (it is long: stop
  // once it has made progress).
  server.start();
  auto c2 = server.client();
  wait_for(c2, id, [](const json& s) {
    return s.at("status") == "running" && s.at("step").get<int>() > 0;
  });
  EXPECT_EQ(server.stop(SIGINT), 0);
}

TEST(ServerLifecycle, SecondServerOnTheSameDataIsRefused) {
  ServerProcess server;
  const std::string cmd = std::string(GEARSPH_BINARY) + " serve --port 0 --data " +
                          server.data().string() + " > /dev/null 2> " +
                          (server.dir() / "second.err").string();
  const int status = std::system(cmd.c_str());
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_NE(slurp(server.dir() / "second.err").find("another gearsph serve"), std::string::npos);
}

TEST(ServerSecurity, BindsToLoopbackByDefault) {
  ServerProcess server;
  EXPECT_EQ(server.host(), "127.0.0.1");
}

TEST(ServerSecurity, TokenRequiredWhenConfigured) {
  TempDir dir;
  std::ofstream(dir.path() / "token") << "s3cret-token\n";
  ServerProcess server(
      {"--token-file", (dir.path() / "token").string(), "--cors-origin", "http://dash.example"});
  auto c = server.client();
  for (const std::string t : {"/health", "/jobs", "/schema"}) {
    const ClientResponse r = c.get(t);
    EXPECT_EQ(r.status, 401u) << t;
    EXPECT_EQ(r.header("WWW-Authenticate"), "Bearer realm=\"gearsph\"");
    EXPECT_EQ(r.header("Content-Type"), "application/problem+json");
  }
  EXPECT_EQ(c.get("/health", {{"Authorization", "Bearer wrong"}}).status, 401u);
  EXPECT_EQ(c.get("/health", {{"Authorization", "Bearer s3cret-tokenX"}}).status, 401u);
  EXPECT_EQ(c.get("/health", {{"Authorization", "Bearer s3cret-toke"}}).status, 401u);
  EXPECT_EQ(c.get("/health", {{"Authorization", "Basic s3cret-token"}}).status, 401u);
  EXPECT_EQ(c.get("/health", {{"Authorization", "Bearer s3cret-token"}}).status, 200u);
  EXPECT_EQ(c.get("/health", {{"Authorization", "bearer s3cret-token"}}).status, 200u);
  // RFC 6750 2.3, for EventSource: on event streams only (test_server_hardening.cpp).
  EXPECT_EQ(c.get("/health?access_token=s3cret-token").status, 401u);
  // A large body without the token is refused before it is read.
  EXPECT_EQ(c.post_json("/jobs", std::string(512 << 10, ' ')).status, 401u);
  // CORS preflight carries no credentials.
  const ClientResponse pre =
      c.request("OPTIONS", "/jobs", "",
                {{"Origin", "http://dash.example"}, {"Access-Control-Request-Method", "POST"}});
  EXPECT_EQ(pre.status, 204u);
  EXPECT_EQ(pre.header("Access-Control-Allow-Origin"), "http://dash.example");
  EXPECT_NE(pre.header("Access-Control-Allow-Headers").find("Authorization"), std::string::npos);
  const ClientResponse cors = c.get(
      "/health", {{"Authorization", "Bearer s3cret-token"}, {"Origin", "http://dash.example"}});
  EXPECT_EQ(cors.header("Access-Control-Allow-Origin"), "http://dash.example");
  const ClientResponse other = c.get(
      "/health", {{"Authorization", "Bearer s3cret-token"}, {"Origin", "http://evil.example"}});
  EXPECT_EQ(other.header("Access-Control-Allow-Origin"), "");
}

TEST(ServerSecurity, CorsOffByDefault) {
  ServerProcess server;
  auto c = server.client();
  const ClientResponse r = c.get("/health", {{"Origin", "http://dash.example"}});
  EXPECT_EQ(r.status, 200u);
  EXPECT_EQ(r.header("Access-Control-Allow-Origin"), "");
  const ClientResponse pre =
      c.request("OPTIONS", "/jobs", "",
                {{"Origin", "http://dash.example"}, {"Access-Control-Request-Method", "POST"}});
  EXPECT_EQ(pre.header("Access-Control-Allow-Origin"), "");
  EXPECT_EQ(pre.header("Access-Control-Allow-Methods"), "");
}

TEST(ServerTimeouts, SlowClientsAreCutOff) {
  ServerProcess server({"--header-timeout", "1", "--body-timeout", "1", "--idle-timeout", "1"});
  auto timed = [&](const std::string& bytes) {
    const auto t0 = Clock::now();
    const std::string answer = raw_exchange(server.host(), server.port(), bytes,
                                            std::chrono::seconds(8), /*half_close=*/false);
    return std::make_pair(answer, std::chrono::duration<double>(Clock::now() - t0).count());
  };
  // Headers that never end.
  const std::string host = "Host: 127.0.0.1:" + server.port() + "\r\n";
  auto [a1, t1] = timed("GET /health HTTP/1.1\r\n" + host);
  EXPECT_TRUE(a1.empty()) << a1;
  EXPECT_LT(t1, 5.0);
  // A body that never comes.
  auto [a2, t2] = timed("POST /jobs HTTP/1.1\r\n" + host +
                        "Content-Type: application/json\r\nContent-Length: "
                        "100\r\n\r\n{");
  EXPECT_LT(t2, 5.0);
  EXPECT_EQ(a2.find("201"), std::string::npos);
  // Silence after connecting, and an idle keep-alive connection after an answer.
  auto [a3, t3] = timed("");
  EXPECT_TRUE(a3.empty());
  EXPECT_LT(t3, 5.0);
  auto [a4, t4] = timed("GET /health HTTP/1.1\r\n" + host + "\r\n");
  EXPECT_EQ(a4.rfind("HTTP/1.1 200", 0), 0u);
  EXPECT_LT(t4, 5.0);
  // Headers over the limit.
  const std::string huge =
      "GET /health HTTP/1.1\r\n" + host + "X-Big: " + std::string(64 << 10, 'a') + "\r\n\r\n";
  EXPECT_EQ(raw_exchange(server.host(), server.port(), huge, std::chrono::seconds(5))
                .rfind("HTTP/1.1 431", 0),
            0u);
  auto c = server.client();
  EXPECT_EQ(c.get("/health").status, 200u);
}

TEST(ServerTimeouts, ExpectContinueAndPipelining) {
  ServerProcess server({"--threads-per-job", "1"});
  const std::string host = "Host: 127.0.0.1:" + server.port() + "\r\n";
  const std::string body = tiny_job().dump();
  const std::string answer =
      raw_exchange(server.host(), server.port(),
                   "POST /jobs HTTP/1.1\r\n" + host +
                       "Content-Type: application/json\r\nExpect: "
                       "100-continue\r\nContent-Length: " +
                       std::to_string(body.size()) + "\r\n\r\n" + body +
                       "GET /health HTTP/1.1\r\n" + host + "Connection: close\r\n\r\n",
                   std::chrono::seconds(10));
  EXPECT_EQ(answer.rfind("HTTP/1.1 100 Continue", 0), 0u) << answer.substr(0, 80);
  EXPECT_NE(answer.find("HTTP/1.1 201 Created"), std::string::npos);
  EXPECT_NE(answer.find("HTTP/1.1 200 OK"), std::string::npos);
}

}  // namespace
}  // namespace gearsph::server::testing
