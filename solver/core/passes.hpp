#pragma once
// A step as a list of passes, run by one executor that owns the threads,
// the barriers between passes, the errors and the clock (the shape of
// Box2D v3's solver stages). A pass is data: a name, where it runs, what it
// runs over, its work, whether a barrier stands before it, and whether it
// runs at all in this scene.
//
//   const Pass<Sums> step[] = {
//       {"kick and drift", Runs::OverChunks, &chunks, kick_drift, Sync::Barrier, true},
//       {"clock", Runs::OnOneThread, nullptr, clock, Sync::Continues, true},
//       ...};
//   const Sums totals = run_passes<Sums>(step, threads, stopped, &sim.pass_times);
//
// Every thread runs every pass in order. A barrier stands before each pass
// marked Sync::Barrier, so such a pass may read whatever the passes before
// it wrote on any thread; a pass marked Sync::Continues follows the one
// before it on the same threads without one, and may read only what those
// threads wrote (the same chunks) or what was final at the last barrier.
// A pass that runs OnCallingThread ends the parallel region: it runs on the
// caller's thread between two regions, so that its own work may use the
// threads (a neighbour list's build). Each thread adds into its own Sums;
// they are added in thread order at the end, so the totals do not depend
// on timing. The physics files provide the work; the executor alone knows
// OpenMP.
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <climits>
#include <cstddef>
#include <exception>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "solver/core/cache_aligned.hpp"
#include "solver/core/pass_times.hpp"
#include "solver/core/row_chunks.hpp"

namespace gearsph {

// A callable by reference, without allocation (std::function would
// allocate for most of the step's closures at every step). The callable
// must outlive the reference: the passes' work are named locals of the step.
template <class Signature>
class FunctionRef;

template <class R, class... Args>
class FunctionRef<R(Args...)> {
 public:
  template <class F>
  requires(!std::is_same_v<std::remove_cvref_t<F>, FunctionRef>)
      FunctionRef(F& f)  // NOLINT(google-explicit-constructor): a pass list reads as data
      : object_(const_cast<void*>(static_cast<const void*>(&f))),
        call_([](void* o, Args... a) { return (*static_cast<F*>(o))(std::forward<Args>(a)...); }) {}
  R operator()(Args... a) const { return call_(object_, std::forward<Args>(a)...); }

