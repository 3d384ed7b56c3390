// Thousands of malformed or random requests at a running server: it keeps
// serving, and its job store stays consistent.
#include <random>
#include <thread>

#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

class Fuzzer {
 public:
  explicit Fuzzer(std::uint64_t seed) : rng_(seed) {}

  std::string random_bytes(std::size_t max) {
    std::string s(pick(0, max), '\0');
    for (char& c : s) c = static_cast<char>(pick(0, 255));
    return s;
  }

  std::string random_token(std::size_t max) {
    static const std::string alphabet =
        "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./%?&=+:;@!~*'()[] \t";
    std::string s(pick(0, max), ' ');
    for (char& c : s) c = alphabet[pick(0, alphabet.size() - 1)];
    return s;
  }

  std::string random_path() {
    static const std::vector<std::string> parts = {"jobs",
                                                   "files",
                                                   "results",
                                                   "events",
                                                   "processes",
                                                   "gearsph-simulation",
                                                   "execution",
                                                   "studies",
                                                   "images",
                                                   "x.png",
                                                   "..",
                                                   ".",
                                                   "%2e%2e",
                                                   "%2F",
                                                   "%00",
                                                   "%",
                                                   "%zz",
                                                   "summary.json",
                                                   "00000000-0000-4000-8000-000000000000",
                                                   "",
                                                   "health",
                                                   "schema",
                                                   "~",
                                                   "a b",
                                                   "\xff"};
    std::string p;
    const std::size_t n = pick(0, 6);
    for (std::size_t i = 0; i < n; ++i) p += "/" + parts[pick(0, parts.size() - 1)];
    if (pick(0, 3) == 0) p += "?" + random_token(30);
    return p.empty() ? "/" : p;
  }

  nlohmann::json random_json(int depth) {
    switch (pick(0, depth > 3 ? 4 : 6)) {
      case 0:
        return nullptr;
      case 1:
        return pick(0, 1) == 1;
      case 2:
        return static_cast<double>(pick(0, 2000)) *
               std::pow(10.0, static_cast<double>(pick(0, 20)) - 12.0) * (pick(0, 1) ? 1 : -1);
      case 3:
        return static_cast<std::int64_t>(pick(0, 1u << 30)) - (1 << 29);
      case 4:
        return random_token(20);
      case 5: {
        nlohmann::json a = nlohmann::json::array();
        for (std::size_t i = pick(0, 4); i > 0; --i) a.push_back(random_json(depth + 1));
        return a;
      }
      default: {
        static const std::vector<std::string> keys = {
            "scene",    "type",           "plate",     "time",       "end_s",  "dt_s",
            "cfl",      "discretization", "spacing_m", "spacing_mm", "kernel", "output",
            "frames",   "method",         "name",      "threads",    "inputs", "job",
            "length_m", "thickness_m",    "x"};
        nlohmann::json o = nlohmann::json::object();
        for (std::size_t i = pick(0, 5); i > 0; --i) {
          o[keys[pick(0, keys.size() - 1)]] = random_json(depth + 1);
        }
        return o;
      }
    }
  }

  // A small valid job with a few fields changed at random: mostly refused,
  // sometimes accepted (and then small, by the server's limits).
  nlohmann::json mutated_job() {
    nlohmann::json j = tiny_job();
    static const std::vector<std::string> pointers = {"/scene/type",
                                                      "/scene/length_m",
                                                      "/scene/thickness_m",
                                                      "/discretization/spacing_m",
                                                      "/discretization/kernel",
                                                      "/time/end_s",
                                                      "/time/cfl",
                                                      "/output/frames",
                                                      "/name",
                                                      "/threads",
                                                      "/method/formulation",
                                                      "/extra",
                                                      "/scene/material/E_Pa"};
    for (std::size_t i = pick(1, 3); i > 0; --i) {
      try {
        j[nlohmann::json::json_pointer(pointers[pick(0, pointers.size() - 1)])] = random_json(2);
      } catch (const nlohmann::json::exception&) {
      }
    }
    return j;
  }

