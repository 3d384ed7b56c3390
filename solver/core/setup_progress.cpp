#include "solver/core/setup_progress.hpp"

#include <chrono>
#include <utility>

namespace gearsph {

namespace {

using Clock = std::chrono::steady_clock;

struct State {
  SetupSink sink;
  Clock::time_point start{};
  Clock::time_point last{};
  double quiet_s = kSetupQuietS;
  bool reported = false;
  std::string stage;  // the last one reported
};

thread_local State state;

}  // namespace

struct SetupProgressScope::Saved {
  State previous;
};

SetupProgressScope::SetupProgressScope(SetupSink sink, double quiet_s)
    : saved_(std::make_unique<Saved>(Saved{std::move(state)})) {
  state = State{};
  state.sink = std::move(sink);
  state.start = Clock::now();
  state.quiet_s = quiet_s;
}

SetupProgressScope::~SetupProgressScope() {
  state = std::move(saved_->previous);
}

void setup_progress(const char* stage, double fraction) {
  if (!state.sink) return;
  const Clock::time_point now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - state.start).count();
  if (elapsed < state.quiet_s) return;
  if (state.reported && state.stage == stage &&
      std::chrono::duration<double>(now - state.last).count() < kSetupReportEveryS) {
    return;
  }
  state.reported = true;
  state.last = now;
  state.stage = stage;
  state.sink({stage, fraction < 0.0 ? 0.0 : fraction > 1.0 ? 1.0 : fraction, elapsed});
}

}  // namespace gearsph
