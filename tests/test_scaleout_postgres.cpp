// Many machines on one PostgreSQL job store, on loopback: a real PostgreSQL
// server (tests/scaleout/postgres.sh), one API process that runs no jobs
// (`gearsph serve --store ... --no-local-workers`) and `gearsph worker`
// processes sharing a results directory. What is checked: jobs spread over
// the workers, no job runs twice unless its worker died, a worker killed
// with SIGKILL mid-job has that job finished by another, the API serves
// results and events of jobs it did not run, and a database restart loses
// nothing.
#include <atomic>
#include <fstream>
#include <random>
#include <thread>

#include "server/documents.hpp"
#include "server/job_store.hpp"
#include "server/open_job_store.hpp"
#include "tests/scaleout/support.hpp"

namespace gearsph::server::testing {
namespace {

class ScaleOutPostgres : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string out;
    if (shell("ls /usr/lib/postgresql/*/bin/initdb", &out) != 0) {
      GTEST_SKIP() << "PostgreSQL server binaries are missing (/usr/lib/postgresql/*/bin/initdb); "
                      "apt-get install postgresql";
    }
    pg_ = std::make_unique<Engine>(script("postgres.sh"));
    ASSERT_TRUE(pg_->started()) << pg_->output();
    uri_ = pg_->last_line();
    ASSERT_EQ(uri_.rfind("postgresql://", 0), 0u) << pg_->output();
  }

  // Leases of 2 s: a killed worker's job is taken over quickly, yet a busy
  // machine does not let a live worker's lease run out (renewed every 0.67 s).
  std::unique_ptr<WorkerProcess> worker(int number, std::vector<std::string> extra = {},
                                        double lease_s = 2) {
    std::vector<std::string> args = {"--store",
                                     uri_,
                                     "--results",
                                     results_.path().string(),
                                     "--threads-per-job",
                                     "1",
                                     "--lease",
                                     std::to_string(lease_s),
                                     "--poll",
                                     "0.2"};
    args.insert(args.end(), extra.begin(), extra.end());
    return std::make_unique<WorkerProcess>(args, logs_.path(), number);
  }
  std::vector<std::string> api_args(std::vector<std::string> extra = {}, double lease_s = 2) {
    std::vector<std::string> args = {"--store",
                                     uri_,
                                     "--no-local-workers",
                                     "--results",
                                     results_.path().string(),
                                     "--lease",
                                     std::to_string(lease_s)};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
  }

  std::unique_ptr<Engine> pg_;
  std::string uri_;
  TempDir results_;  // the results directory all "nodes" share
  TempDir logs_;
};

