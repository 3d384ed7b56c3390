// The job service over real HTTP: the `gearsph serve` process, a Beast
// client. Submit, poll, results, files, errors, idempotency, pagination,
// events, cancellation, studies, the dashboard's files.
#include <fstream>
#include <thread>

#include "solver/job/job.hpp"
#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

// One server for the tests that do not need a fresh one.
class ServerApi : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { server_ = new ServerProcess({"--threads-per-job", "1"}); }
  static void TearDownTestSuite() {
    expect_consistent_store(server_->data());
    delete server_;
    server_ = nullptr;
  }
  static ServerProcess* server_;
};
ServerProcess* ServerApi::server_ = nullptr;

TEST_F(ServerApi, SubmitPollResultsAndDownload) {
  auto c = server_->client();
  const ClientResponse r = c.post_json("/jobs", tiny_job().dump());
  ASSERT_EQ(r.status, 201u) << r.body;
  const json doc = r.json();
  const std::string id = doc.at("jobID");
  EXPECT_EQ(r.header("Location"), "/jobs/" + id);
  EXPECT_EQ(r.header("Content-Type"), "application/json");
  EXPECT_TRUE(doc.at("status") == "accepted" || doc.at("status") == "running") << doc.dump();
  EXPECT_EQ(doc.at("processID"), "gearsph-simulation");
  EXPECT_GT(doc.at("particles").get<int>(), 0);
  EXPECT_GT(doc.at("steps").get<int>(), 0);

  const json final_status = wait_final(c, id);
  ASSERT_EQ(final_status.at("status"), "successful") << final_status.dump();
  EXPECT_EQ(final_status.at("progress"), 100);
  EXPECT_EQ(final_status.at("step"), final_status.at("steps"));
  EXPECT_GT(final_status.at("wall_s").get<double>(), 0.0);
  EXPECT_FALSE(final_status.at("started").is_null());
  EXPECT_FALSE(final_status.at("finished").is_null());

  const ClientResponse res = c.get("/jobs/" + id + "/results");
  ASSERT_EQ(res.status, 200u) << res.body;
  const json results = res.json();
  EXPECT_GT(results.at("summary").at("max_von_mises_Pa").get<double>(), 0.0);
  EXPECT_EQ(results.at("summary").at("status"), "completed");
  std::set<std::string> names;
  for (const json& f : results.at("files")) names.insert(f.at("name").get<std::string>());
  for (const char* n : {"summary.json", "history.csv", "job.json"})
    EXPECT_TRUE(names.count(n)) << n;

  // The file, its content type, and the same bytes streamed to disk.
  const ClientResponse csv = c.get("/jobs/" + id + "/files/history.csv");
  ASSERT_EQ(csv.status, 200u);
  EXPECT_EQ(csv.header("Content-Type"), "text/csv; charset=utf-8");
  EXPECT_TRUE(csv.body == slurp(server_->data() / "jobs" / id / "history.csv"));
  EXPECT_EQ(csv.body.rfind("time_s", 0), 0u);
  const fs::path saved = server_->dir() / "history-download.csv";
  EXPECT_EQ(c.download("/jobs/" + id + "/files/history.csv", saved).status, 200u);
  EXPECT_TRUE(slurp(saved) == csv.body);
  EXPECT_EQ(c.get("/jobs/" + id + "/files/summary.json").header("Content-Type"),
            "application/json");

  // Ranges, and HEAD.
  const ClientResponse part = c.get("/jobs/" + id + "/files/history.csv", {{"Range", "bytes=2-9"}});
  EXPECT_EQ(part.status, 206u);
  EXPECT_EQ(part.body, csv.body.substr(2, 8));
  EXPECT_EQ(part.header("Content-Range"), "bytes 2-9/" + std::to_string(csv.body.size()));
  const ClientResponse tail = c.get("/jobs/" + id + "/files/history.csv", {{"Range", "bytes=-5"}});
  EXPECT_EQ(tail.body, csv.body.substr(csv.body.size() - 5));
  EXPECT_EQ(c.get("/jobs/" + id + "/files/history.csv", {{"Range", "bytes=99999999-"}}).status,
            416u);
  const ClientResponse head = c.request("HEAD", "/jobs/" + id + "/files/history.csv");
  EXPECT_EQ(head.status, 200u);
  EXPECT_EQ(head.header("Content-Length"), std::to_string(csv.body.size()));
  EXPECT_TRUE(head.body.empty());

  const ClientResponse listing = c.get("/jobs/" + id + "/files");
  EXPECT_EQ(listing.status, 200u);
  EXPECT_GE(listing.json().at("files").size(), 3u);
}

