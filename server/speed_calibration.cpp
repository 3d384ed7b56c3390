#include "server/speed_calibration.hpp"

#include <exception>
#include <optional>

#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"

namespace gearsph::server {

namespace {

// 0.4 ms of simulated time: about 8,000 steps of the paper's case, 1 to 3 s
// of its loop on a 2-core machine, short against the set-up.
constexpr double kCalibrationEnd_s = 4e-4;

// Stops on request, and keeps the first and the last progress report: the
// speed between them leaves out the loop's start (the pairs' first build,
// the thread trial), which a long run spreads over many more steps.
class Calibrating : public RunObserver {
 public:
  explicit Calibrating(const std::function<bool()>& stop) : stop_(stop) {}
  bool cancelled() override { return stop_ && stop_(); }
  void on_progress(const Progress& p) override {
    if (!first_) first_ = p;
    last_ = p;
  }
  std::optional<Progress> first_, last_;

 private:
  const std::function<bool()>& stop_;
};

// Progress reports come every 0.5 s: two a second apart at least.
constexpr double kShortestSpan_s = 1.0;

}  // namespace

SpeedCalibration calibrate_speed(int threads, const std::function<bool()>& stop) {
  SpeedCalibration out;
  try {
    const nlohmann::json job = {{"name", "speed-calibration"},
                                {"scene", {{"type", "rack_pinion"}}},
                                {"time", {{"end_s", kCalibrationEnd_s}}},
                                {"output", {{"frames", 0}}}};
    PreparedJob prepared = prepare_job(job, threads);
    Calibrating observer(stop);
    const RunResult r = run_job(prepared, &observer);
    if (r.status != "completed" || r.wall_s <= 0.0) return out;
    out.particles = double(prepared.scene.sim.particles.n);
    out.steps = double(r.steps_done);
    out.wall_s = r.wall_s;
    const auto& a = observer.first_;
    const auto& b = observer.last_;
    if (a && b && b->wall_s - a->wall_s >= kShortestSpan_s) {
      out.steps = double(b->step - a->step);
      out.wall_s = b->wall_s - a->wall_s;
    }
    out.particle_steps_per_s = out.particles * out.steps / out.wall_s;
  } catch (const std::exception&) {
    // Unmeasured: the estimate says it uses its fallback.
  }
  return out;
}

}  // namespace gearsph::server
