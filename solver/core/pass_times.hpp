#pragma once
// Where a step's time goes, pass by pass (the executor's clock, passes.hpp),
// as Box2D v3 times its solver stages by name. Thread 0 reads a steady
// clock as each pass starts, on one step in kTimedEvery, so that the clock
// costs nothing measurable (one clock read a pass on 1 step in 16: about
// 20 reads of ~25 ns in 16 gear steps of at least 100 us, 0.03 %). A pass's time is thread 0's,
// up to the start of the next pass or the end of its parallel region: its
// own work and its wait at the barrier after it, i.e. what the pass costs
// the step. What no pass saw (starting the threads) has a row of its own.
#include <cstdint>
#include <cstring>
#include <vector>

namespace gearsph {

struct PassTime {
  const char* name = "";  // a string literal of a pass table
  double seconds = 0.0;   // summed over the timed steps
  std::int64_t runs = 0;  // timed steps that ran it
};

class PassTimes {
 public:
  // One step in this many is timed.
  static constexpr std::int64_t kTimedEvery = 16;
  static bool timed(std::int64_t step) { return step % kTimedEvery == 0; }

  void add(const char* name, double seconds) {
    for (PassTime& t : entries_) {
      // Pointers first: a table's names are the same literals every step.
      if (t.name == name || std::strcmp(t.name, name) == 0) {
        t.seconds += seconds;
        ++t.runs;
        return;
      }
    }
    entries_.push_back({name, seconds, 1});  // allocates on the first timed step only
  }
  void count_step() { ++steps_; }
  // In the order the passes first ran.
  const std::vector<PassTime>& entries() const { return entries_; }
  std::int64_t timed_steps() const { return steps_; }
  double total_seconds() const {
    double s = 0.0;
    for (const PassTime& t : entries_) s += t.seconds;
    return s;
  }

 private:
  std::vector<PassTime> entries_;
  std::int64_t steps_ = 0;
};

}  // namespace gearsph