// N6: result files carry a strong ETag and Last-Modified; If-Range,
// If-None-Match and If-Modified-Since are honoured; a malformed Range is
// ignored, never read as another range (RFC 9110, 13 and 14).
TEST_F(ServerApi, ResultFilesHaveValidatorsAndStrictRanges) {
  auto c = server_->client();
  const std::string id = submit(c, tiny_job());
  ASSERT_EQ(wait_final(c, id).at("status"), "successful");
  const std::string file = "/jobs/" + id + "/files/history.csv";
  const ClientResponse whole = c.get(file);
  ASSERT_EQ(whole.status, 200u);
  const std::string etag = whole.header("ETag");
  const std::string modified = whole.header("Last-Modified");
  ASSERT_GE(etag.size(), 3u) << "no ETag";
  EXPECT_EQ(etag.front(), '"') << etag;  // strong: no W/
  EXPECT_EQ(etag.back(), '"') << etag;
  EXPECT_NE(modified.find(" GMT"), std::string::npos) << modified;

  // "1e2" is no first-byte-pos: the header is malformed and ignored, not a suffix range.
  const ClientResponse odd = c.get(file, {{"Range", "bytes=1e2-200"}});
  EXPECT_EQ(odd.status, 200u);
  EXPECT_TRUE(odd.body == whole.body);
  for (const char* bad : {"bytes= 2-9", "bytes=2 -9", "bytes=+2-9", "bytes=0x2-9"}) {
    EXPECT_EQ(c.get(file, {{"Range", bad}}).status, 200u) << bad;
  }
  EXPECT_EQ(c.get(file, {{"Range", "Bytes=2-9"}}).status, 206u);  // the unit is case-insensitive

  // If-Range: the current ETag or date gives the range, another gives the whole file.
  const ClientResponse same = c.get(file, {{"Range", "bytes=2-9"}, {"If-Range", etag}});
  EXPECT_EQ(same.status, 206u);
  EXPECT_EQ(same.header("ETag"), etag);
  EXPECT_EQ(c.get(file, {{"Range", "bytes=2-9"}, {"If-Range", modified}}).status, 206u);
  const ClientResponse changed =
      c.get(file, {{"Range", "bytes=2-9"}, {"If-Range", "\"not-this-one\""}});
  EXPECT_EQ(changed.status, 200u);
  EXPECT_TRUE(changed.body == whole.body);
  EXPECT_EQ(c.get(file, {{"Range", "bytes=2-9"}, {"If-Range", "W/" + etag}}).status, 200u);
  EXPECT_EQ(
      c.get(file, {{"Range", "bytes=2-9"}, {"If-Range", "Thu, 01 Jan 1970 00:00:00 GMT"}}).status,
      200u);

  // Conditional GET: 304 without a body, with the validators.
  const ClientResponse cached = c.get(file, {{"If-None-Match", "\"x\", " + etag}});
  EXPECT_EQ(cached.status, 304u);
  EXPECT_TRUE(cached.body.empty());
  EXPECT_EQ(cached.header("ETag"), etag);
  EXPECT_EQ(c.get(file, {{"If-None-Match", "*"}}).status, 304u);
  EXPECT_EQ(c.get(file, {{"If-None-Match", "\"x\""}}).status, 200u);
  EXPECT_EQ(c.get(file, {{"If-Modified-Since", modified}}).status, 304u);
  EXPECT_EQ(c.get(file, {{"If-Modified-Since", "Thu, 01 Jan 1970 00:00:00 GMT"}}).status, 200u);
  // If-None-Match wins over If-Modified-Since (RFC 9110, 13.2.2).
  EXPECT_EQ(c.get(file, {{"If-None-Match", "\"x\""}, {"If-Modified-Since", modified}}).status,
            200u);
}

TEST_F(ServerApi, OgcExecuteRequestAndProcessDescription) {
  auto c = server_->client();
  const ClientResponse r = c.post_json("/processes/gearsph-simulation/execution",
                                       json{{"inputs", {{"job", tiny_job()}}}}.dump());
  ASSERT_EQ(r.status, 201u) << r.body;
  EXPECT_EQ(wait_final(c, r.json().at("jobID")).at("status"), "successful");

  json bad = tiny_job();
  bad["time"]["end_s"] = -1;
  const ClientResponse invalid = c.post_json("/processes/gearsph-simulation/execution",
                                             json{{"inputs", {{"job", bad}}}}.dump());
  EXPECT_EQ(invalid.status, 400u);
  EXPECT_EQ(invalid.json().at("errors").at(0).at("pointer"), "/inputs/job/time/end_s");
  EXPECT_EQ(c.post_json("/processes/nope/execution", tiny_job().dump()).status, 404u);

  const ClientResponse list = c.get("/processes");
  ASSERT_EQ(list.status, 200u);
  EXPECT_EQ(list.json().at("processes").at(0).at("id"), "gearsph-simulation");
  const ClientResponse desc = c.get("/processes/gearsph-simulation");
  ASSERT_EQ(desc.status, 200u);
  EXPECT_EQ(desc.json().at("inputs").at("job").at("schema"), job_schema());
  const ClientResponse none = c.get("/processes/other");
  EXPECT_EQ(none.status, 404u);
  EXPECT_EQ(none.json().at("type"),
            "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/no-such-process");
  EXPECT_EQ(c.get("/conformance").status, 200u);
}

TEST_F(ServerApi, SchemaHealthAndLanding) {
  auto c = server_->client();
  const ClientResponse schema = c.get("/schema");
  ASSERT_EQ(schema.status, 200u);
  EXPECT_EQ(schema.json(), job_schema());
  const ClientResponse health = c.get("/health");
  ASSERT_EQ(health.status, 200u);
  const json h = health.json();
  EXPECT_EQ(h.at("status"), "ok");
  EXPECT_FALSE(h.at("version").get<std::string>().empty());
  for (const char* s : {"accepted", "running", "successful", "failed", "dismissed"}) {
    EXPECT_TRUE(h.at("queue").contains(s)) << s;
  }
  EXPECT_EQ(h.at("workers").get<int>() * h.at("threads_per_job").get<int>() >= 1, true);
  const ClientResponse landing = c.get("/", {{"Accept", "application/json"}});
  ASSERT_EQ(landing.status, 200u);
  EXPECT_FALSE(landing.json().at("links").empty());
}

