// gearsph submit JOB.json --server URL [--wait] [--out DIR] [--token-file F]
//                [--idempotency-key KEY] [--retry-for SECONDS]
// Submits a job to a running `gearsph serve`, follows its progress (Server-
// Sent Events) on stderr and downloads the results. URL may carry a path
// (a server behind a proxy at http://host/gearsph): every request goes
// below it.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <thread>

#include "apps/gearsph/cli.hpp"
#include "server/config.hpp"
#include "server/http_client.hpp"

namespace gearsph::cli {

namespace {

using Clock = std::chrono::steady_clock;
using server::ClientResponse;
using server::HttpClient;

// How long --wait keeps trying while the server is unreachable.
constexpr double kDefaultRetryFor_s = 300;
// Between two attempts to reach it.
constexpr std::chrono::seconds kRetryPause{2};

void print_problem(const ClientResponse& r) {
  try {
    const auto p = r.json();
    std::fprintf(stderr, "gearsph submit: %u %s: %s\n", r.status,
                 p.value("title", std::string()).c_str(), p.value("detail", std::string()).c_str());
    if (p.contains("errors") && p["errors"].is_array()) {
      for (const auto& e : p["errors"]) {
        const std::string pointer = e.value("pointer", std::string());
        std::fprintf(stderr, "  %s: %s\n", pointer.empty() ? "(document)" : pointer.c_str(),
                     e.value("detail", std::string()).c_str());
      }
    }
  } catch (const std::exception&) {
    std::fprintf(stderr, "gearsph submit: the server answered %u: %s\n", r.status, r.body.c_str());
  }
}

class ProgressLine {
 public:
  ProgressLine() : tty_(isatty(2) != 0) {}
  void show(const nlohmann::json& p) {
    std::fprintf(stderr, "%s[%3d%%] step %lld/%lld  t = %.4g s  wall %.1f s  ETA %.1f s%s",
                 tty_ ? "\r" : "", p.value("progress", 0),
                 static_cast<long long>(p.value("step", 0LL)),
                 static_cast<long long>(p.value("steps", 0LL)), p.value("simulated_s", 0.0),
                 p.value("wall_s", 0.0), p.value("eta_s", 0.0), tty_ ? "   " : "\n");
    shown_ = true;
  }
  void end() {
    if (tty_ && shown_) std::fputc('\n', stderr);
    shown_ = false;
  }

