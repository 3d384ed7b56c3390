#pragma once
// A step as a list of passes, run by one executor that owns the threads,
// the barriers between passes and the errors (the shape of Box2D v3's
// solver stages). A pass is data: a name, what it runs over and its work.
// The physics files provide the work; the executor alone knows OpenMP.
//
//   const Pass<Sums> step[] = {
//       {"kick and drift", Runs::OverChunks, &chunks, kick_drift},
//       {"clock", Runs::OnOneThread, nullptr, clock},
//       ...};
//   const Sums totals = run_passes<Sums>(step, threads, stopped);
//
// Every thread runs every pass in order; a barrier stands between two
// passes, so a pass may read whatever the passes before it wrote on any
// thread. Each thread adds into its own Sums; they are added in thread
// order at the end, so the totals do not depend on timing.
#include <omp.h>

#include <atomic>
#include <climits>
#include <cstddef>
#include <exception>
#include <span>
#include <type_traits>
#include <utility>
#include <vector>

#include "solver/core/cache_aligned.hpp"
#include "solver/neighbours/row_chunks.hpp"

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
  OverChunks,    // chunk c of `chunks` on thread c mod team (for_my_chunks)
  OnOneThread,   // thread 0 alone; the others wait at the next barrier
  OnEveryThread  // every thread once (work that shares itself out: omp for)
};

template <class Sums>
struct Pass {
  const char* name;
  Runs runs;
  const RowChunks* chunks;             // Runs::OverChunks only
  FunctionRef<void(int, Sums&)> work;  // (chunk, or -1; this thread's sums)
};

// Runs `passes` in order on `threads` threads: one thread runs them without
// a parallel region (libgomp wakes a team of one through the kernel at each
// barrier, ~7 % of a small step). Once `stop` reads nonzero after a
// barrier, or a pass has thrown, the rest are skipped on every thread
// alike; the first exception is rethrown after the region. Only the first
// pass may write `stop`: every thread reads it after the barrier that ends
// that pass, never before the first pass, where a slow thread would see
// what a fast one's first pass already wrote, leave, and leave the fast
// one waiting at the next barrier for ever.
template <class Sums>
Sums run_passes(std::span<const Pass<Sums>> passes, int threads, const std::size_t& stop) {
  struct alignas(kCacheLine) Slot {
    Sums sums{};
  };
  const int team_size = threads > 1 ? threads : 1;
  std::vector<Slot> slots(team_size);
  std::exception_ptr failed;
  // The first pass that threw. A flag would race: a fast thread could set
  // it in pass k while a slow one still reads it before pass k.
  std::atomic<int> failed_pass{INT_MAX};
  auto run = [&](int me, int team) {
    Sums& mine = slots[me].sums;
    for (std::size_t k = 0; k < passes.size(); ++k) {
      if (k > 0) {
#pragma omp barrier
        // Every thread reads the same here: `stop` was final before the
        // barrier, and a failure counts from the pass after it.
        if (stop > 0 || failed_pass.load() < static_cast<int>(k)) break;
      }
      const Pass<Sums>& pass = passes[k];
      try {
        switch (pass.runs) {
          case Runs::OverChunks:
            for (int c = me; c < pass.chunks->chunks(); c += team) pass.work(c, mine);
            break;
          case Runs::OnOneThread:
            if (me == 0) pass.work(-1, mine);
            break;
          case Runs::OnEveryThread:
            pass.work(-1, mine);
            break;
        }
      } catch (...) {
#pragma omp critical(gearsph_pass_failure)
        {
          if (!failed) failed = std::current_exception();
          if (static_cast<int>(k) < failed_pass.load()) failed_pass.store(static_cast<int>(k));
        }
      }
    }
  };
  if (team_size == 1) {
    run(0, 1);
  } else {
#pragma omp parallel num_threads(team_size)
    run(omp_get_thread_num(), omp_get_num_threads());
  }
  if (failed) std::rethrow_exception(failed);
  Sums total{};
  for (const Slot& s : slots) total += s.sums;
  return total;
}

}  // namespace gearsph