TEST_F(ServerApi, InvalidJobListsEveryPointer) {
  auto c = server_->client();
  json job = tiny_job();
  job["scene"]["lenght_m"] = 0.1;
  job["time"]["end_s"] = -1;
  const ClientResponse r = c.post_json("/jobs", job.dump());
  ASSERT_EQ(r.status, 400u);
  EXPECT_EQ(r.header("Content-Type"), "application/problem+json");
  const json p = r.json();
  EXPECT_EQ(p.at("status"), 400);
  EXPECT_EQ(p.at("instance"), "/jobs");
  std::set<std::string> pointers;
  for (const json& e : p.at("errors")) {
    pointers.insert(e.at("pointer").get<std::string>());
    EXPECT_FALSE(e.at("detail").get<std::string>().empty());
  }
  EXPECT_TRUE(pointers.count("/scene/lenght_m"));
  EXPECT_TRUE(pointers.count("/time/end_s"));
  for (const char* key : {"type", "title", "status", "detail", "instance"})
    EXPECT_TRUE(p.contains(key));
}

TEST_F(ServerApi, RefusesTooLargeJobsWithTheEstimate) {
  auto c = server_->client();
  json huge = tiny_job();
  huge["discretization"]["spacing_m"] = 1e-7;  // ~1e11 particles: refused before building
  const ClientResponse r = c.post_json("/jobs", huge.dump());
  ASSERT_EQ(r.status, 422u) << r.body;
  EXPECT_EQ(r.json().at("type"), "urn:gearsph:problem:job-too-large");
  EXPECT_TRUE(r.json().contains("estimate"));
  json slow = tiny_job(1000.0);  // ~5000 particles, ~3e8 steps: over the step limits
  slow["discretization"]["spacing_m"] = 0.0005;
  const ClientResponse s = c.post_json("/jobs", slow.dump());
  ASSERT_EQ(s.status, 422u) << s.body.substr(0, 300);
  EXPECT_GT(s.json().at("estimate").at("steps").get<double>(), 1e8);
  EXPECT_EQ(s.json().at("errors").at(0).at("pointer"), "/time/end_s");
}

TEST_F(ServerApi, MalformedBodiesAndWrongTypes) {
  auto c = server_->client();
  const ClientResponse malformed = c.post_json("/jobs", "{\"scene\": ");
  EXPECT_EQ(malformed.status, 400u);
  EXPECT_EQ(malformed.json().at("type"), "urn:gearsph:problem:malformed-json");
  EXPECT_EQ(c.post_json("/jobs", std::string(100, '[')).status, 400u);  // nested too deep
  EXPECT_EQ(c.post_json("/jobs", "").status, 400u);
  EXPECT_EQ(c.request("POST", "/jobs", tiny_job().dump(), {{"Content-Type", "text/plain"}}).status,
            415u);
  EXPECT_EQ(c.request("POST", "/jobs", tiny_job().dump()).status, 415u);  // no Content-Type
  EXPECT_EQ(c.request("POST", "/jobs", tiny_job().dump(),
                      {{"Content-Type", "application/json; charset=utf-8"}})
                .status,
            201u);
  // Over the 1 MiB default: 413, declared or not.
  const std::string big(2 << 20, ' ');
  EXPECT_EQ(c.post_json("/jobs", big).status, 413u);
  EXPECT_EQ(c.get("/health").status, 200u);  // and the server goes on
}

TEST_F(ServerApi, NotFoundAndMethodNotAllowed) {
  auto c = server_->client();
  const ClientResponse route = c.get("/no/such/route");
  EXPECT_EQ(route.status, 404u);
  EXPECT_EQ(route.header("Content-Type"), "application/problem+json");
  const std::string unknown = "00000000-0000-4000-8000-000000000000";
  for (const std::string& t :
       std::vector<std::string>{"/jobs/" + unknown, "/jobs/" + unknown + "/results",
                                "/jobs/" + unknown + "/files/summary.json", "/jobs/not-an-id",
                                "/jobs/" + unknown + "/events", "/studies/" + unknown}) {
    const ClientResponse r = c.get(t);
    EXPECT_EQ(r.status, 404u) << t;
  }
  EXPECT_EQ(c.get("/jobs/" + unknown).json().at("type"),
            "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/no-such-job");
  // The job's own routes answer alike: its status, files and events.
  for (const std::string& t :
       std::vector<std::string>{"/jobs/" + unknown, "/jobs/" + unknown + "/files/summary.json",
                                "/jobs/" + unknown + "/events"}) {
    const json p = c.get(t).json();
    EXPECT_EQ(p.at("type"),
              "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/no-such-job")
        << t;
    EXPECT_EQ(p.at("title"), "No such job") << t;
    EXPECT_EQ(p.at("detail"), "there is no job " + unknown) << t;
  }
  // So do the process's: its description and its execution.
  const json described = c.get("/processes/no-such").json();
  const json executed = c.post_json("/processes/no-such/execution", "{}").json();
  EXPECT_EQ(described.at("title"), "No such process");
  EXPECT_EQ(executed.at("title"), "No such process");
  EXPECT_EQ(described.at("detail"), executed.at("detail"));
  EXPECT_EQ(c.request("DELETE", "/jobs/" + unknown).status, 404u);

  const ClientResponse put = c.request("PUT", "/jobs", "{}");
  EXPECT_EQ(put.status, 405u);
  EXPECT_EQ(put.header("Allow"), "GET, POST, HEAD, OPTIONS");
  const ClientResponse del = c.request("DELETE", "/health");
  EXPECT_EQ(del.status, 405u);
  EXPECT_EQ(del.header("Allow"), "GET, HEAD, OPTIONS");
  EXPECT_EQ(c.request("PATCH", "/jobs/" + unknown).status, 405u);
  EXPECT_EQ(c.request("BREW", "/jobs").status, 405u);  // a method nobody knows
  EXPECT_EQ(c.request("OPTIONS", "/jobs").status, 204u);
}