  std::string request() {
    static const std::vector<std::string> methods = {"GET",  "POST",    "DELETE", "PUT",
                                                     "HEAD", "OPTIONS", "PATCH",  "BREW",
                                                     "get",  "G\x01T",  "",       "POST /jobs"};
    switch (pick(0, 9)) {
      case 0:
        return random_bytes(2000);
      case 1: {  // a valid request cut short
        const std::string full =
            "POST /jobs HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
            "Content-Length: 120\r\n\r\n" +
            tiny_job().dump();
        return full.substr(0, pick(0, full.size()));
      }
      case 2:  // huge header
        return "GET /health HTTP/1.1\r\nHost: x\r\nX-" + random_token(10) + ": " +
               std::string(pick(10000, 70000), 'h') + "\r\n\r\n";
      case 3:
        return methods[pick(0, methods.size() - 1)] + " " + random_path() +
               " HTTP/1.1\r\nHost: x\r\n\r\n";
      case 4: {  // random JSON to the submission endpoints
        const std::string body = pick(0, 1) ? random_json(0).dump() : mutated_job().dump();
        const std::string target = pick(0, 3) == 0   ? "/processes/gearsph-simulation/execution"
                                   : pick(0, 5) == 0 ? "/studies"
                                                     : "/jobs";
        return "POST " + target +
               " HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
               "Content-Length: " +
               std::to_string(body.size()) + "\r\n\r\n" + body;
      }
      case 5: {  // lying Content-Length, chunked garbage
        return "POST /jobs HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n" +
               std::string(pick(0, 1)
                               ? "Content-Length: " + std::to_string(pick(0, 1u << 31)) + "\r\n"
                               : "Transfer-Encoding: chunked\r\n") +
               "\r\n" + random_bytes(300);
      }
      case 6:  // random header lines
        return "GET " + random_path() + " HTTP/1.1\r\n" + random_token(60) + "\r\n" +
               random_token(60) + ": " + random_token(60) + "\r\n\r\n";
      case 7:  // bad versions and request lines
        return "GET / HTTP/" + random_token(4) + "\r\n\r\n";
      case 8:  // Range and Last-Event-ID oddities
        return "GET /jobs/" +
               std::string(pick(0, 1) ? "00000000-0000-4000-8000-000000000000" : "x") +
               "/files/history.csv HTTP/1.1\r\nHost: x\r\nRange: " + random_token(20) +
               "\r\nLast-Event-ID: " + random_token(10) + "\r\n\r\n";
      default: {  // several pipelined requests, some broken
        std::string s;
        for (std::size_t i = pick(1, 4); i > 0; --i) {
          s += "GET " + random_path() + " HTTP/1.1\r\nHost: x\r\n\r\n";
          if (pick(0, 3) == 0) s += random_bytes(50);
        }
        return s;
      }
    }
  }

 private:
  std::size_t pick(std::size_t lo, std::size_t hi) {
    return std::uniform_int_distribution<std::size_t>(lo, hi)(rng_);
  }
  std::mt19937_64 rng_;
};

TEST(ServerFuzz, KeepsServingAndTheStoreStaysConsistent) {
  // The fuzzer's requests name the server "x".
  ServerProcess server({"--workers", "1", "--threads-per-job", "1", "--max-particles", "2000",
                        "--max-steps", "500", "--header-timeout", "2", "--body-timeout", "2",
                        "--idle-timeout", "2", "--allowed-host", "x"});
  constexpr int kThreads = 4;
  constexpr int kPerThread = 1500;
  std::atomic<int> sent{0}, answered{0}, failed{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      Fuzzer f(1234 + static_cast<std::uint64_t>(t));
      for (int i = 0; i < kPerThread; ++i) {
        try {
          const std::string answer =
              raw_exchange(server.host(), server.port(), f.request(), std::chrono::seconds(5));
          ++sent;
          if (answer.rfind("HTTP/1.1 ", 0) == 0) ++answered;
          // A 5xx would be a server bug, but for 501 (images without a renderer,
          // transfer codings it does not read) and 505 (HTTP versions but 1.x).
          if (answer.rfind("HTTP/1.1 5", 0) == 0 && answer.rfind("HTTP/1.1 501", 0) != 0 &&
              answer.rfind("HTTP/1.1 505", 0) != 0) {
            ++failed;
          }
        } catch (const std::exception&) {
          ++failed;  // could not even connect: the server is gone
        }
      }
    });
  }
  for (std::thread& t : threads) t.join();
  std::printf("[ fuzz ] %d requests sent, %d answered with HTTP, %d failures\n", sent.load(),
              answered.load(), failed.load());
  EXPECT_EQ(sent.load(), kThreads * kPerThread);
  EXPECT_EQ(failed.load(), 0);

  auto c = server.client();
  const ClientResponse health = c.get("/health");
  ASSERT_EQ(health.status, 200u) << server.log();
  EXPECT_EQ(health.json().at("status"), "ok");
  // Still doing its job (after the queue the fuzzing left is dismissed).
  const nlohmann::json queued = c.get("/jobs?status=accepted&limit=1000").json();
  for (const nlohmann::json& j : queued.at("jobs")) {
    EXPECT_EQ(c.request("DELETE", "/jobs/" + j.at("jobID").get<std::string>()).status, 200u);
  }
  const std::string id = submit(c, tiny_job());
  EXPECT_EQ(wait_final(c, id, std::chrono::seconds(300)).at("status"), "successful");
  expect_consistent_store(server.data());
  EXPECT_EQ(server.stop(SIGTERM), 0);
  expect_consistent_store(server.data());
}

// Random JSON through the whole validation path, in-process fast.
TEST(ServerFuzz, RandomJsonBodiesGetProblemAnswers) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1", "--max-particles", "2000",
                        "--max-steps", "500"});
  auto c = server.client();
  Fuzzer f(99);
  int accepted = 0, refused = 0;
  for (int i = 0; i < 1000; ++i) {
    const nlohmann::json body = i % 2 ? f.random_json(0) : f.mutated_job();
    const ClientResponse r = c.post_json("/jobs", body.dump());
    ASSERT_TRUE(r.status == 201u || r.status == 400u || r.status == 422u)
        << r.status << " for " << body.dump() << ": " << r.body;
    if (r.status == 201u) {
      ++accepted;
    } else {
      ++refused;
      EXPECT_EQ(r.header("Content-Type"), "application/problem+json");
      EXPECT_TRUE(r.json().contains("detail"));
    }
  }
  std::printf("[ fuzz ] 1000 random job bodies: %d accepted, %d refused\n", accepted, refused);
  EXPECT_GT(refused, 0);
  EXPECT_EQ(c.get("/health").status, 200u);
  expect_consistent_store(server.data());
}

}  // namespace
}  // namespace gearsph::server::testing