 private:
  void* object_;
  R (*call_)(void*, Args...);
};

enum class Runs {
  OverChunks,      // chunk c of `chunks` on thread c mod team: work(c, chunks)
  OnOneThread,     // thread 0 alone, inside the region: work(0, 1)
  OnEveryThread,   // every thread once: work(thread, team) (share() splits a range)
  OnCallingThread  // the caller's thread between two regions: work(0, 1)
};

enum class Sync {
  Barrier,   // a barrier before the pass (the first pass of a region has none to wait for)
  Continues  // no barrier: the same threads go on (see above)
};

template <class Sums>
struct Pass {
  const char* name;
  Runs runs;
  const RowChunks* chunks;                  // Runs::OverChunks only
  FunctionRef<void(int, int, Sums&)> work;  // (index, of; this thread's sums)
  Sync sync;
  bool on;  // false: skipped, with its barrier (a term the scene does not have)
};

// Items lo .. hi of `count` for share `index` of `of` (Runs::OnEveryThread):
// contiguous, in order, the same cut as a static loop over one thread.
struct Share {
  std::size_t lo, hi;
};
inline Share share(std::size_t count, int index, int of) {
  return {count * index / of, count * (index + 1) / of};
}

namespace detail {

using PassClock = std::chrono::steady_clock;

// The share of a timed step outside every pass: forking and joining the
// team, the threads' sums.
inline constexpr const char* kStartAndJoin = "threads start and join";

inline double seconds_between(PassClock::time_point a, PassClock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

}  // namespace detail

// Runs `passes` in order on `threads` threads: one thread runs them without
// a parallel region (libgomp wakes a team of one through the kernel at each
// barrier, ~7 % of a small step), and so does a call from inside a region
// (a pass's work that runs passes of its own). Once `stop` reads nonzero at
// a barrier or between regions, or a pass has thrown, the rest are skipped
// on every thread alike; the first exception is rethrown at the end. Only
// the passes before a region's first barrier may write `stop`: every
// thread reads it after that barrier, and a pass after it would be seen by
// a slow thread that has not read it yet and leaves, while a fast one
// waits at the next barrier for ever. With `times`, thread 0 reads a
// steady clock at each pass (pass_times.hpp).
template <class Sums>
Sums run_passes(std::span<const Pass<Sums>> passes, int threads, const std::size_t& stop,
                PassTimes* times = nullptr) {
  struct alignas(kCacheLine) Slot {
    Sums sums{};
  };
  const bool nested = omp_in_parallel() != 0;
  const int team_size = threads > 1 && !nested ? threads : 1;
  std::vector<Slot> slots(team_size);
  std::exception_ptr failed;
  // The first pass that threw. A flag would race: a fast thread could set
  // it in pass k while a slow one still reads it before pass k.
  std::atomic<int> failed_pass{INT_MAX};
  auto fail = [&](std::size_t k) {
#pragma omp critical(gearsph_pass_failure)
    {
      if (!failed) failed = std::current_exception();
      if (static_cast<int>(k) < failed_pass.load()) failed_pass.store(static_cast<int>(k));
    }
  };
  // Thread 0's clock (the calling thread is thread 0 of each region).
  const auto whole = times != nullptr ? detail::PassClock::now() : detail::PassClock::time_point{};
  detail::PassClock::time_point started{};
  double attributed = 0.0;
  std::size_t timing = passes.size();  // the pass the clock runs for
  auto clock = [&](std::size_t k) {    // pass k starts (k = size: none)
    if (times == nullptr) return;
    const auto now = detail::PassClock::now();
    if (timing < passes.size()) {
      const double s = detail::seconds_between(started, now);
      times->add(passes[timing].name, s);
      attributed += s;
    }
    started = now;
    timing = k;
  };
  auto run_one = [&](const Pass<Sums>& pass, int me, int team, Sums& mine) {
    switch (pass.runs) {
      case Runs::OverChunks:
        for (int c = me; c < pass.chunks->chunks(); c += team)
          pass.work(c, pass.chunks->chunks(), mine);
        break;
      case Runs::OnOneThread:
      case Runs::OnCallingThread:
        if (me == 0) pass.work(0, 1, mine);
        break;
      case Runs::OnEveryThread:
        pass.work(me, team, mine);
        break;
    }
  };
  // Passes first .. last-1 (none of them OnCallingThread) in one region.
  auto region = [&](std::size_t first, std::size_t last, int me, int team) {
    Sums& mine = slots[me].sums;
    for (std::size_t k = first; k < last; ++k) {
      const Pass<Sums>& pass = passes[k];
      if (!pass.on) continue;
      if (k > first && pass.sync == Sync::Barrier) {
#pragma omp barrier
        // Every thread reads the same here: `stop` was final before the
        // barrier, and a failure counts from the pass after it.
        if (stop > 0 || failed_pass.load() < static_cast<int>(k)) break;
      }
      if (me == 0) clock(k);
      try {
        run_one(pass, me, team, mine);
      } catch (...) {
        fail(k);
      }
    }
  };
  std::size_t k = 0;
  while (k < passes.size()) {
    if (k > 0 && (stop > 0 || failed)) break;  // between regions: the caller's thread alone
    if (passes[k].runs == Runs::OnCallingThread) {
      if (passes[k].on) {
        clock(k);
        try {
          passes[k].work(0, 1, slots[0].sums);
        } catch (...) {
          fail(k);
        }
      }
      ++k;
      continue;
    }
    std::size_t end = k;
    while (end < passes.size() && passes[end].runs != Runs::OnCallingThread) ++end;
    clock(passes.size());  // a pass on the calling thread ends here; the fork is no pass's
    if (team_size == 1) {
      region(k, end, 0, 1);
    } else {
#pragma omp parallel num_threads(team_size)
      region(k, end, omp_get_thread_num(), omp_get_num_threads());
    }
    clock(passes.size());
    k = end;
  }
  clock(passes.size());
  // What the passes' clocks did not see: the regions' start, the slots.
  if (times != nullptr) {
    times->add(detail::kStartAndJoin,
               detail::seconds_between(whole, detail::PassClock::now()) - attributed);
  }
  if (failed) std::rethrow_exception(failed);
  Sums total{};
  for (const Slot& s : slots) total += s.sums;
  return total;
}

// One pass over `count` items in even shares, one a thread: f(lo, hi, sums)
// for items lo .. hi (a per-particle term called on its own, outside a
// step's table: set-up, tests).
template <class Sums, class F>
Sums over_shares(const char* name, std::size_t count, int threads, F&& f) {
  auto work = [&](int me, int team, Sums& s) {
    const Share part = share(count, me, team);
    f(part.lo, part.hi, s);
  };
  const Pass<Sums> pass[] = {{name, Runs::OnEveryThread, nullptr, work, Sync::Barrier, true}};
  constexpr std::size_t kNeverStop = 0;
  return run_passes<Sums>(pass, threads, kNeverStop);
}

// The threads a run takes when it asks for none: OpenMP's default
// (OMP_NUM_THREADS, else the cores).
inline int available_threads() {
  return omp_get_max_threads();
}

// For passes that add up nothing.
struct NoSums {
  NoSums& operator+=(const NoSums&) { return *this; }
};

// One pass over `count` items whose costs differ widely (a clipped Voronoi
// cell against one wholly inside): blocks of `block` items handed out in
// turn as threads come free, f(i) for each item. Which thread runs an item
// then depends on timing, so f must write item i's result alone.
template <class F>
void over_blocks(const char* name, std::size_t count, std::size_t block, int threads, F&& f) {
  std::atomic<std::size_t> next{0};
  auto work = [&](int, int, NoSums&) {
    for (std::size_t lo = next.fetch_add(block); lo < count; lo = next.fetch_add(block)) {
      const std::size_t hi = std::min(count, lo + block);
      for (std::size_t i = lo; i < hi; ++i) f(i);
    }
  };
  const Pass<NoSums> pass[] = {{name, Runs::OnEveryThread, nullptr, work, Sync::Barrier, true}};
  constexpr std::size_t kNeverStop = 0;
  run_passes<NoSums>(pass, threads, kNeverStop);
}

}  // namespace gearsph