TEST_F(ServerApi, PathTraversalIsRefused) {
  auto c = server_->client();
  const std::string id = submit(c, tiny_job());
  ASSERT_EQ(wait_final(c, id).at("status"), "successful");
  // Asked through the API first: the job is recorded successful a moment
  // before its worker renames its directory into place, and the API
  // publishes it when asked (attempt_dirs.cpp).
  ASSERT_EQ(c.get("/jobs/" + id + "/results").status, 200u);
  // A link in the job directory pointing out of it is not served either.
  fs::create_symlink(server_->data() / "gearsph.db", server_->data() / "jobs" / id / "db.json");
  const std::string base = "/jobs/" + id + "/files/";
  const std::vector<std::string> targets = {
      base + "../../gearsph.db",
      base + "%2e%2e/%2e%2e/gearsph.db",
      base + "%2E%2E%2F%2E%2E%2Fgearsph.db",
      base + "..%2F..%2Fgearsph.db",
      base + "..%5C..%5Cgearsph.db",
      base + "%2Fetc%2Fpasswd",
      base + "/etc/passwd",
      base + "%2fetc%2fpasswd",
      base + ".",
      base + "..",
      base + "%00",
      base + "job.json%00.png",
      base + "db.json",
      base + ".hidden",
      base + "summary.json/",
      "/jobs/..%2F..%2Fgearsph.db/files/x",
      "/jobs/" + id + "/../../gearsph.db",
      "/../../../../etc/passwd",
      "/%2e%2e/%2e%2e/etc/passwd",
      "/..%2f..%2fetc%2fpasswd",
      "/etc/passwd",
      "//etc/passwd",
      "/jobs/" + id + "/files/%",
      "/jobs/" + id + "/files/%zz",
  };
  for (const std::string& t : targets) {
    const ClientResponse r = c.get(t);
    EXPECT_TRUE(r.status == 400u || r.status == 404u) << t << " -> " << r.status;
    EXPECT_EQ(r.body.find("SQLite format"), std::string::npos) << t;
    EXPECT_EQ(r.body.find("root:"), std::string::npos) << t;
  }
  // Targets that are not even paths.
  for (const std::string t : {"http://example.com/etc/passwd", "*", "etc/passwd"}) {
    const std::string answer =
        raw_exchange(server_->host(), server_->port(),
                     "GET " + t + " HTTP/1.1\r\nHost: 127.0.0.1:" + server_->port() +
                         "\r\nConnection: close\r\n\r\n",
                     std::chrono::seconds(5));
    EXPECT_EQ(answer.rfind("HTTP/1.1 400", 0), 0u) << t << ": " << answer.substr(0, 40);
  }
}

TEST_F(ServerApi, IdempotencyKey) {
  auto c = server_->client();
  const json job = tiny_job();
  const ClientResponse first = c.post_json("/jobs", job.dump(), {{"Idempotency-Key", "k-1"}});
  ASSERT_EQ(first.status, 201u) << first.body;
  // The same request, even formatted differently: the same job, 200.
  const ClientResponse again = c.post_json("/jobs", job.dump(2), {{"Idempotency-Key", "k-1"}});
  ASSERT_EQ(again.status, 200u) << again.body;
  EXPECT_EQ(again.json().at("jobID"), first.json().at("jobID"));
  EXPECT_EQ(again.header("Location"), first.header("Location"));
  // The key with another body: 409.
  const ClientResponse other =
      c.post_json("/jobs", tiny_job(0.004).dump(), {{"Idempotency-Key", "k-1"}});
  EXPECT_EQ(other.status, 409u);
  EXPECT_EQ(other.header("Content-Type"), "application/problem+json");
  // Without a key, or with another, a new job.
  EXPECT_NE(submit(c, job), first.json().at("jobID").get<std::string>());
  EXPECT_EQ(c.post_json("/jobs", job.dump(), {{"Idempotency-Key", "k-2"}}).status, 201u);
  EXPECT_EQ(c.post_json("/jobs", job.dump(), {{"Idempotency-Key", std::string(300, 'k')}}).status,
            400u);
}

TEST(ServerJobs, PaginationAndStatusFilter) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  std::set<std::string> ids;
  for (int i = 0; i < 5; ++i) ids.insert(submit(c, tiny_job()));
  for (const std::string& id : ids) EXPECT_EQ(wait_final(c, id).at("status"), "successful");
  // One more, dismissed while queued behind a longer one.
  const std::string longer = submit(c, tiny_job(0.5));
  const std::string queued = submit(c, tiny_job());
  EXPECT_EQ(c.request("DELETE", "/jobs/" + queued).json().at("status"), "dismissed");

  std::set<std::string> seen;
  std::string next = "/jobs?limit=2";
  int pages = 0;
  while (!next.empty() && pages < 10) {
    const ClientResponse r = c.get(next);
    ASSERT_EQ(r.status, 200u) << r.body;
    const json page = r.json();
    EXPECT_EQ(page.at("numberMatched"), 7);
    EXPECT_LE(page.at("jobs").size(), 2u);
    for (const json& j : page.at("jobs")) seen.insert(j.at("jobID").get<std::string>());
    next.clear();
    for (const json& l : page.at("links")) {
      if (l.at("rel") == "next") next = l.at("href");
    }
    ++pages;
  }
  EXPECT_EQ(pages, 4);
  EXPECT_EQ(seen.size(), 7u);

  const json done = c.get("/jobs?status=successful&limit=100").json();
  EXPECT_EQ(done.at("numberMatched"), 5);
  for (const json& j : done.at("jobs")) EXPECT_EQ(j.at("status"), "successful");
  const json two = c.get("/jobs?status=dismissed,successful").json();
  EXPECT_EQ(two.at("numberMatched"), 6);
  const json page2 = c.get("/jobs?limit=3&offset=3").json();
  bool has_prev = false;
  for (const json& l : page2.at("links")) has_prev = has_prev || l.at("rel") == "prev";
  EXPECT_TRUE(has_prev);
  EXPECT_EQ(c.get("/jobs?status=finished").status, 400u);
  EXPECT_EQ(c.get("/jobs?limit=0").status, 400u);
  EXPECT_EQ(c.get("/jobs?limit=abc").status, 400u);
  EXPECT_EQ(c.get("/jobs?offset=-1").status, 400u);
  c.request("DELETE", "/jobs/" + longer);
}

