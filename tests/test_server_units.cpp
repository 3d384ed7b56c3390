// The server's parts on their own: job store, studies, ranges, targets,
// event hub, token comparison.
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <thread>

#include "server/client_identity.hpp"
#include "server/documents.hpp"
#include "server/event_hub.hpp"
#include "server/http_types.hpp"
#include "server/job_limits.hpp"
#include "server/job_store.hpp"
#include "server/log.hpp"
#include "server/range_file.hpp"
#include "server/router.hpp"
#include "server/sessions.hpp"
#include "server/sha256.hpp"
#include "server/static_files.hpp"
#include "server/study.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"
#ifdef GEARSPH_WITH_RENDER  // the results layer is built too
#include "results/register_outputs.hpp"
#endif
#include "tests/test_server_support.hpp"

namespace gearsph::server::testing {
namespace {

// The service refuses jobs by this estimate and the dashboard shows it: it
// must bound what the job directory really takes.
TEST(JobLimits, DiskEstimateBoundsTheWholeJobDirectory) {
  const nlohmann::json job = nlohmann::json::parse(R"({
    "name": "disk-estimate",
    "scene": {"type": "plate", "length_m": 0.1, "thickness_m": 0.01},
    "discretization": {"spacing_m": 0.002},
    "time": {"end_s": 0.002},
    "output": {"frames": 40, "history_points": 500}})");
#ifdef GEARSPH_WITH_RENDER
  results::register_outputs();  // results.h5 and results.xmf are written too
#endif
  PreparedJob prepared = prepare_job(job, 1);
  const JobEstimate estimate = estimate_job(prepared);
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("gearsph-disk-estimate-" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  ExecuteOptions options;
  options.threads = 1;
  ASSERT_EQ(execute_job(job, dir, options).run.status, "completed");
  std::uint64_t used = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) used += e.file_size();
  }
  EXPECT_GE(estimate.disk_bytes, used);
#ifdef GEARSPH_WITH_RENDER
  EXPECT_TRUE(std::filesystem::exists(dir / "results.h5"));
#endif
  std::printf("  estimate %llu bytes, the job directory %llu\n",
              static_cast<unsigned long long>(estimate.disk_bytes),
              static_cast<unsigned long long>(used));
  std::filesystem::remove_all(dir);
}

NewJob new_job(const std::string& name = "j") {
  NewJob j;
  j.id = new_id();
  j.name = name;
  j.job_json = "{}";
  j.steps = 100;
  return j;
}