TEST_F(ScaleOutPostgres, StoreClaimsEachJobOnceAcrossConnections) {
  auto store = open_job_store(uri_);
  constexpr int kJobs = 60;
  for (int i = 0; i < kJobs; ++i) {
    NewJob j;
    j.id = new_id();
    j.name = std::to_string(i);
    j.job_json = "{}";
    store->submit(j, std::nullopt);
  }
  std::mutex mutex;
  std::vector<std::string> claimed;
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      auto own = open_job_store(uri_);  // another connection, as another machine
      Holder holder{"w", 60};
      holder.worker.push_back(static_cast<char>('0' + t));
      while (auto job = own->claim(holder)) {
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
  // Opening again finds the schema current and migrates nothing.
  open_job_store(uri_);
  PgDatabase db(uri_);
  EXPECT_EQ(db.value("SELECT version FROM schema_version"), "6");
  EXPECT_EQ(db.value("SELECT COUNT(*) FROM schema_version"), "1");
}

// Leases on either store: renewed, expired and reclaimed, fenced off by the
// claim's token from the holder that lost them (even one of the same name:
// two containers' workers are both host:1), still the holder's while
// nobody claimed the job again, and reported lost when it was dismissed.
void expect_leases_work(JobStore& store) {
  NewJob j;
  j.id = new_id();
  j.name = "leased";
  j.job_json = "{}";
  store.submit(j, std::nullopt);
  // a's lease is short enough to expire during the test, long enough that a
  // busy machine does not let it expire between two statements. b has the
  // same name as a.
  const Holder a{"vm:1", 1.5}, b{"vm:1", 60};
  const auto expire = [] { std::this_thread::sleep_for(std::chrono::milliseconds(2000)); };
  const ProgressUpdate done{j.id, 1, 1, 1, 0, 100};
  const auto first = store.claim(a);
  ASSERT_TRUE(first);
  ASSERT_EQ(first->claim.size(), 32u);
  EXPECT_TRUE(store.renew(a, {{j.id, first->claim}}).empty());
  EXPECT_EQ(store.renew(b, {{j.id, "another claim"}}), std::vector<std::string>{j.id});
  EXPECT_TRUE(store.reclaim_expired(3).requeued.empty());  // just renewed
  expire();
  EXPECT_EQ(store.reclaim_expired(3).requeued, std::vector<std::string>{j.id});
  EXPECT_NE(store.job(j.id)->message.find("its worker vm:1 stopped renewing its lease"),
            std::string::npos)
      << store.job(j.id)->message;
  const auto again = store.claim(b);
  ASSERT_TRUE(again);
  EXPECT_EQ(again->attempts, 2);
  EXPECT_EQ(again->worker, "vm:1");
  EXPECT_NE(again->claim, first->claim);
  // The first holder is fenced off by its token, though its name is b's:
  // it can neither renew, finish nor re-queue.
  EXPECT_EQ(store.renew(a, {{j.id, first->claim}}), std::vector<std::string>{j.id});
  EXPECT_FALSE(store.finish(j.id, JobStatus::successful, "done", done, first->claim));
  EXPECT_FALSE(store.requeue(j.id, "stopping", first->claim));
  EXPECT_EQ(store.job(j.id)->status, JobStatus::running);
  EXPECT_TRUE(store.finish(j.id, JobStatus::successful, "done", done, again->claim));
  EXPECT_EQ(store.job(j.id)->status, JobStatus::successful);
  EXPECT_FALSE(store.finish(j.id, JobStatus::failed, "late", done, again->claim));

  // A lease that ran out while nobody claimed the job since (its holder was
  // cut off from the store): the holder's heartbeat takes it back, and its
  // finish is recorded.
  NewJob cut = j;
  cut.id = new_id();
  store.submit(cut, std::nullopt);
  const auto held = store.claim(a);
  ASSERT_TRUE(held);
  expire();
  EXPECT_EQ(store.reclaim_expired(3).requeued, std::vector<std::string>{cut.id});
  EXPECT_TRUE(store.renew(a, {{cut.id, held->claim}}).empty());
  EXPECT_EQ(store.job(cut.id)->status, JobStatus::running);
  expire();
  EXPECT_EQ(store.reclaim_expired(3).requeued, std::vector<std::string>{cut.id});
  EXPECT_TRUE(
      store.finish(cut.id, JobStatus::successful, "done", {cut.id, 1, 1, 1, 0, 100}, held->claim));
  EXPECT_EQ(store.job(cut.id)->status, JobStatus::successful);
  EXPECT_FALSE(store.claim(b));  // nothing left queued

  // Dismissed while running: the holder learns it at its next heartbeat.
  NewJob k = j;
  k.id = new_id();
  store.submit(k, std::nullopt);
  const auto mine = store.claim(b);
  ASSERT_TRUE(mine);
  store.dismiss(k.id);
  EXPECT_EQ(store.renew(b, {{k.id, mine->claim}}), std::vector<std::string>{k.id});
  // An expired job started max_attempts times fails instead, and its
  // holder can no longer record an outcome.
  NewJob m = j;
  m.id = new_id();
  store.submit(m, std::nullopt);
  const auto last = store.claim(a);
  ASSERT_TRUE(last);
  expire();
  EXPECT_EQ(store.reclaim_expired(1).failed, std::vector<std::string>{m.id});
  EXPECT_EQ(store.job(m.id)->status, JobStatus::failed);
  EXPECT_FALSE(
      store.finish(m.id, JobStatus::successful, "late", {m.id, 1, 1, 1, 0, 100}, last->claim));
  // The single server's own claims carry no lease: never reclaimed, and
  // recovered at its start-up instead.
  NewJob n = j;
  n.id = new_id();
  store.submit(n, std::nullopt);
  ASSERT_TRUE(store.claim());
  EXPECT_TRUE(store.reclaim_expired(3).requeued.empty());
  EXPECT_EQ(store.recover(3).requeued, std::vector<std::string>{n.id});
}

TEST_F(ScaleOutPostgres, LeasesRenewExpireAndFence) {
  auto store = open_job_store(uri_);
  expect_leases_work(*store);
}

// The same on SQLite (`--store sqlite:PATH`: worker processes on one machine).
TEST(ScaleOutSqlite, LeasesRenewExpireAndFence) {
  TempDir dir;
  auto store = open_job_store("sqlite:" + (dir.path() / "jobs.db").string());
  expect_leases_work(*store);
}

TEST_F(ScaleOutPostgres, WorkersShareTheQueueAndFinishAKilledWorkersJob) {
  ServerProcess api(api_args());
  std::vector<std::unique_ptr<WorkerProcess>> workers;
  for (int i = 0; i < 3; ++i) workers.push_back(worker(i));
  auto c = api.client();

  // A long job first: some worker takes it; that worker is killed mid-run.
  // About 4 s of one core: well beyond the moment it is killed.
  const std::string long_job = submit(c, tiny_job(1.0));
  std::vector<std::string> ids;
  for (int i = 0; i < 12; ++i) ids.push_back(submit(c, tiny_job(0.02)));
  // Progress reaches the API through the store only.
  wait_for(c, long_job, [](const json& s) { return s.at("step").get<int>() > 0; });
  PgDatabase db(uri_);
  const std::string holder = db.value("SELECT worker FROM jobs WHERE id = '" + long_job + "'");
  int killed = -1;
  for (int i = 0; i < 3; ++i) {
    if (workers[i]->name() == holder) killed = i;
  }
  ASSERT_NE(killed, -1) << "no worker is named " << holder;
  EXPECT_EQ(workers[killed]->stop(SIGKILL), 128 + SIGKILL);

  ids.push_back(long_job);
  for (const std::string& id : ids) {
    const json s = wait_final(c, id);
    EXPECT_EQ(s.at("status"), "successful") << s.dump();
    // Served by the API from the shared results directory.
    EXPECT_EQ(c.get("/jobs/" + id + "/results").status, 200u) << id;
  }
  const json l = c.get("/jobs/" + long_job).json();
  EXPECT_EQ(l.at("attempts"), 2) << l.dump();
  EXPECT_NE(db.value("SELECT worker FROM jobs WHERE id = '" + long_job + "'"), holder);

  // From the workers' own logs: every job ran once, except the long one,
  // whose first run died with its worker; each worker ran some jobs.
  std::vector<std::string> started;
  for (int i = 0; i < 3; ++i) {
    const auto mine = workers[i]->started();
    EXPECT_FALSE(mine.empty()) << "worker " << i << " ran nothing:\n" << workers[i]->log();
    started.insert(started.end(), mine.begin(), mine.end());
  }
  const auto runs = count(started);
  for (const std::string& id : ids) {
    EXPECT_EQ(runs.count(id) ? runs.at(id) : 0, id == long_job ? 2 : 1) << id;
    EXPECT_EQ(db.value("SELECT attempts FROM jobs WHERE id = '" + id + "'"),
              id == long_job ? "2" : "1");
  }
  EXPECT_EQ(count(workers[killed]->started()).count(long_job), 1u);
  EXPECT_TRUE(count(workers[killed]->finished()).count(long_job) == 0);
  // Whoever noticed first (the API's watcher or an idle worker) put it back.
  std::string logs = api.log();
  for (const auto& w : workers) logs += w->log();
  EXPECT_NE(logs.find("job " + long_job + ": its worker stopped renewing its lease"),
            std::string::npos)
      << logs;
}

// Workers in PID namespaces of their own (containers with host
// networking) have the same host name and pid; their names still differ,
// and so do their claims.
TEST_F(ScaleOutPostgres, WorkersInTheirOwnPidNamespacesAreToldApart) {
  if (::geteuid() != 0 || shell("unshare --pid --fork --mount-proc --kill-child true") != 0) {
    GTEST_SKIP() << "unshare --pid needs root";
  }
  ServerProcess api(api_args());
  auto c = api.client();
  const std::vector<std::string> ns = {"unshare", "--pid", "--fork", "--mount-proc",
                                       "--kill-child"};
  const std::vector<std::string> args = {
      "--store", uri_,     "--results", results_.path().string(), "--lease",
      "2",       "--poll", "0.2",       "--threads-per-job",      "1"};
  WorkerProcess a(args, logs_.path(), 0, ns), b(args, logs_.path(), 1, ns);
  const std::string host = a.name().substr(0, a.name().find(':'));
  EXPECT_EQ(a.name().rfind(host + ":1:", 0), 0u) << a.name();
  EXPECT_EQ(b.name().rfind(host + ":1:", 0), 0u) << b.name();
  EXPECT_NE(a.name(), b.name());
  std::vector<std::string> ids;
  for (int i = 0; i < 6; ++i) ids.push_back(submit(c, tiny_job(0.2)));
  for (const std::string& id : ids) EXPECT_EQ(wait_final(c, id).at("status"), "successful");
  PgDatabase db(uri_);
  EXPECT_EQ(db.value("SELECT COUNT(DISTINCT claim) FROM jobs"), "6");
  EXPECT_EQ(db.value("SELECT MAX(attempts) FROM jobs"), "1");
}

// Every file of a directory: name -> size and modification time.
std::map<std::string, std::pair<std::uintmax_t, fs::file_time_type>> snapshot(const fs::path& dir) {
  std::map<std::string, std::pair<std::uintmax_t, fs::file_time_type>> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.is_regular_file()) {
      files[fs::relative(e.path(), dir).string()] = {e.file_size(), e.last_write_time()};
    }
  }
  return files;
}