TEST(ServerJobs, EventsStreamProgressAndFinalStatus) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  // Everything on the multiplexed stream, read beside the job's own stream.
  std::vector<SseEvent> all;
  std::string id;
  std::mutex id_mutex;
  // A jthread joins even when the test body throws, and the reader's own
  // errors are reported, not fatal: either used to abort the whole binary.
  std::string reader_error;
  std::jthread reader([&] {
    try {
      auto mc = server.client(std::chrono::seconds(60));
      mc.events("/events", [&](const SseEvent& e) {
        all.push_back(e);
        std::lock_guard<std::mutex> lock(id_mutex);
        const json d = json::parse(e.data);
        return !(e.event == "status" && d.value("jobID", "") == id && !id.empty() &&
                 is_final(d.value("status", "")));
      });
    } catch (const std::exception& e) {
      reader_error = e.what();
    }
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the stream is open
  {
    std::lock_guard<std::mutex> lock(id_mutex);
    id = submit(c, tiny_job(0.1));
  }
  std::vector<SseEvent> events;
  const ClientResponse head = c.events("/jobs/" + id + "/events", [&](const SseEvent& e) {
    events.push_back(e);
    return true;  // the server ends the stream after the final status
  });
  EXPECT_EQ(head.status, 200u);
  EXPECT_EQ(head.header("Content-Type"), "text/event-stream");
  reader.join();
  EXPECT_TRUE(reader_error.empty()) << "the /events reader failed: " << reader_error;

  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.front().event, "status");  // the stream starts with the job's status
  int progress = 0;
  std::uint64_t last_id = 0;
  for (const SseEvent& e : events) {
    const std::uint64_t n = std::stoull(e.id);
    EXPECT_GE(n, last_id);  // ids only grow
    last_id = n;
    const json d = json::parse(e.data);
    EXPECT_EQ(d.at("jobID"), id);
    if (e.event == "progress") {
      ++progress;
      EXPECT_GE(d.at("progress").get<int>(), 0);
      EXPECT_LE(d.at("progress").get<int>(), 100);
    }
  }
  EXPECT_GE(progress, 1);
  EXPECT_EQ(events.back().event, "status");
  EXPECT_EQ(json::parse(events.back().data).at("status"), "successful");

  int all_progress = 0;
  bool all_final = false;
  for (const SseEvent& e : all) {
    const json d = json::parse(e.data);
    if (d.value("jobID", "") != id) continue;
    all_progress += e.event == "progress";
    all_final = all_final || (e.event == "status" && d.at("status") == "successful");
  }
  EXPECT_GE(all_progress, 1);
  EXPECT_TRUE(all_final);

  // Resuming with Last-Event-ID: only what came after that event, no snapshot.
  const SseEvent& resume_from = events.at(1);
  std::vector<SseEvent> rest;
  c.events("/jobs/" + id + "/events",
           [&](const SseEvent& e) {
             rest.push_back(e);
             return true;
           },
           {{"Last-Event-ID", resume_from.id}});
  ASSERT_FALSE(rest.empty());
  EXPECT_GT(std::stoull(rest.front().id), std::stoull(resume_from.id));
  EXPECT_EQ(json::parse(rest.back().data).at("status"), "successful");
}

TEST(ServerJobs, CancelRunningDismissQueuedDeleteFinished) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  const std::string done = submit(c, tiny_job());
  ASSERT_EQ(wait_final(c, done).at("status"), "successful");
  const std::string running = submit(c, tiny_job(20.0));
  const std::string queued = submit(c, tiny_job());
  wait_for(c, running, [](const json& s) { return s.at("step").get<int>() > 0; });

  // Queued: dismissed at once, never runs.
  const ClientResponse q = c.request("DELETE", "/jobs/" + queued);
  ASSERT_EQ(q.status, 200u);
  EXPECT_EQ(q.json().at("status"), "dismissed");

  // Running: the worker stops at its next check.
  const auto t0 = Clock::now();
  const ClientResponse r = c.request("DELETE", "/jobs/" + running);
  ASSERT_EQ(r.status, 200u);
  EXPECT_EQ(r.json().at("status"), "dismissed");
  const json stopped = wait_for(c, running, [](const json& s) {
    return s.at("message").get<std::string>().find("stopped at step") != std::string::npos;
  });
  EXPECT_LT(Clock::now() - t0, std::chrono::seconds(10));
  EXPECT_EQ(stopped.at("status"), "dismissed");
  EXPECT_LT(stopped.at("step").get<long>(), stopped.at("steps").get<long>());
  EXPECT_EQ(c.get("/jobs/" + running + "/results").status, 404u);
  EXPECT_EQ(c.get("/jobs/" + queued).json().at("started"), nullptr);

  // Finished: dismissed, and its files are deleted.
  ASSERT_TRUE(fs::exists(server.data() / "jobs" / done / "summary.json"));
  const ClientResponse d = c.request("DELETE", "/jobs/" + done);
  ASSERT_EQ(d.status, 200u);
  EXPECT_EQ(d.json().at("status"), "dismissed");
  EXPECT_FALSE(fs::exists(server.data() / "jobs" / done));
  EXPECT_EQ(c.get("/jobs/" + done + "/files/summary.json").status, 404u);
  const ClientResponse results = c.get("/jobs/" + done + "/results");
  EXPECT_EQ(results.status, 404u);
  EXPECT_EQ(results.json().at("type"),
            "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/result-not-ready");
  // Dismissing again changes nothing.
  EXPECT_EQ(c.request("DELETE", "/jobs/" + done).json().at("status"), "dismissed");
  expect_consistent_store(server.data());
}

