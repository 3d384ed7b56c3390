// The executor of a step's pass table (core/passes.hpp): the order of the
// passes, the barriers a table asks for, passes that are off, the stop
// flag, the passes on the calling thread between regions, and the clock
// that times each pass by name; blocks handed out as threads come free.
#include <gtest/gtest.h>

#include <omp.h>

#include <atomic>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/core/passes.hpp"

namespace gearsph {
namespace {

constexpr std::size_t kNeverStop = 0;

struct Count {
  long n = 0;
  Count& operator+=(const Count& o) {
    n += o.n;
    return *this;
  }
};

// Every thread writes its share of a vector; the pass after the barrier
// reads every share: it sees them all written, on any team.
TEST(Passes, ABarrierMakesEveryThreadsWritesVisible) {
  constexpr std::size_t kItems = 1000;
  for (int threads : {1, 2, 3}) {
    std::vector<int> written(kItems, 0);
    long seen = 0;
    auto write = [&](int me, int team, Count&) {
      const Share part = share(kItems, me, team);
      for (std::size_t i = part.lo; i < part.hi; ++i) written[i] = 1;
    };
    auto read = [&](int, int, Count&) {
      for (int w : written) seen += w;
    };
    const Pass<Count> passes[] = {
        {"write", Runs::OnEveryThread, nullptr, write, Sync::Barrier, true},
        {"read", Runs::OnOneThread, nullptr, read, Sync::Barrier, true},
    };
    run_passes<Count>(passes, threads, kNeverStop);
    EXPECT_EQ(seen, static_cast<long>(kItems)) << threads << " threads";
  }
}

// A pass that is off does not run; the sums of the others add up in
// thread order, once per thread and pass.
TEST(Passes, APassThatIsOffDoesNotRun) {
  for (int threads : {1, 2}) {
    auto one = [](int, int, Count& c) { ++c.n; };
    auto never = [](int, int, Count& c) { c.n += 1000; };
    const Pass<Count> passes[] = {
        {"a", Runs::OnEveryThread, nullptr, one, Sync::Barrier, true},
        {"off", Runs::OnEveryThread, nullptr, never, Sync::Barrier, false},
        {"b", Runs::OnEveryThread, nullptr, one, Sync::Continues, true},
    };
    EXPECT_EQ(run_passes<Count>(passes, threads, kNeverStop).n, 2L * threads);
  }
}

// A stop raised before the first barrier skips every pass after that
// barrier on every thread, and the passes that continue without a barrier
// before it still run (the step's clock counts a stopped step).
TEST(Passes, AStopBeforeTheFirstBarrierSkipsTheRest) {
  for (int threads : {1, 2, 3}) {
    std::size_t stop = 0;
    std::atomic<int> after{0};
    bool clocked = false;
    auto raise = [&](int me, int, Count&) {
      if (me == 0) stop = 1;
    };
    auto clock = [&](int, int, Count&) { clocked = true; };
    auto later = [&](int, int, Count&) { ++after; };
    const Pass<Count> passes[] = {
        {"raise", Runs::OnEveryThread, nullptr, raise, Sync::Barrier, true},
        {"clock", Runs::OnOneThread, nullptr, clock, Sync::Continues, true},
        {"later", Runs::OnEveryThread, nullptr, later, Sync::Barrier, true},
        {"on calling thread", Runs::OnCallingThread, nullptr, later, Sync::Barrier, true},
    };
    run_passes<Count>(passes, threads, stop);
    EXPECT_TRUE(clocked) << threads << " threads";
    EXPECT_EQ(after.load(), 0) << threads << " threads";
  }
}

// A pass on the calling thread runs between two parallel regions, outside
// both, so that its own work may run passes on every thread.
TEST(Passes, APassOnTheCallingThreadRunsBetweenRegions) {
  int in_parallel = -1, inner_team = 0;
  auto before = [](int, int, Count& c) { ++c.n; };
  auto between = [&](int, int, Count&) {
    in_parallel = omp_in_parallel();
    auto inner = [&](int, int team, Count&) {
#pragma omp atomic write
      inner_team = team;
    };
    const Pass<Count> nested[] = {
        {"inner", Runs::OnEveryThread, nullptr, inner, Sync::Barrier, true}};
    run_passes<Count>(nested, 2, kNeverStop);
  };
  const Pass<Count> passes[] = {
      {"before", Runs::OnEveryThread, nullptr, before, Sync::Barrier, true},
      {"between", Runs::OnCallingThread, nullptr, between, Sync::Barrier, true},
      {"after", Runs::OnEveryThread, nullptr, before, Sync::Barrier, true},
  };
  EXPECT_EQ(run_passes<Count>(passes, 2, kNeverStop).n, 4);
  EXPECT_EQ(in_parallel, 0);
  EXPECT_EQ(inner_team, 2);
}

// Chunks are run each once, on thread c mod team, with their count.
TEST(Passes, EveryChunkRunsOnce) {
  RowChunks chunks;
  const std::vector<std::uint32_t> rows = {0, 1, 2, 3, 4, 5, 6, 7, 8};
  const std::vector<std::uint32_t> j = {1, 2, 3, 4, 5, 6, 7, 8};
  chunks.plan(rows, j, 4, 1);
  ASSERT_EQ(chunks.chunks(), 4);
  for (int threads : {1, 2, 3}) {
    std::vector<int> ran(4, 0);
    auto work = [&](int c, int of, Count&) {
      EXPECT_EQ(of, 4);
      ++ran[c];
    };
    const Pass<Count> passes[] = {{"chunks", Runs::OverChunks, &chunks, work, Sync::Barrier, true}};
    run_passes<Count>(passes, threads, kNeverStop);
    EXPECT_EQ(ran, std::vector<int>(4, 1)) << threads << " threads";
  }
}

// With a clock, every pass that ran is timed under its name, once per
// call, and what no pass saw (the region's start) under its own name.
TEST(Passes, TheClockTimesEachPassByName) {
  PassTimes times;
  auto busy = [](int, int, Count& c) {
    for (int k = 0; k < 1000; ++k) c.n += k % 3;
  };
  const Pass<Count> passes[] = {
      {"first", Runs::OnEveryThread, nullptr, busy, Sync::Barrier, true},
      {"second", Runs::OnOneThread, nullptr, busy, Sync::Barrier, true},
      {"off", Runs::OnOneThread, nullptr, busy, Sync::Barrier, false},
  };
  for (int call = 0; call < 3; ++call) run_passes<Count>(passes, 2, kNeverStop, &times);
  std::vector<std::string> names;
  for (const PassTime& t : times.entries()) {
    names.push_back(t.name);
    EXPECT_EQ(t.runs, 3) << t.name;
    EXPECT_GE(t.seconds, 0.0) << t.name;
  }
  EXPECT_EQ(names, (std::vector<std::string>{"first", "second", "threads start and join"}));
  EXPECT_GT(times.total_seconds(), 0.0);
}

// Blocks handed out as threads come free (over_blocks): every item runs
// exactly once on any team, a last block shorter than the rest included,
// and an item's exception reaches the caller.
TEST(Passes, OverBlocksRunsEveryItemOnceAndPassesOnAnError) {
  for (int threads : {1, 2, 3}) {
    for (std::size_t block : {1, 7, 64}) {
      std::vector<std::atomic<int>> ran(1000);
      over_blocks("items", ran.size(), block, threads, [&](std::size_t i) { ++ran[i]; });
      int wrong = 0;
      for (const auto& r : ran) wrong += r.load() != 1;
      EXPECT_EQ(wrong, 0) << threads << " threads, blocks of " << block;
    }
    EXPECT_THROW(over_blocks("items", 100, 8, threads,
                             [](std::size_t i) {
                               if (i == 42) throw std::runtime_error("item 42");
                             }),
                 std::runtime_error);
  }
}

}  // namespace
}  // namespace gearsph