// A worker frozen (SIGSTOP) past its lease while another worker runs its job
// again and records it; thawed, the frozen run must not touch the job: the
// results stay those of the run that was recorded, file for file.
TEST_F(ScaleOutPostgres, AFrozenWorkerNeverTouchesAJobItLost) {
  ServerProcess api(api_args());
  auto w0 = worker(0);
  auto w1 = worker(1);
  auto c = api.client();
  const double end_s = 1.0;  // about 4 s of one core
  const std::string id = submit(c, tiny_job(end_s));
  wait_for(c, id, [](const json& s) { return s.value("progress", 0) >= 20; });
  PgDatabase db(uri_);
  const std::string holder = db.value("SELECT worker FROM jobs WHERE id = '" + id + "'");
  WorkerProcess* frozen = w0->name() == holder ? w0.get() : w1.get();
  ASSERT_EQ(frozen->name(), holder);
  ASSERT_EQ(::kill(frozen->pid(), SIGSTOP), 0);
  const json done = wait_final(c, id);
  EXPECT_EQ(done.at("status"), "successful") << done.dump();
  EXPECT_EQ(done.at("attempts"), 2) << done.dump();
  // The worker renames its attempt's directory just after it records the
  // outcome; a client that asks in between gets the files all the same,
  // because the API publishes a recorded attempt when first asked
  // (attempt_dirs.cpp). Asked first, as a user would.
  ASSERT_EQ(c.get("/jobs/" + id + "/files/summary.json").status, 200u);
  const fs::path published = results_.path() / id;
  const auto before = snapshot(published);
  ASSERT_TRUE(before.count("summary.json") && before.count("results.h5") &&
              before.count("results.xmf") && before.count("history.csv"));

  ASSERT_EQ(::kill(frozen->pid(), SIGCONT), 0);
  // Thawed, its heartbeat learns that the claim is gone; its run stops and
  // its files are discarded.
  const auto deadline = Clock::now() + std::chrono::seconds(60);
  while (frozen->log().find("job " + id + " stopped") == std::string::npos &&
         frozen->log().find("job " + id + ": this run") == std::string::npos &&
         Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  ASSERT_NE(frozen->log().find("files were discarded"), std::string::npos) << frozen->log();
  EXPECT_EQ(snapshot(published), before);
  const json summary = json::parse(c.get("/jobs/" + id + "/files/summary.json").body);
  EXPECT_EQ(summary.at("status"), "completed");
  std::istringstream history(slurp(published / "history.csv"));
  std::string row, last_row;
  while (std::getline(history, row)) {
    if (!row.empty()) last_row = row;
  }
  // The last row at the end time, not where the frozen run stood.
  EXPECT_GE(std::stod(last_row), end_s) << last_row;
  EXPECT_LT(std::stod(last_row), end_s * 1.001) << last_row;
  const json status = c.get("/jobs/" + id).json();
  EXPECT_EQ(status.at("status"), "successful");
  EXPECT_EQ(status.at("attempts"), 2);
  // No attempt directory of the job is left behind.
  for (const auto& e : fs::directory_iterator(results_.path() / ".attempts")) {
    EXPECT_NE(e.path().filename().string().rfind(id, 0), 0u) << e.path();
  }
}

TEST_F(ScaleOutPostgres, RandomKillsLoseNoJobAndRunNoneTwice) {
  std::random_device device;
  const unsigned seed = std::getenv("GEARSPH_SCALEOUT_SEED")
                            ? std::stoul(std::getenv("GEARSPH_SCALEOUT_SEED"))
                            : device();
  std::mt19937 random(seed);
  SCOPED_TRACE("GEARSPH_SCALEOUT_SEED=" + std::to_string(seed));
  ServerProcess api(api_args({"--max-attempts", "20"}));
  std::vector<std::unique_ptr<WorkerProcess>> workers;
  for (int i = 0; i < 3; ++i) workers.push_back(worker(i, {"--max-attempts", "20"}));
  auto c = api.client();
  std::vector<std::string> ids;
  std::uniform_real_distribution<double> length(0.005, 0.12);
  for (int i = 0; i < 14; ++i) ids.push_back(submit(c, tiny_job(length(random))));

  // Three times: wait a random moment, SIGKILL a random live worker, start
  // a replacement.
  std::vector<int> killed;
  std::uniform_int_distribution<int> pause_ms(200, 1500);
  for (int round = 0; round < 3; ++round) {
    std::this_thread::sleep_for(std::chrono::milliseconds(pause_ms(random)));
    std::vector<int> alive;
    for (int i = 0; i < static_cast<int>(workers.size()); ++i) {
      if (workers[i]->alive()) alive.push_back(i);
    }
    const int victim =
        alive[std::uniform_int_distribution<std::size_t>(0, alive.size() - 1)(random)];
    workers[victim]->stop(SIGKILL);
    killed.push_back(victim);
    workers.push_back(worker(static_cast<int>(workers.size()), {"--max-attempts", "20"}));
  }
  for (const std::string& id : ids) {
    const json s = wait_final(c, id, std::chrono::seconds(150));
    EXPECT_EQ(s.at("status"), "successful") << s.dump();
  }
  // A run that a killed worker started and did not finish was interrupted;
  // every job ran exactly once more than it was interrupted, and the store
  // counted exactly those runs. The store names who finished each job: a
  // worker killed after recording the outcome, before logging it, finished
  // its run.
  PgDatabase db(uri_);
  std::map<std::string, std::string> finisher;
  for (const auto& row : db.query("SELECT id, worker FROM jobs")) finisher[row[0]] = row[1];
  std::map<std::string, int> runs, interrupted;
  for (std::size_t i = 0; i < workers.size(); ++i) {
    const auto started = count(workers[i]->started());
    for (const auto& [id, n] : started) runs[id] += n;
    if (std::find(killed.begin(), killed.end(), static_cast<int>(i)) != killed.end()) {
      const auto done = count(workers[i]->finished());
      for (const auto& [id, n] : started) {
        int unfinished = n - (done.count(id) ? done.at(id) : 0);
        if (unfinished > 0 && finisher[id] == workers[i]->name()) --unfinished;
        interrupted[id] += unfinished;
      }
    }
  }
  for (const std::string& id : ids) {
    EXPECT_EQ(runs[id], 1 + interrupted[id]) << id;
    EXPECT_EQ(db.value("SELECT attempts FROM jobs WHERE id = '" + id + "'"),
              std::to_string(runs[id]))
        << id;
    // Through the API first, which publishes a recorded attempt when
    // asked (the worker's own rename may still be under way).
    EXPECT_EQ(c.get("/jobs/" + id + "/files/summary.json").status, 200u) << id;
    EXPECT_TRUE(fs::exists(results_.path() / id / "summary.json")) << id;
  }
}

TEST_F(ScaleOutPostgres, EventsOfJobsRunElsewhereReachTheApi) {
  ServerProcess api(api_args());
  auto w = worker(0);
  auto c = api.client();
  const std::string id = submit(c, tiny_job(0.05));
  std::vector<std::string> statuses;
  auto ec = api.client(std::chrono::seconds(60));
  const ClientResponse head = ec.events("/jobs/" + id + "/events", [&](const SseEvent& e) {
    if (e.event == "status") statuses.push_back(json::parse(e.data).at("status"));
    return true;
  });
  EXPECT_EQ(head.status, 200u);
  ASSERT_FALSE(statuses.empty());
  EXPECT_EQ(statuses.back(), "successful");  // the stream ended after the final status
  EXPECT_EQ(c.get("/jobs/" + id).json().at("status"), "successful");
}

// Issue 49: on PostgreSQL too the quota is counted in the transaction that
// inserts (behind an advisory lock: READ COMMITTED alone would let two
// submissions count the same queue), so connections submitting at once,
// as API nodes do, never overfill it.
TEST_F(ScaleOutPostgres, QueueQuotaHoldsUnderConcurrentSubmissions) {
  constexpr int kThreads = 8, kEach = 10;
  QueueQuota quota;
  quota.max_queued = 20;
  quota.max_queued_per_client = 15;
  quota.client = "a";
  std::atomic<int> created{0}, whole{0}, share{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      auto own = open_job_store(uri_);
      for (int i = 0; i < kEach; ++i) {
        NewJob j;
        j.id = new_id();
        j.name = "quota";
        j.job_json = "{}";
        j.steps = 1;
        // Half the threads are client "a", half another client.
        j.client = t % 2 ? "a" : "b";
        QueueQuota q = quota;
        q.client = j.client;
        const SubmitResult r = own->submit(j, std::nullopt, q);
        if (r.kind == SubmitResult::Kind::created) ++created;
        if (r.kind == SubmitResult::Kind::queue_full) ++whole;
        if (r.kind == SubmitResult::Kind::client_queue_full) ++share;
      }
    });
  }
  for (auto& th : threads) th.join();
  auto store = open_job_store(uri_);
  EXPECT_EQ(created.load(), 20);
  EXPECT_EQ(whole.load() + share.load(), kThreads * kEach - 20);
  EXPECT_EQ(store->count_by_status().at("accepted"), 20);
  EXPECT_LE(store->queued_from("a"), 15);
  EXPECT_LE(store->queued_from("b"), 15);
}