TEST(ServerJobs, ResultsNotReadyAndFailedJobs) {
  ServerProcess server({"--workers", "1", "--threads-per-job", "1"});
  auto c = server.client();
  const std::string blocker = submit(c, tiny_job(20.0));
  wait_for(c, blocker, [](const json& s) { return s.at("status") == "running"; });
  const ClientResponse running = c.get("/jobs/" + blocker + "/results");
  EXPECT_EQ(running.status, 404u);
  EXPECT_EQ(running.json().at("type"),
            "http://www.opengis.net/def/exceptions/ogcapi-processes-1/1.0/result-not-ready");
  c.request("DELETE", "/jobs/" + blocker);

  // A run that diverges fails, and its results say why.
  json unstable = tiny_job(0.01);
  unstable["time"]["cfl"] = 1.6;
  unstable["time"]["allow_unstable"] = true;
  const std::string id = submit(c, unstable);
  const json final_status = wait_final(c, id);
  ASSERT_EQ(final_status.at("status"), "failed");
  EXPECT_NE(final_status.at("message").get<std::string>().find("diverged"), std::string::npos);
  const ClientResponse r = c.get("/jobs/" + id + "/results");
  EXPECT_EQ(r.status, 500u);
  EXPECT_EQ(r.json().at("type"), "urn:gearsph:problem:job-failed");
  EXPECT_NE(r.json().at("detail").get<std::string>().find("diverged"), std::string::npos);
}

#ifndef GEARSPH_WITH_RENDER
// With the renderer built in, test_server_images.cpp checks the images.
TEST(ServerJobs, ImagesWithoutARendererAnswer501) {
  ServerProcess server({"--threads-per-job", "1"});
  auto c = server.client();
  const std::string id = submit(c, tiny_job());
  ASSERT_EQ(wait_final(c, id).at("status"), "successful");
  const ClientResponse r = c.get("/jobs/" + id + "/images/von_mises.png?frame=0");
  EXPECT_EQ(r.status, 501u);
  EXPECT_EQ(r.json().at("detail"), "rendering not available in this build");
  EXPECT_EQ(c.get("/jobs/" + id + "/images/von_mises.png?frame=x").status, 400u);
  EXPECT_EQ(c.get("/jobs/" + id + "/images/von_mises.png?zoom=1,1,0,0").status, 400u);
  EXPECT_EQ(c.get("/jobs/" + id + "/images/a..b.png").status, 404u);
}
#endif

TEST(ServerStatic, DashboardFilesFromTheWebRoot) {
  TempDir web;
  std::ofstream(web.path() / "index.html") << "<!doctype html><title>GearSPH</title>";
  std::ofstream(web.path() / "app.js") << "console.log(1);";
  fs::create_directories(web.path() / "vendor");
  std::ofstream(web.path() / "vendor" / "chart.css") << "body{}";
  TempDir outside;
  std::ofstream(outside.path() / "secret.txt") << "root:secret";
  fs::create_symlink(outside.path() / "secret.txt", web.path() / "leak.txt");
  ServerProcess server({"--web", web.path().string()});
  auto c = server.client();
  const ClientResponse page = c.get("/", {{"Accept", "text/html,*/*"}});
  ASSERT_EQ(page.status, 200u);
  EXPECT_EQ(page.header("Content-Type"), "text/html; charset=utf-8");
  EXPECT_NE(page.body.find("GearSPH"), std::string::npos);
  EXPECT_EQ(c.get("/app.js").header("Content-Type"), "text/javascript; charset=utf-8");
  EXPECT_EQ(c.get("/vendor/chart.css").status, 200u);
  EXPECT_EQ(c.get("/index.html").status, 200u);
  EXPECT_EQ(c.get("/missing.js").status, 404u);
  EXPECT_EQ(c.get("/leak.txt").status, 404u);
  EXPECT_EQ(c.get("/vendor/../app.js").status, 400u);
  EXPECT_EQ(c.request("POST", "/app.js", "x").status, 404u);
  EXPECT_EQ(c.get("/", {{"Accept", "application/json"}}).header("Content-Type"),
            "application/json");
}

