#pragma once
// How fast this server computes, measured when it starts: the seed paper's
// rack-and-pinion case (its default scene) run for a few thousand steps on
// the threads a job gets, so that the first preview's run-time estimate is
// this machine's figure rather than a constant (docs/api.md, Preview).
#include <functional>

namespace gearsph::server {

struct SpeedCalibration {
  double particle_steps_per_s = 0.0;  // 0: not measured (stopped, or failed)
  double particles = 0.0, steps = 0.0, wall_s = 0.0;
};

// Runs the calibration (about 5 s on a 2-core machine, 4 of them the
// scene's set-up); `stop()` ends it early with nothing measured.
SpeedCalibration calibrate_speed(int threads, const std::function<bool()>& stop);

}  // namespace gearsph::server
