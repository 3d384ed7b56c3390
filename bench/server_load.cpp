// Load benchmark of the job service: concurrent status and list requests
// (kept-alive connections) while jobs run; reports requests per second and
// latency percentiles. Measures, never asserts.
//
//   gearsph_server_load --server http://127.0.0.1:8080 [--connections 8] [--seconds 10]
//                       [--jobs 1] [--job JOB.json] [--token-file F]
//
// bench/server_load.sh starts a server on a scratch directory and runs this.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "server/config.hpp"
#include "server/http_client.hpp"

namespace {

using gearsph::server::ClientResponse;
using gearsph::server::HttpClient;
using Clock = std::chrono::steady_clock;

struct Options {
  std::string server = "http://127.0.0.1:8080";
  int connections = 8;
  double seconds = 10.0;
  int jobs = 1;
  std::string job_file;
  std::string token_file;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + " needs a value");
      return argv[++i];
    };
    if (a == "--server") {
      o.server = value();
    } else if (a == "--connections") {
      o.connections = std::stoi(value());
    } else if (a == "--seconds") {
      o.seconds = std::stod(value());
    } else if (a == "--jobs") {
      o.jobs = std::stoi(value());
    } else if (a == "--job") {
      o.job_file = value();
    } else if (a == "--token-file") {
      o.token_file = value();
    } else {
      throw std::invalid_argument("unknown option " + a);
    }
  }
  return o;
}

// A plate that runs for a while on any machine, so requests meet running jobs.
const char* kDefaultJob =
    R"({"name": "load-benchmark", "scene": {"type": "plate", "length_m": 0.1, "thickness_m": 0.01},
        "discretization": {"spacing_m": 0.001}, "time": {"end_s": 5}})";

double percentile(std::vector<double>& v, double p) {
  if (v.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(p * double(v.size() - 1) + 0.5);
  std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
  return v[k];
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const Options o = parse(argc, argv);
    const auto url = gearsph::server::Url::parse(o.server);
    std::string token;
    if (!o.token_file.empty()) token = gearsph::server::read_token_file(o.token_file);
    auto make_client = [&] {
      auto c = std::make_unique<HttpClient>(url.host, url.port, std::chrono::seconds(30));
      if (!token.empty()) c->set_default_header("Authorization", "Bearer " + token);
      return c;
    };

    std::string job = kDefaultJob;
    if (!o.job_file.empty()) {
      std::ifstream in(o.job_file);
      std::stringstream s;
      s << in.rdbuf();
      job = s.str();
    }
    auto setup = make_client();
    std::vector<std::string> ids;
    for (int i = 0; i < o.jobs; ++i) {
      const ClientResponse r = setup->post_json("/jobs", job);
      if (r.status != 201) throw std::runtime_error("submitting the job failed: " + r.body);
      ids.push_back(r.json().at("jobID").get<std::string>());
    }
    // Let the first job start, so the requests meet a running one.
    for (int i = 0; i < 100; ++i) {
      if (setup->get("/jobs/" + ids[0]).json().at("status") != "accepted") break;
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }

    const std::vector<std::string> kinds = {"status", "list", "health"};
    struct Sample {
      std::size_t kind;
      double ms;
    };
    std::mutex mutex;
    std::vector<Sample> samples;
    std::atomic<long> errors{0};
    const auto end = Clock::now() + std::chrono::duration<double>(o.seconds);
    std::vector<std::thread> threads;
    const auto t0 = Clock::now();
    for (int t = 0; t < o.connections; ++t) {
      threads.emplace_back([&, t] {
        auto c = make_client();
        std::vector<Sample> mine;
        std::size_t n = static_cast<std::size_t>(t);
        while (Clock::now() < end) {
          const std::size_t slot = n++ % 4;  // status : list : health = 2 : 1 : 1
          const std::size_t kind = slot < 2 ? 0 : slot == 2 ? 1 : 2;
          const std::string target = kind == 0   ? "/jobs/" + ids[n % ids.size()]
                                     : kind == 1 ? "/jobs?limit=20"
                                                 : "/health";
          const auto s = Clock::now();
          try {
            const ClientResponse r = c->get(target);
            if (r.status != 200) ++errors;
          } catch (const std::exception&) {
            ++errors;
            continue;
          }
          mine.push_back(
              {kind, std::chrono::duration<double, std::milli>(Clock::now() - s).count()});
        }
        std::lock_guard<std::mutex> lock(mutex);
        samples.insert(samples.end(), mine.begin(), mine.end());
      });
    }
    for (auto& th : threads) th.join();
    const double wall = std::chrono::duration<double>(Clock::now() - t0).count();
    const std::string status = setup->get("/jobs/" + ids[0]).json().at("status");
    for (const std::string& id : ids) setup->request("DELETE", "/jobs/" + id);

    std::printf("server %s, %d connections, %.1f s, %d job(s) submitted (first: %s at the end)\n",
                o.server.c_str(), o.connections, wall, o.jobs, status.c_str());
    std::printf("%-8s %9s %10s %9s %9s %9s %9s\n", "request", "count", "req/s", "p50 ms", "p90 ms",
                "p99 ms", "max ms");
    auto row = [&](const std::string& name, std::vector<double> ms) {
      const double mx = ms.empty() ? 0.0 : *std::max_element(ms.begin(), ms.end());
      const double p50 = percentile(ms, 0.50), p90 = percentile(ms, 0.90),
                   p99 = percentile(ms, 0.99);
      std::printf("%-8s %9zu %10.0f %9.2f %9.2f %9.2f %9.2f\n", name.c_str(), ms.size(),
                  double(ms.size()) / wall, p50, p90, p99, mx);
    };
    std::vector<double> all;
    for (std::size_t k = 0; k < kinds.size(); ++k) {
      std::vector<double> ms;
      for (const Sample& s : samples) {
        if (s.kind == k) ms.push_back(s.ms);
      }
      row(kinds[k], ms);
    }
    for (const Sample& s : samples) all.push_back(s.ms);
    row("all", all);
    std::printf("errors: %ld\n", errors.load());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "server_load: %s\n", e.what());
    return 1;
  }
}