TEST(ServerStudies, SweepExpandsRunsAndTabulates) {
  ServerProcess server({"--threads-per-job", "1"});
  auto c = server.client();
  const json study = {{"name", "sweep"},
                      {"base", tiny_job(0.002)},
                      {"axes",
                       {{{"pointer", "/discretization/spacing_m"}, {"values", {0.004, 0.002}}},
                        {{"pointer", "/time/end_s"}, {"values", {0.002, 0.003}}}}}};
  const ClientResponse r = c.post_json("/studies", study.dump(), {{"Idempotency-Key", "s1"}});
  ASSERT_EQ(r.status, 201u) << r.body;
  const json doc = r.json();
  const std::string id = doc.at("studyID");
  EXPECT_EQ(r.header("Location"), "/studies/" + id);
  ASSERT_EQ(doc.at("jobs").size(), 4u);
  EXPECT_EQ(doc.at("jobs").at(1).at("parameters").at("/time/end_s"), 0.003);
  EXPECT_EQ(doc.at("jobs").at(2).at("parameters").at("/discretization/spacing_m"), 0.002);
  EXPECT_FALSE(doc.contains("table"));
  EXPECT_EQ(c.post_json("/studies", study.dump(), {{"Idempotency-Key", "s1"}}).json().at("studyID"),
            id);

  json done;
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (Clock::now() < deadline) {
    done = c.get("/studies/" + id).json();
    if (done.at("status") == "successful") break;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_EQ(done.at("status"), "successful") << done.dump();
  ASSERT_EQ(done.at("table").size(), 4u);
  const json& row = done.at("table").at(3);
  EXPECT_EQ(row.at("/discretization/spacing_m"), 0.002);
  EXPECT_EQ(row.at("/time/end_s"), 0.003);
  EXPECT_GT(row.at("max_von_mises_Pa").get<double>(), 0.0);
  EXPECT_GT(row.at("particles").get<int>(), done.at("table").at(0).at("particles").get<int>());

  const ClientResponse csv = c.get("/studies/" + id + "?format=csv");
  ASSERT_EQ(csv.status, 200u);
  EXPECT_EQ(csv.header("Content-Type"), "text/csv; charset=utf-8");
  EXPECT_EQ(std::count(csv.body.begin(), csv.body.end(), '\n'), 5);
  EXPECT_EQ(csv.body.rfind("job,jobID,status,/discretization/spacing_m,/time/end_s,", 0), 0u)
      << csv.body.substr(0, 200);
  EXPECT_EQ(c.get("/studies/" + id, {{"Accept", "text/csv"}}).body, csv.body);

  // Refusals point into the study request.
  json bad_axis = study;
  bad_axis["axes"][0]["pointer"] = "discretization";
  const ClientResponse b1 = c.post_json("/studies", bad_axis.dump());
  EXPECT_EQ(b1.status, 400u);
  EXPECT_EQ(b1.json().at("errors").at(0).at("pointer"), "/axes/0/pointer");
  json bad_value = study;
  bad_value["axes"][0]["values"][1] = -1;
  const ClientResponse b2 = c.post_json("/studies", bad_value.dump());
  EXPECT_EQ(b2.status, 400u);
  EXPECT_EQ(b2.json().at("errors").at(0).at("pointer"), "/axes/0/values/1");
  json too_many = study;
  too_many["axes"][0]["values"] = json::array();
  for (int i = 0; i < 200; ++i) too_many["axes"][0]["values"].push_back(0.002);
  EXPECT_EQ(c.post_json("/studies", too_many.dump()).status, 400u);
}

// A speed sweep as a study (docs/dynamics.md): planned as the CLI plans it,
// one job per ratio, each ending on its steady mesh; refused at pointers
// into the request before any job is stored; and once no job is left to
// run, the study's document carries the sweep's report (here with the jobs
// dismissed before any ran: the lumped model's curve, no SPH values). An
// API without workers keeps the jobs queued until then.
TEST(ServerStudies, ASpeedSweepIsPlannedRefusedAndReported) {
  ServerProcess server({"--no-local-workers"});
  auto c = server.client();
  const json job = {{"name", "pair"},
                    {"scene",
                     {{"type", "rack_pinion"},
                      {"pinion", {{"omega_rad_s", -15.0}}},
                      {"rack", {{"velocity_m_s", -0.36}, {"load_N", 5000.0}}}}},
                    {"discretization", {{"particles", "lattice"}, {"spacing_mm", 2.0}}}};
  const json sweep = {
      {"name", "paper-pair"},
      {"speed_sweep", {{"job", job}, {"ratios", {0.5, 1.5}}, {"steady_periods", 2}}}};
  auto refused_at = [&](const json& body) {
    const ClientResponse r = c.post_json("/studies", body.dump());
    EXPECT_EQ(r.status, 400u) << r.body;
    std::vector<std::string> pointers;
    const json problem = r.json();
    for (const json& e : problem.at("errors")) pointers.push_back(e.at("pointer"));
    return pointers;
  };
  json bad = sweep;
  bad["speed_sweep"]["ratios"] = {0.5, -1.0};
  EXPECT_EQ(refused_at(bad), std::vector<std::string>{"/speed_sweep/ratios/1"});
  bad = sweep;
  bad["speed_sweep"]["job"]["scene"]["quasi_static"] = true;
  EXPECT_EQ(refused_at(bad), std::vector<std::string>{"/speed_sweep/job/scene/quasi_static"});
  bad = sweep;
  bad["speed_sweep"]["job"]["scene"]["rack"]["load_N"] = 0.0;
  EXPECT_EQ(refused_at(bad), std::vector<std::string>{"/speed_sweep/job/scene/rack/load_N"});
  bad = sweep;
  bad["speed_sweep"]["stiffness"] = "measured";
  EXPECT_EQ(refused_at(bad), std::vector<std::string>{"/speed_sweep/stiffness"});
  bad = sweep;
  bad["speed_sweep"]["stiffness"] = {{"position", {0.5, 0.2}}, {"stiffness_N_m", {3e8, 4e8}}};
  EXPECT_EQ(refused_at(bad), std::vector<std::string>{"/speed_sweep/stiffness"});
  bad = sweep;
  bad["axes"] = json::array();
  EXPECT_EQ(refused_at(bad), std::vector<std::string>{"/axes"});
  EXPECT_EQ(c.get("/jobs").json().at("jobs").size(), 0u);  // nothing was stored

  const ClientResponse r = c.post_json("/studies", sweep.dump());
  ASSERT_EQ(r.status, 201u) << r.body;
  const json doc = r.json();
  EXPECT_EQ(doc.at("kind"), "speed_sweep");
  EXPECT_EQ(doc.at("name"), "paper-pair");
  ASSERT_EQ(doc.at("jobs").size(), 2u);
  std::vector<double> f_mesh;
  for (std::size_t k = 0; k < 2; ++k) {
    const json& j = doc.at("jobs").at(k);
    EXPECT_EQ(j.at("parameters").at("ratio"), sweep["speed_sweep"]["ratios"][k]);
    f_mesh.push_back(j.at("parameters").at("mesh_frequency_Hz").get<double>());
  }
  EXPECT_NEAR(f_mesh[1] / f_mesh[0], 3.0, 1e-9);
  EXPECT_FALSE(doc.contains("speed_sweep"));  // not before the jobs are over

  for (const json& j : doc.at("jobs")) {
    EXPECT_EQ(c.request("DELETE", "/jobs/" + j.at("jobID").get<std::string>()).status, 200u);
  }
  const json done = c.get("/studies/" + doc.at("studyID").get<std::string>()).json();
  ASSERT_TRUE(done.contains("speed_sweep")) << done.dump();
  const json& report = done.at("speed_sweep");
  ASSERT_FALSE(report.contains("error")) << report.dump();
  ASSERT_EQ(report.at("mesh_frequency_Hz").size(), 2u);
  EXPECT_NEAR(report.at("mesh_frequency_Hz").at(0).get<double>(), f_mesh[0], 1e-9 * f_mesh[0]);
  EXPECT_TRUE(report.at("K_v_sph").at(0).is_null());  // no job ran
  EXPECT_GT(report.at("K_v_sdof").at(0).get<double>(), 1.0);
  EXPECT_GT(report.at("natural_frequency_Hz_sdof").get<double>(), 0.0);
  EXPECT_EQ(report.at("stiffness_from"), "iso");
}

TEST(ServerSubmit, CliSubmitsWaitsAndDownloads) {
  ServerProcess server({"--threads-per-job", "1"});
  const fs::path job = server.dir() / "job.json";
  std::ofstream(job) << tiny_job(0.02).dump();
  const fs::path out = server.dir() / "out";
  const std::string cmd = std::string(GEARSPH_BINARY) + " submit " + job.string() + " --server " +
                          server.url() + " --wait --out " + out.string() + " > " +
                          (server.dir() / "submit.out").string() + " 2> " +
                          (server.dir() / "submit.err").string();
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0) << slurp(server.dir() / "submit.err");
  const std::string id = slurp(server.dir() / "submit.out");
  EXPECT_EQ(id.size(), 37u) << id;  // the id and a newline
  EXPECT_NE(slurp(server.dir() / "submit.err").find("successful"), std::string::npos);
  for (const char* f : {"summary.json", "history.csv", "job.json", "results.json"}) {
    EXPECT_TRUE(fs::exists(out / f)) << f;
  }
  EXPECT_TRUE(slurp(out / "history.csv") ==
              slurp(server.data() / "jobs" / id.substr(0, 36) / "history.csv"));

  // An invalid job: exit status 2 and the pointers on stderr.
  std::ofstream(job) << R"({"scene": {"type": "plate", "lenght_m": 1}})";
  const int bad =
      std::system((std::string(GEARSPH_BINARY) + " submit " + job.string() + " --server " +
                   server.url() + " 2> " + (server.dir() / "bad.err").string())
                      .c_str());
  EXPECT_EQ(WEXITSTATUS(bad), 2);
  EXPECT_NE(slurp(server.dir() / "bad.err").find("/scene/lenght_m"), std::string::npos);
}