TEST(ServerJobStore, ClaimIsAtomicAcrossThreads) {
  TempDir dir;
  auto store = open_sqlite_job_store(dir.path() / "jobs.db");
  constexpr int kJobs = 60;
  for (int i = 0; i < kJobs; ++i) store->submit(new_job(std::to_string(i)), std::nullopt);
  std::mutex mutex;
  std::vector<std::string> claimed;
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&] {
      auto own =
          open_sqlite_job_store(dir.path() / "jobs.db");  // another connection, as another process
      while (auto job = own->claim()) {
        std::lock_guard<std::mutex> lock(mutex);
        claimed.push_back(job->id);
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(claimed.size(), static_cast<std::size_t>(kJobs));
  EXPECT_EQ(std::set<std::string>(claimed.begin(), claimed.end()).size(),
            static_cast<std::size_t>(kJobs));
  EXPECT_EQ(store->count_by_status().at("running"), kJobs);
}

TEST(ServerJobStore, OldestFirstAndTheLifeCycle) {
  TempDir dir;
  auto store = open_sqlite_job_store(dir.path() / "jobs.db");
  const NewJob a = new_job("a"), b = new_job("b");
  store->submit(a, std::nullopt);
  store->submit(b, std::nullopt);
  auto first = store->claim();
  ASSERT_TRUE(first);
  EXPECT_EQ(first->id, a.id);
  EXPECT_EQ(first->status, JobStatus::running);
  EXPECT_EQ(first->attempts, 1);
  EXPECT_FALSE(first->started.empty());

  ProgressUpdate p{a.id, 50, 0.1, 2.0, 2.0, 50};
  EXPECT_TRUE(store->save_progress({p}).empty());
  EXPECT_EQ(store->job(a.id)->step, 50);
  // A dismissed job is reported back by the next progress batch.
  store->dismiss(a.id);
  EXPECT_EQ(store->save_progress({p}), std::vector<std::string>{a.id});
  EXPECT_FALSE(store->finish(a.id, JobStatus::successful, "done", p));
  EXPECT_TRUE(store->close_dismissed(a.id, "stopped at step 50", p));
  EXPECT_EQ(store->job(a.id)->status, JobStatus::dismissed);

  auto second = store->claim();
  ASSERT_TRUE(second);
  EXPECT_TRUE(
      store->finish(second->id, JobStatus::successful, "done", {second->id, 100, 1, 1, 0, 100}));
  EXPECT_FALSE(store->claim());
  const auto rec = store->job(b.id);
  EXPECT_EQ(rec->status, JobStatus::successful);
  EXPECT_EQ(rec->progress, 100);
  EXPECT_FALSE(rec->finished.empty());
  const auto before = store->dismiss(b.id);
  EXPECT_EQ(before->status, JobStatus::successful);
  EXPECT_NE(store->job(b.id)->message.find("files were deleted"), std::string::npos);
  EXPECT_FALSE(store->dismiss(new_id()));
}

TEST(ServerJobStore, RecoverRequeuesThenFailsAfterMaxAttempts) {
  TempDir dir;
  const auto file = dir.path() / "jobs.db";
  const NewJob j = new_job();
  {
    auto store = open_sqlite_job_store(file);
    store->submit(j, std::nullopt);
    store->claim();
  }
  {
    auto store = open_sqlite_job_store(file);  // after a crash
    const Recovery r = store->recover(2);
    EXPECT_EQ(r.requeued, std::vector<std::string>{j.id});
    EXPECT_TRUE(r.failed.empty());
    const auto rec = store->job(j.id);
    EXPECT_EQ(rec->status, JobStatus::accepted);
    EXPECT_NE(rec->message.find("re-queued"), std::string::npos);
    EXPECT_EQ(store->claim()->attempts, 2);
  }
  {
    auto store = open_sqlite_job_store(file);
    const Recovery r = store->recover(2);
    EXPECT_EQ(r.failed, std::vector<std::string>{j.id});
    EXPECT_EQ(store->job(j.id)->status, JobStatus::failed);
    EXPECT_NE(store->job(j.id)->message.find("interrupted 2 times"), std::string::npos);
  }
  Database db(file);
  // Version 2 added claims with leases and outside schedulers (scale-out),
  // version 3 the claims' tokens, version 4 the workers' heartbeats,
  // version 5 the run's stage, the FE check's outcome and the submitter,
  // version 6 the dashboard's sessions.
  EXPECT_EQ(db.query("SELECT version FROM schema_version").at(0).at(0), "6");
  EXPECT_EQ(db.query("PRAGMA journal_mode").at(0).at(0), "wal");
}

TEST(ServerJobStore, GracefulRequeueDoesNotCountTheAttempt) {
  TempDir dir;
  auto store = open_sqlite_job_store(dir.path() / "jobs.db");
  const NewJob j = new_job();
  store->submit(j, std::nullopt);
  store->claim();
  EXPECT_TRUE(store->requeue(j.id, "re-queued: stopping"));
  EXPECT_EQ(store->job(j.id)->attempts, 0);
  EXPECT_EQ(store->job(j.id)->status, JobStatus::accepted);
  EXPECT_FALSE(store->requeue(j.id, "again"));  // only a running job
}

TEST(ServerJobStore, IdempotencyKeys) {
  TempDir dir;
  auto store = open_sqlite_job_store(dir.path() / "jobs.db");
  const Idempotency k{"jobs", "key", "{\"a\":1}"};
  const NewJob a = new_job(), b = new_job();
  EXPECT_EQ(store->submit(a, k).kind, SubmitResult::Kind::created);
  const SubmitResult same = store->submit(b, k);
  EXPECT_EQ(same.kind, SubmitResult::Kind::existing);
  EXPECT_EQ(same.id, a.id);
  EXPECT_FALSE(store->job(b.id));  // nothing new stored
  EXPECT_EQ(store->submit(b, Idempotency{"jobs", "key", "{\"a\":2}"}).kind,
            SubmitResult::Kind::conflict);
  EXPECT_EQ(store->submit(b, Idempotency{"studies", "key", "{\"a\":2}"}).kind,
            SubmitResult::Kind::created);  // keys are per endpoint
}

TEST(ServerJobStore, PagesAndFilters) {
  TempDir dir;
  auto store = open_sqlite_job_store(dir.path() / "jobs.db");
  std::vector<std::string> ids;
  for (int i = 0; i < 7; ++i) {
    const NewJob j = new_job();
    ids.push_back(j.id);
    store->submit(j, std::nullopt);
  }
  store->claim();
  JobQuery q;
  q.limit = 3;
  JobPage p = store->jobs(q);
  EXPECT_EQ(p.total, 7);
  ASSERT_EQ(p.jobs.size(), 3u);
  EXPECT_EQ(p.jobs[0].id, ids[6]);  // newest first
  q.offset = 6;
  EXPECT_EQ(store->jobs(q).jobs.size(), 1u);
  q = {};
  q.statuses = {JobStatus::running};
  p = store->jobs(q);
  EXPECT_EQ(p.total, 1);
  EXPECT_EQ(p.jobs.at(0).id, ids[0]);
}

TEST(ServerStudy, ExpandsTheCartesianProductLastAxisFastest) {
  const StudySpec spec = parse_study({{"base", tiny_job()},
                                      {"axes",
                                       {{{"pointer", "/time/end_s"}, {"values", {1, 2, 3}}},
                                        {{"pointer", "/output/frames"}, {"values", {0, 10}}}}}},
                                     100);
  const auto points = expand_study(spec);
  ASSERT_EQ(points.size(), 6u);
  EXPECT_EQ(points[0].job["time"]["end_s"], 1);
  EXPECT_EQ(points[0].job["output"]["frames"], 0);
  EXPECT_EQ(points[1].job["output"]["frames"], 10);
  EXPECT_EQ(points[5].job["time"]["end_s"], 3);
  EXPECT_EQ(points[5].parameters, json({{"/time/end_s", 3}, {"/output/frames", 10}}));
  EXPECT_EQ(points[3].value_index, (std::vector<std::size_t>{1, 1}));
  EXPECT_EQ(points[0].job["scene"], tiny_job()["scene"]);  // the rest untouched
}

TEST(ServerStudy, RefusalsPointIntoTheRequest) {
  auto pointers = [](const json& body) {
    try {
      parse_study(body, 10);
    } catch (const InvalidJob& e) {
      std::set<std::string> out;
      for (const JobIssue& i : e.issues) out.insert(i.pointer);
      return out;
    }
    return std::set<std::string>{};
  };
  EXPECT_TRUE(pointers({{"axes", json::array()}}).count("/base"));
  EXPECT_TRUE(pointers({{"base", tiny_job()}}).count("/axes"));
  EXPECT_TRUE(pointers({{"base", tiny_job()}, {"axes", {{{"pointer", "a"}, {"values", {1}}}}}})
                  .count("/axes/0/pointer"));
  EXPECT_TRUE(pointers({{"base", tiny_job()}, {"axes", {{{"pointer", "/a"}, {"values", 1}}}}})
                  .count("/axes/0/values"));
  EXPECT_TRUE(pointers({{"base", tiny_job()},
                        {"axes",
                         {{{"pointer", "/a"}, {"values", {1, 2, 3, 4}}},
                          {{"pointer", "/b"}, {"values", {1, 2, 3}}}}}})
                  .count("/axes"));  // 12 > 10 jobs
  EXPECT_TRUE(
      pointers(
          {{"base", tiny_job()}, {"axes", {{{"pointer", "/a"}, {"values", {1}}}}}, {"extra", 1}})
          .count("/extra"));
  // N9: the job's name is the study's to set: an axis there is refused, not dropped.
  for (const char* name : {"/name", "/name/x", "/name/0"}) {
    try {
      parse_study({{"base", tiny_job()},
                   {"axes",
                    {{{"pointer", "/time/end_s"}, {"values", {1e-3}}},
                     {{"pointer", name}, {"values", {"a", "b"}}}}}},
                  10);
      ADD_FAILURE() << name << " was taken as an axis";
    } catch (const InvalidJob& e) {
      ASSERT_EQ(e.issues.size(), 1u) << name;
      EXPECT_EQ(e.issues[0].pointer, "/axes/1/pointer") << name;
      EXPECT_NE(e.issues[0].message.find("name"), std::string::npos) << e.issues[0].message;
    }
  }
  // A pointer through a number cannot be set.
  const StudySpec spec = parse_study(
      {{"base", tiny_job()}, {"axes", {{{"pointer", "/time/end_s/x"}, {"values", {1}}}}}}, 10);
  EXPECT_THROW(expand_study(spec), InvalidJob);
}

TEST(ServerStudy, TableAndCsv) {
  StudyRow a, b;
  a.emplace_back("job", 1);
  flatten_scalars({{"peak", 2.5}, {"pos", {1, 2}}, {"e", {{"drift", 0.1}}}, {"note", "a, \"b\""}},
                  "", a);
  b.emplace_back("job", 2);
  flatten_scalars({{"peak", 3.5}, {"extra", true}}, "", b);
  const StudyTable t = study_table({a, b});
  EXPECT_EQ(t.columns, (std::vector<std::string>{"job", "e.drift", "note", "peak", "pos[0]",
                                                 "pos[1]", "extra"}));
  EXPECT_EQ(to_csv(t),
            "job,e.drift,note,peak,pos[0],pos[1],extra\n"
            "1,0.1,\"a, \"\"b\"\"\",2.5,1,2,\n"
            "2,,,3.5,,,true\n");
}

TEST(ServerHttp, RangeHeaders) {
  ByteRange r;
  EXPECT_EQ(parse_range("bytes=0-9", 100, r), RangeParse::ok);
  EXPECT_EQ(r.first, 0u);
  EXPECT_EQ(r.last, 9u);
  EXPECT_EQ(parse_range("bytes=90-", 100, r), RangeParse::ok);
  EXPECT_EQ(r.length(), 10u);
  EXPECT_EQ(parse_range("bytes=-5", 100, r), RangeParse::ok);
  EXPECT_EQ(r.first, 95u);
  EXPECT_EQ(parse_range("bytes=-500", 100, r), RangeParse::ok);
  EXPECT_EQ(r.first, 0u);
  EXPECT_EQ(parse_range("bytes=50-5000", 100, r), RangeParse::ok);
  EXPECT_EQ(r.last, 99u);
  EXPECT_EQ(parse_range("bytes=100-", 100, r), RangeParse::unsatisfiable);
  EXPECT_EQ(parse_range("bytes=-0", 100, r), RangeParse::unsatisfiable);
  for (const char* none :
       {"bytes=0-1,5-6", "items=0-1", "bytes=a-b", "bytes=9-1", "bytes=-", "bytes=1", "",
        // N6: malformed first or last positions are no range at all (RFC 9110, 14.1.2).
        "bytes=1e2-200", "bytes=-1e2", "bytes= 1-2", "bytes=1 -2", "bytes=+1-2", "bytes=1-+2",
        "bytes=1-2 ", "bytes=--5", "bytes=0x1-2"}) {
    EXPECT_EQ(parse_range(none, 100, r), RangeParse::none) << none;
  }
  EXPECT_EQ(parse_range("BYTES=1-2", 100, r), RangeParse::ok);  // the unit is case-insensitive
  // Positions past 2^64 are still positions: the end of the file, or past it.
  EXPECT_EQ(parse_range("bytes=5-99999999999999999999999", 100, r), RangeParse::ok);
  EXPECT_EQ(r.last, 99u);
  EXPECT_EQ(parse_range("bytes=99999999999999999999999-", 100, r), RangeParse::unsatisfiable);
  EXPECT_EQ(parse_range("bytes=-99999999999999999999999", 100, r), RangeParse::ok);
  EXPECT_EQ(r.first, 0u);
}

// N12: failed logins count per address within a minute; the wait is until
// the oldest of them is a minute old; a success forgets them.
TEST(ServerSessions, FailedLoginsWaitUntilTheOldestIsAMinuteOld) {
  using std::chrono::seconds;
  LoginThrottle t(5, seconds(60));
  const auto t0 = LoginThrottle::Clock::now();
  for (int i = 0; i < 4; ++i) t.failed("a", t0 + seconds(i));
  EXPECT_EQ(t.wait("a", t0 + seconds(4)).count(), 0);
  t.failed("a", t0 + seconds(4));
  EXPECT_EQ(t.wait("a", t0 + seconds(10)).count(), 50);  // the first failure leaves at 60 s
  EXPECT_EQ(t.wait("b", t0 + seconds(10)).count(), 0);   // another address
  EXPECT_EQ(t.wait("a", t0 + seconds(60)).count(), 0);   // four left in the window
  t.succeeded("a");
  t.failed("a", t0 + seconds(61));
  EXPECT_EQ(t.wait("a", t0 + seconds(61)).count(), 0);

  TempDir dir;
  auto store = open_sqlite_job_store(dir.path() / "jobs.db");
  Sessions s(*store, "the token", seconds(3600), 2);
  const std::string a = s.open(), b = s.open();
  EXPECT_EQ(a.size(), 32u);  // 128 bits as hex
  EXPECT_TRUE(s.valid(a) && s.valid(b));
  EXPECT_FALSE(s.valid("not-a-session"));
  const std::string c = s.open();  // beyond the cap the oldest goes
  EXPECT_FALSE(s.valid(a));
  EXPECT_TRUE(s.valid(b) && s.valid(c));
  EXPECT_TRUE(s.close(b));
  EXPECT_FALSE(s.valid(b));
  EXPECT_FALSE(s.close(b));
}

// Issue 49: sessions are in the job store, so another process on it (an
// API node) knows them and a revocation holds there; the store keeps only
// hashes; another token's sessions are not this one's.
TEST(ServerSessions, SessionsAreSharedThroughTheStore) {
  using std::chrono::seconds;
  TempDir dir;
  auto one_store = open_sqlite_job_store(dir.path() / "jobs.db");
  auto other_store = open_sqlite_job_store(dir.path() / "jobs.db");  // another connection
  Sessions one(*one_store, "t", seconds(3600), 10);
  Sessions other(*other_store, "t", seconds(3600), 10);
  const std::string id = one.open();
  EXPECT_TRUE(other.valid(id));
  EXPECT_EQ(other.size(), 1u);
  EXPECT_TRUE(other.close(id));  // revoked on the other node
  EXPECT_FALSE(other.valid(id));
  // The first node confirmed it before; past kSessionRecheck it asks the store again.
  std::this_thread::sleep_for(kSessionRecheck + std::chrono::milliseconds(100));
  EXPECT_FALSE(one.valid(id));
  // Not a usable secret in the file: the id is nowhere in it.
  const std::string kept = one.open();
  const std::string bytes = slurp(dir.path() / "jobs.db") + slurp(dir.path() / "jobs.db-wal");
  EXPECT_EQ(bytes.find(kept), std::string::npos);
  Sessions rotated(*other_store, "another token", seconds(3600), 10);
  EXPECT_FALSE(rotated.valid(kept));
  EXPECT_TRUE(other.valid(kept));
  // Ended ones are not open.
  Sessions brief(*one_store, "t", seconds(0), 10);
  EXPECT_FALSE(brief.valid(brief.open()));
}

TEST(ServerSessions, Sha256OfTheStandardVectors) {
  // FIPS 180-2, appendix B, and the empty message.
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // Padding into a second block (sha256sum of 56 and 64 'x').
  EXPECT_EQ(sha256_hex(std::string(56, 'x')),
            "04c26261370ee7541549d16dee320c723e3fd14671e66a099afe0a377c16888e");
  EXPECT_EQ(sha256_hex(std::string(64, 'x')),
            "7ce100971f64e7001e8fe5a51973ecdfe1ced42befe7ee8d5fd6219506b5393c");
}

// Issue 49: X-Forwarded-For is heeded only from a --trusted-proxy, read
// from the right, and what the client wrote left of the proxy's own entry
// changes nothing.
TEST(ServerClient, ForwardedForOnlyFromTrustedProxies) {
  const std::vector<std::string> none, proxy = {"10.0.0.1"}, two = {"10.0.0.1", "10.0.0.2"};
  EXPECT_EQ(forwarded_client("10.0.0.1", "203.0.113.5", none), "10.0.0.1");
  EXPECT_EQ(forwarded_client("192.0.2.9", "203.0.113.5", proxy), "192.0.2.9");
  EXPECT_EQ(forwarded_client("10.0.0.1", "203.0.113.5", proxy), "203.0.113.5");
  EXPECT_EQ(forwarded_client("10.0.0.1", "", proxy), "10.0.0.1");
  // A client's own forged entry stays left of the one the proxy appended.
  EXPECT_EQ(forwarded_client("10.0.0.1", "1.2.3.4, 203.0.113.5", proxy), "203.0.113.5");
  // Through two trusted proxies.
  EXPECT_EQ(forwarded_client("10.0.0.1", "203.0.113.5, 10.0.0.2", two), "203.0.113.5");
  // Garbage stops the walk at the hop before it.
  EXPECT_EQ(forwarded_client("10.0.0.1", "nonsense", proxy), "10.0.0.1");
  EXPECT_EQ(forwarded_client("10.0.0.1", "203.0.113.5, unknown", proxy), "10.0.0.1");
  EXPECT_EQ(forwarded_client("::ffff:10.0.0.1", " 2001:db8::1 ", proxy), "2001:db8::1");
  EXPECT_TRUE(is_ip_address("::1"));
  EXPECT_FALSE(is_ip_address("proxy.example"));
}

// Issue 49: the queue quota is counted in the transaction that inserts, so
// that submissions at the same time (threads on their own connections, as
// API nodes would be) never overfill the queue, as a whole or one
// client's share.
TEST(ServerJobStore, QueueQuotaHoldsUnderConcurrentSubmissions) {
  TempDir dir;
  auto store = open_sqlite_job_store(dir.path() / "jobs.db");
  constexpr int kThreads = 8, kEach = 10;
  auto race = [&](const QueueQuota& quota, const std::string& client) {
    std::atomic<int> created{0}, refused{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t) {
      threads.emplace_back([&] {
        auto own = open_sqlite_job_store(dir.path() / "jobs.db");
        for (int i = 0; i < kEach; ++i) {
          NewJob j = new_job();
          j.client = client;
          const SubmitResult r = own->submit(j, std::nullopt, quota);
          if (r.kind == SubmitResult::Kind::created) ++created;
          if (r.kind == SubmitResult::Kind::queue_full ||
              r.kind == SubmitResult::Kind::client_queue_full) {
            ++refused;
          }
        }
      });
    }
    for (auto& t : threads) t.join();
    return std::make_pair(created.load(), refused.load());
  };
  QueueQuota per_client;
  per_client.max_queued_per_client = 7;
  per_client.client = "a";
  EXPECT_EQ(race(per_client, "a"), std::make_pair(7, kThreads * kEach - 7));
  EXPECT_EQ(store->queued_from("a"), 7);
  QueueQuota whole;
  whole.max_queued = 20;
  EXPECT_EQ(race(whole, "b"), std::make_pair(13, kThreads * kEach - 13));
  EXPECT_EQ(store->count_by_status().at("accepted"), 20);
  // A study beyond the quota stores nothing, not even the study.
  NewStudy study;
  study.id = new_id();
  study.name = "s";
  study.spec_json = "{}";
  const SubmitResult r = store->submit_study(study, {new_job(), new_job()}, std::nullopt, whole);
  EXPECT_EQ(r.kind, SubmitResult::Kind::queue_full);
  EXPECT_EQ(r.queued, 20);
  EXPECT_FALSE(store->study(study.id));
}

TEST(ServerHttp, TargetsAreDecodedPerSegment) {
  Request r;
  ASSERT_TRUE(parse_target("/jobs/a%2Fb/files/x%20y?status=a,b&limit=2&q=a+b&flag", r));
  EXPECT_EQ(r.path, "/jobs/a%2Fb/files/x%20y");
  EXPECT_EQ(r.segments, (std::vector<std::string>{"jobs", "a/b", "files", "x y"}));
  EXPECT_EQ(r.query_value("status"), "a,b");
  EXPECT_EQ(r.query_value("q"), "a b");
  EXPECT_EQ(r.query_value("flag"), "");
  EXPECT_FALSE(r.query_value("none"));
  EXPECT_TRUE(parse_target("/", r));
  EXPECT_TRUE(r.segments.empty());
  EXPECT_FALSE(parse_target("/a%zz", r));
  EXPECT_FALSE(parse_target("/a%2", r));
  EXPECT_FALSE(parse_target("http://x/a", r));
  EXPECT_FALSE(parse_target("", r));
  EXPECT_FALSE(is_plain_file_name("../x"));
  EXPECT_FALSE(is_plain_file_name(".hidden"));
  EXPECT_FALSE(is_plain_file_name("a/b"));
  EXPECT_FALSE(is_plain_file_name(std::string("a\0b", 3)));
  EXPECT_TRUE(is_plain_file_name("results.h5"));
  EXPECT_TRUE(is_plain_file_name("image-von_mises-frame3.png"));
}

TEST(ServerHttp, TokenComparison) {
  EXPECT_TRUE(token_matches("abc", "abc"));
  EXPECT_FALSE(token_matches("abd", "abc"));
  EXPECT_FALSE(token_matches("ab", "abc"));
  EXPECT_FALSE(token_matches("abcd", "abc"));
  EXPECT_FALSE(token_matches("", "abc"));
}

TEST(ServerEventHub, FiltersResumesAndReportsGaps) {
  EventHub hub(4);
  std::atomic<int> woken{0};
  auto sub = hub.subscribe("a", [&] { ++woken; });
  const std::uint64_t start = hub.last_id();
  hub.publish("a", "progress", "1");
  hub.publish("b", "progress", "2");
  hub.publish("a", "status", "3", true);
  EXPECT_EQ(woken.load(), 2);  // only events of job a
  auto batch = hub.after(start, "a", 10);
  ASSERT_EQ(batch.events.size(), 2u);
  EXPECT_FALSE(batch.gap);
  EXPECT_TRUE(batch.events[1].terminal);
  EXPECT_EQ(batch.seen, hub.last_id());
  EXPECT_EQ(hub.after(start, "", 10).events.size(), 3u);
  EXPECT_EQ(hub.after(batch.events[0].id, "", 10).events.size(), 2u);
  for (int i = 0; i < 10; ++i) hub.publish("c", "progress", "x");
  EXPECT_TRUE(hub.after(start, "a", 10).gap);  // fell out of the ring of 4
  sub.reset();
  EXPECT_EQ(hub.subscribers(), 0u);
  hub.close();
  EXPECT_TRUE(hub.closed());
}

}  // namespace
}  // namespace gearsph::server::testing

namespace gearsph::server::testing {
namespace {

// N4: a string from a request (a job's name) with a newline and an escape
// code cannot forge a second log line or reach the terminal raw.
TEST(ServerLog, ControlCharactersAreEscaped) {
  TempDir dir;
  const fs::path file = dir.path() / "stderr";
  std::fflush(stderr);
  const int saved = ::dup(2);
  const int fd = ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  ASSERT_GE(fd, 0);
  ::dup2(fd, 2);
  const std::string name = "x\n2026-01-01T00:00:00.000Z ERROR forged\x1b[31m\r\\";
  log_line(LogLevel::info, "gearsph serve: job %s\n", name.c_str());
  std::fflush(stderr);
  ::dup2(saved, 2);
  ::close(saved);
  ::close(fd);
  const std::string text = slurp(file);
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 1) << text;
  EXPECT_EQ(text.find('\x1b'), std::string::npos);
  EXPECT_EQ(text.find('\r'), std::string::npos);
  EXPECT_NE(text.find("job x\\n2026-01-01T00:00:00.000Z ERROR forged\\x1b[31m\\r\\\\\n"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace gearsph::server::testing