// Issue 49: two API nodes on one PostgreSQL store share the dashboard's
// sessions: a login on one is known on the other, a DELETE /login on one
// holds on the other (within kSessionRecheck, 2 s).
TEST_F(ScaleOutPostgres, SessionsHoldOnEveryApiNode) {
  TempDir dir;
  const std::string token = "the-service-token-0123456789";
  std::ofstream(dir.path() / "token") << token << "\n";
  const std::vector<std::string> extra = {"--token-file", (dir.path() / "token").string()};
  ServerProcess one(api_args(extra)), two(api_args(extra));
  auto c1 = one.client();
  auto c2 = two.client();
  const ClientResponse login = c1.post_json("/login", json{{"token", token}}.dump());
  ASSERT_EQ(login.status, 204u) << login.body << one.log();
  const std::string set = login.header("Set-Cookie");
  const std::string cookie = set.substr(0, set.find(';'));
  EXPECT_EQ(c2.get("/jobs", {{"Cookie", cookie}}).status, 200u) << two.log();
  EXPECT_EQ(c1.request("DELETE", "/login", "", {{"Cookie", cookie}}).status, 204u);
  EXPECT_EQ(c1.get("/jobs", {{"Cookie", cookie}}).status, 401u);
  unsigned status = 0;
  const auto until = Clock::now() + std::chrono::seconds(10);
  while (Clock::now() < until && (status = c2.get("/jobs", {{"Cookie", cookie}}).status) != 401u) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_EQ(status, 401u);
}