// By default the cores are a budget the jobs share: a study of small jobs
// runs one job per core, each on one thread while others wait (two
// paper-size jobs at once on two cores), and every job completes.
TEST(ServerScheduling, AStudysJobsShareTheCoresOneThreadEach) {
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  if (cores < 2) GTEST_SKIP() << "needs two cores";
  ServerProcess server;
  auto c = server.client();
  const json health = c.get("/health").json();
  EXPECT_EQ(health.at("core_budget").get<int>(), cores);
  EXPECT_EQ(health.at("workers").get<int>(), cores);
  // cores + 1 jobs of one to four seconds each on one thread.
  json lengths = json::array();
  for (int k = 0; k <= cores; ++k) lengths.push_back(0.6 + 0.001 * k);
  const json study = {{"name", "share"},
                      {"base", tiny_job(0.6)},
                      {"axes", {{{"pointer", "/time/end_s"}, {"values", lengths}}}}};
  const ClientResponse r = c.post_json("/studies", study.dump());
  ASSERT_EQ(r.status, 201u) << r.body;
  const std::string id = r.json().at("studyID");
  int most_running = 0;
  json done;
  const auto deadline = Clock::now() + std::chrono::seconds(120);
  for (;;) {
    most_running = std::max(most_running, c.get("/health").json().at("running_here").get<int>());
    done = c.get("/studies/" + id).json();
    if (done.at("status") != "running" && done.at("status") != "accepted") break;
    ASSERT_LT(Clock::now(), deadline) << done.dump();
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_EQ(done.at("status"), "successful") << done.dump();
  EXPECT_EQ(most_running, cores);  // all cores busy, never more jobs than cores
  // The jobs claimed while others waited ran on one thread (the last one
  // may have found a free core more).
  const json& jobs = done.at("jobs");
  ASSERT_EQ(jobs.size(), static_cast<std::size_t>(cores) + 1);
  for (int k = 0; k < cores; ++k) {
    const std::string job = jobs.at(k).at("jobID");
    EXPECT_EQ(c.get("/jobs/" + job + "/files/summary.json").json().at("threads").get<int>(), 1)
        << k;
  }
}

}  // namespace
}  // namespace gearsph::server::testing
