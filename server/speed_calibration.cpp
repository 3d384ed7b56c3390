#include "server/speed_calibration.hpp"

#include <exception>

#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"

namespace gearsph::server {

namespace {

// 0.4 ms of simulated time: about 8,000 steps of the paper's case, long
// against the loop's start (its first steps fill the caches) and short
// against the set-up.
constexpr double kCalibrationEnd_s = 4e-4;

class StopWhen : public RunObserver {
 public:
  explicit StopWhen(const std::function<bool()>& stop) : stop_(stop) {}
  bool cancelled() override { return stop_ && stop_(); }

 private:
  const std::function<bool()>& stop_;
};

}  // namespace

SpeedCalibration calibrate_speed(int threads, const std::function<bool()>& stop) {
  SpeedCalibration out;
  try {
    const nlohmann::json job = {{"name", "speed-calibration"},
                                {"scene", {{"type", "rack_pinion"}}},
                                {"time", {{"end_s", kCalibrationEnd_s}}},
                                {"output", {{"frames", 0}}}};
    PreparedJob prepared = prepare_job(job, threads);
    StopWhen observer(stop);
    const RunResult r = run_job(prepared, &observer);
    if (r.status != "completed" || r.wall_s <= 0.0) return out;
    out.particles = double(prepared.scene.sim.particles.n);
    out.steps = double(r.steps_done);
    out.wall_s = r.wall_s;
    out.particle_steps_per_s = out.particles * out.steps / out.wall_s;
  } catch (const std::exception&) {
    // Unmeasured: the estimate says it uses its fallback.
  }
  return out;
}

}  // namespace gearsph::server