 private:
  bool tty_;
  bool shown_ = false;
};

bool terminal(const std::string& status) {
  return status == "successful" || status == "failed" || status == "dismissed";
}

// Follows the job's event stream until it has a final status; reconnects
// (resuming with Last-Event-ID) if the server goes away meanwhile, for as
// long as `retry_for` since it was last reached.
nlohmann::json follow(HttpClient& client, const std::string& base, const std::string& id,
                      double retry_for) {
  ProgressLine line;
  nlohmann::json final_status;
  std::string last_id;
  // Since when every attempt to reach the server has failed.
  std::optional<Clock::time_point> failing_since;
  auto reached = [&] { failing_since.reset(); };
  auto unreachable = [&](const std::string& what) {
    line.end();
    const auto now = Clock::now();
    if (!failing_since) failing_since = now;
    const double silent = std::chrono::duration<double>(now - *failing_since).count();
    if (silent >= retry_for) {
      throw std::runtime_error(what + "; gave up after " + std::to_string(int(silent)) +
                               " s without the server (--retry-for " +
                               std::to_string(int(retry_for)) + ")");
    }
    std::fprintf(stderr, "gearsph submit: %s; trying again\n", what.c_str());
    std::this_thread::sleep_for(kRetryPause);
  };
  for (;;) {
    try {
      HttpClient::Headers headers;
      if (!last_id.empty()) headers.emplace_back("Last-Event-ID", last_id);
      const ClientResponse head = client.events(
          base + "/jobs/" + id + "/events",
          [&](const server::SseEvent& e) {
            reached();
            if (!e.id.empty()) last_id = e.id;
            const auto data = nlohmann::json::parse(e.data, nullptr, false);
            if (data.is_discarded()) return true;
            if (e.event == "progress") {
              line.show(data);
            } else if (e.event == "status") {
              const std::string status = data.value("status", std::string());
              if (status == "running" && data.contains("progress")) line.show(data);
              if (terminal(status)) {
                final_status = data;
                return false;
              }
              if (status == "accepted") {
                line.end();
                std::fprintf(stderr, "gearsph submit: queued: %s\n",
                             data.value("message", std::string()).c_str());
              }
            }
            return true;
          },
          headers);
      reached();
      // 204: the stream has nothing more (its final status was sent before).
      if (head.status != 200 && head.status != 204) {
        line.end();
        print_problem(head);
        throw std::logic_error("cannot follow job " + id);
      }
    } catch (const std::runtime_error& e) {
      unreachable(e.what());
      continue;
    }
    if (!final_status.is_null()) break;
    // The stream ended without a final status (the server stopped, or it
    // had been sent already): ask.
    try {
      const ClientResponse r = client.get(base + "/jobs/" + id);
      reached();
      if (r.status == 200 && terminal(r.json().value("status", std::string()))) {
        final_status = r.json();
        break;
      }
    } catch (const std::runtime_error& e) {
      unreachable(e.what());
      continue;
    }
    std::this_thread::sleep_for(std::chrono::seconds(1));
  }
  line.end();
  return final_status;
}

// A link of the server's ("/jobs/..."), below the URL's path.
std::string below(const std::string& base, const std::string& href) {
  return !href.empty() && href.front() == '/' ? base + href : href;
}

void download_results(HttpClient& client, const std::string& base, const std::string& id,
                      const std::filesystem::path& out) {
  const ClientResponse r = client.get(base + "/jobs/" + id + "/results");
  if (r.status != 200) {
    print_problem(r);
    return;
  }
  std::filesystem::create_directories(out);
  const auto doc = r.json();
  std::ofstream(out / "results.json") << doc.dump(2) << "\n";
  for (const auto& f : doc.value("files", nlohmann::json::array())) {
    const std::string name = f.value("name", std::string());
    // Names come from the server: keep them plain.
    if (name.empty() || name.find('/') != std::string::npos || name.front() == '.') continue;
    const ClientResponse d =
        client.download(below(base, f.value("href", std::string())), out / name);
    if (d.status != 200) {
      std::fprintf(stderr, "gearsph submit: %s: %u\n", name.c_str(), d.status);
    }
  }
  std::fprintf(stderr, "gearsph submit: results in %s\n", out.string().c_str());
}

}  // namespace

int cmd_submit(Args& args) {
  const auto url = args.option("server");
  const auto out = args.option("out");
  const auto token_file = args.option("token-file");
  const auto key = args.option("idempotency-key");
  const double retry_for =
      args.seconds("retry-for", kDefaultRetryFor_s, {0.0, false, 30 * 86400.0, "0 or more"});
  const bool wait = args.flag("wait") || out.has_value();
  const auto pos = args.positional();
  if (pos.size() != 1 || !url) {
    throw std::invalid_argument(
        "usage: gearsph submit JOB.json --server URL [--wait] [--out DIR] [--token-file F] "
        "[--idempotency-key KEY] [--retry-for SECONDS]");
  }
  const server::Url u = server::Url::parse(*url);
  HttpClient client(u.host, u.port, std::chrono::seconds(60));
  if (token_file)
    client.set_default_header("Authorization", "Bearer " + server::read_token_file(*token_file));

  HttpClient::Headers headers;
  if (key) headers.emplace_back("Idempotency-Key", *key);
  const ClientResponse r = client.post_json(u.base + "/jobs", read_file(pos[0]), headers);
  if (r.status != 201 && r.status != 200) {
    print_problem(r);
    return r.status == 400 || r.status == 422 || r.status == 415 || r.status == 413 ? 2 : 1;
  }
  const auto status = r.json();
  const std::string id = status.value("jobID", std::string());
  std::printf("%s\n", id.c_str());
  std::fflush(stdout);
  std::fprintf(stderr, "gearsph submit: job %s %s (%s)\n", id.c_str(),
               r.status == 201 ? "submitted" : "already submitted with this key",
               (u.root() + "/jobs/" + id).c_str());
  if (!wait) return 0;

  const nlohmann::json final_status = follow(client, u.base, id, retry_for);
  const std::string s = final_status.value("status", std::string());
  std::fprintf(stderr, "gearsph submit: job %s %s: %s\n", id.c_str(), s.c_str(),
               final_status.value("message", std::string()).c_str());
  if (out && s == "successful") download_results(client, u.base, id, *out);
  return s == "successful" ? 0 : s == "failed" ? 3 : 4;
}

}  // namespace gearsph::cli