TEST_F(ScaleOutPostgres, DatabaseRestartLosesNothing) {
  ServerProcess api(api_args({}, 10));
  auto w0 = worker(0, {}, 10);
  auto w1 = worker(1, {}, 10);
  auto c = api.client();
  std::vector<std::string> ids;
  for (int i = 0; i < 6; ++i) ids.push_back(submit(c, tiny_job(0.05)));
  wait_for(c, ids[0], [](const json& s) { return s.at("status") != "accepted"; });
  ASSERT_EQ(pg_->run("restart"), 0);
  // Submitting works again once the database is back.
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  ClientResponse r;
  while (Clock::now() < deadline) {
    r = c.post_json("/jobs", tiny_job(0.01).dump());
    if (r.status == 201) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  ASSERT_EQ(r.status, 201u) << r.body;
  ids.push_back(r.json().at("jobID"));
  for (const std::string& id : ids) {
    EXPECT_EQ(wait_final(c, id).at("status"), "successful") << id;
  }
}

// The database down: every endpoint that needs it answers 503 with
// Retry-After (not 500), /health names the store as the dependency that is
// down, and everything works again once it is back.
TEST_F(ScaleOutPostgres, TheStoreDownAnswers503WithRetryAfter) {
  ServerProcess api(api_args());
  auto c = api.client();
  const std::string id = submit(c, tiny_job(0.01));  // no worker: it stays queued
  {
    // A worker's heartbeat reaches /metrics through the store (it takes the
    // job, which is of no matter here).
    auto w = worker(0);
    const auto seen_by = Clock::now() + std::chrono::seconds(20);
    std::string m;
    do {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      m = c.get("/metrics").body;
    } while (m.find("gearsph_workers_seen 1") == std::string::npos && Clock::now() < seen_by);
    EXPECT_NE(m.find("gearsph_workers_seen 1"), std::string::npos) << m;
    EXPECT_NE(m.find("gearsph_worker_heartbeat_age_seconds{worker=\"" + w->name() + "\"}"),
              std::string::npos)
        << m;
    wait_final(c, id);
  }
  ASSERT_EQ(pg_->run("down"), 0);
  const std::vector<std::pair<std::string, std::string>> requests = {
      {"GET", "/jobs"},
      {"GET", "/jobs/" + id},
      {"GET", "/jobs/" + id + "/results"},
      {"GET", "/jobs/" + id + "/files"},
      {"GET", "/jobs/" + id + "/files/summary.json"},
      {"GET", "/jobs/" + id + "/events"},
      {"DELETE", "/jobs/" + id},
      {"POST", "/jobs"},
      {"POST", "/studies"},
      {"GET", "/studies/00000000-0000-0000-0000-000000000000"}};
  for (const auto& [method, target] : requests) {
    const ClientResponse r =
        method == "POST"
            ? c.post_json(
                  target,
                  target == "/jobs"
                      ? tiny_job(0.01).dump()
                      : json{{"base", tiny_job(0.01)},
                             {"axes", {{{"pointer", "/time/end_s"}, {"values", {0.01, 0.02}}}}}}
                            .dump())
            : c.request(method, target);
    EXPECT_EQ(r.status, 503u) << method << " " << target << ": " << r.body;
    EXPECT_EQ(r.header("retry-after"), "5") << method << " " << target;
  }
  // /health: 503 once its refresh (every second) found the store away.
  ClientResponse h;
  const auto deadline = Clock::now() + std::chrono::seconds(10);
  do {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    h = c.get("/health");
  } while (h.status != 503 && Clock::now() < deadline);
  ASSERT_EQ(h.status, 503u) << h.body;
  EXPECT_EQ(h.header("retry-after"), "5");
  // /metrics answers all the same: that is when it is needed.
  const ClientResponse m = c.get("/metrics");
  EXPECT_EQ(m.status, 200u);
  EXPECT_NE(m.body.find("gearsph_store_up 0"), std::string::npos) << m.body;
  const json health = h.json();
  EXPECT_EQ(health.at("status"), "degraded");
  EXPECT_EQ(health.at("dependencies").at("store").at("status"), "down") << h.body;
  EXPECT_EQ(health.at("dependencies").at("results").at("status"), "up") << h.body;

  ASSERT_EQ(pg_->run("up"), 0);
  const auto back = Clock::now() + std::chrono::seconds(30);
  do {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    h = c.get("/health");
  } while (h.status != 200 && Clock::now() < back);
  EXPECT_EQ(h.status, 200u) << h.body;
  EXPECT_EQ(h.json().at("dependencies").at("store").at("status"), "up");
  EXPECT_EQ(c.get("/jobs/" + id).json().at("status"), "successful");
}

// A run that finishes while the database is down (longer than its lease) is
// recorded once the database is back: not thrown away, not run again.
TEST_F(ScaleOutPostgres, ARunThatFinishesDuringAnOutageIsKept) {
  ServerProcess api(api_args());
  auto w = worker(0);
  auto c = api.client();
  const std::string id = submit(c, tiny_job(2.0));  // 2-5 s of one core
  wait_for(c, id, [](const json& s) { return s.value("progress", 0) >= 5; });
  ASSERT_EQ(pg_->run("down"), 0);
  // Down for five leases: the run finishes meanwhile.
  std::this_thread::sleep_for(std::chrono::seconds(10));
  ASSERT_EQ(pg_->run("up"), 0);
  const json done = wait_final(c, id);
  EXPECT_EQ(done.at("status"), "successful") << done.dump();
  EXPECT_EQ(done.at("attempts"), 1) << done.dump();
  EXPECT_EQ(count(w->started()).at(id), 1) << w->log();
  EXPECT_EQ(json::parse(c.get("/jobs/" + id + "/files/summary.json").body).at("status"),
            "completed");
  EXPECT_NE(w->log().find("recording its outcome failed"), std::string::npos) << w->log();
}

// A warm shutdown: SIGTERM lets the running job finish (the worker claims
// nothing more meanwhile) and the worker exits; a second SIGTERM during the
// grace stops the job at once and puts it back in the queue.
TEST_F(ScaleOutPostgres, AWarmShutdownLetsRunningJobsFinish) {
  ServerProcess api(api_args());
  auto c = api.client();
  auto w = worker(0, {"--job-grace", "60"});
  const std::string first = submit(c, tiny_job(1.0));  // 2-5 s of one core
  wait_for(c, first, [](const json& s) { return s.value("progress", 0) >= 10; });
  const std::string queued = submit(c, tiny_job(0.02));
  EXPECT_EQ(w->stop(SIGTERM), 0) << w->log();
  EXPECT_EQ(c.get("/jobs/" + first).json().at("status"), "successful");
  EXPECT_EQ(c.get("/jobs/" + first).json().at("attempts"), 1);
  EXPECT_EQ(c.get("/jobs/" + queued).json().at("status"), "accepted");
  EXPECT_EQ(count(w->started()).count(queued), 0u) << w->log();  // never claimed
  EXPECT_NE(w->log().find("letting 1 running job(s) finish"), std::string::npos) << w->log();

  // Cut short: the second signal stops the job, which is queued again.
  auto w2 = worker(1, {"--job-grace", "60"});
  const std::string second = submit(c, tiny_job(5.0));
  wait_for(c, second, [](const json& s) { return s.value("progress", 0) >= 1; });
  ::kill(w2->pid(), SIGTERM);
  const auto deadline = Clock::now() + std::chrono::seconds(30);
  while (w2->log().find("letting") == std::string::npos && Clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  EXPECT_EQ(w2->stop(SIGTERM), 0) << w2->log();
  const json back = c.get("/jobs/" + second).json();
  EXPECT_EQ(back.at("status"), "accepted") << back.dump();
  EXPECT_NE(back.at("message").get<std::string>().find("re-queued"), std::string::npos)
      << back.dump();
}

// What an idle API node costs: it waits for PostgreSQL's notifications
// instead of reading the table, and then reads only the rows that changed,
// without their job documents (5,000 queued jobs were read twice a second).
TEST_F(ScaleOutPostgres, TheWatcherHearsOfChangesAndReadsOnlyThem) {
  auto watcher = open_job_store(uri_);
  auto other = open_job_store(uri_);  // another node
  ASSERT_TRUE(watcher->notifies());
  watcher->wait_for_change(std::chrono::milliseconds(100));  // connects and listens
  while (watcher->wait_for_change(std::chrono::milliseconds(100))) {
  }
  std::vector<std::string> ids;
  for (int i = 0; i < 20; ++i) {
    NewJob j;
    j.id = new_id();
    j.name = "queued";
    j.job_json = std::string(4096, ' ') + "{}";
    other->submit(j, std::nullopt);
    ids.push_back(j.id);
  }
  EXPECT_TRUE(watcher->wait_for_change(std::chrono::milliseconds(2000)));
  while (watcher->wait_for_change(std::chrono::milliseconds(100))) {
  }
  EXPECT_FALSE(watcher->wait_for_change(std::chrono::milliseconds(300)));  // nothing changed
  std::this_thread::sleep_for(std::chrono::milliseconds(1200));
  const auto claimed = other->claim(Holder{"w", 60});
  ASSERT_TRUE(claimed);
  EXPECT_TRUE(watcher->wait_for_change(std::chrono::milliseconds(2000)));
  // Changed in the last second: the claimed job alone, without its document.
  const std::vector<JobRecord> changed = watcher->changed_within(1.0);
  ASSERT_EQ(changed.size(), 1u);
  EXPECT_EQ(changed[0].id, claimed->id);
  EXPECT_EQ(changed[0].status, JobStatus::running);
  EXPECT_TRUE(changed[0].job_json.empty());
}

}  // namespace
}  // namespace gearsph::server::testing
