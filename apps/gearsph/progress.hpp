#pragma once
// Progress with ETA on stderr, redrawn in place on a terminal.
#include <unistd.h>

#include <cstdio>

#include "solver/run/runner.hpp"

namespace gearsph::cli {

class ProgressPrinter : public RunObserver {
 public:
  explicit ProgressPrinter(bool quiet) : quiet_(quiet), tty_(isatty(2) != 0) {}
  void on_progress(const Progress& p) override {
    if (quiet_) return;
    std::fprintf(stderr, "%s[%5.1f%%] step %lld/%lld  t = %.4g s  wall %.1f s  ETA %.1f s%s",
                 tty_ ? "\r" : "", 100.0 * p.fraction(), static_cast<long long>(p.step),
                 static_cast<long long>(p.steps), p.time_s, p.wall_s, p.eta_s, tty_ ? "   " : "\n");
    if (tty_ && p.step >= p.steps) std::fputc('\n', stderr);
  }
  // A stage after the time loop (the FE check): a line of its own each time
  // it reports, read back by the Slurm dispatcher (server/slurm_dispatch.hpp).
  void on_stage(const StageProgress& s) override {
    if (quiet_) return;
    std::fprintf(stderr, "[stage %s] %.1f %% done, %.2f s\n", s.stage.c_str(), 100.0 * s.fraction,
                 s.elapsed_s);
  }

 private:
  bool quiet_;
  bool tty_;
};

}  // namespace gearsph::cli
