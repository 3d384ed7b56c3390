#pragma once
// The run's health check: the solver watches its own failure modes
// (method.md, "known weaknesses") while it runs, and stops or warns with a
// message that says what failed, when, where and what to change.
//
//  - energy growth: kinetic + elastic + contact + dissipated - work in must
//    stay constant for a symplectic step; it grows when the step is above
//    the stable limit or a non-conservative term (artificial stress, a
//    penalty law too stiff for dt) feeds the motion;
//  - particle disorder: the closest pair of particles of one body, over the
//    spacing. Elastic strains never bring lattice neighbours within half a
//    spacing; the tensile instability (Swegle et al. 1995) and hourglass
//    modes do, long before anything becomes NaN;
//  - penetration: how far particles of different bodies overlap, over the
//    spacing (contact too soft for the impact, or no contact force at all);
//  - zig-zag (hourglass) indicator: the part of the stress field that
//    changes sign from a particle to its lattice neighbours, over the
//    field's RMS (warning only: fields that hold give 0.2-0.9, the most at
//    sharp wave fronts; clumped or zig-zag fields 1.2-1.4; a checkerboard
//    gives 1, its 8 lattice neighbours averaging to zero);
//  - NaN/Inf and escape from the domain stay with the divergence guard
//    (guard.hpp), which always stops.
// Limits come from the job's `health` section (schemas/job.schema.json).
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/diagnostics/divergence.hpp"
#include "solver/diagnostics/energy.hpp"

namespace gearsph {
struct Simulation;
namespace diagnostics {

struct HealthLimits {
  bool stop = true;  // false: warn only, never stop
  // Of the largest mechanical energy so far. Artificial stress acts as a
  // repulsion whose energy the balance does not count: it reads +13 % on a
  // strip stretched to 10 % (docs/stability.md), so the limit sits above it;
  // a real instability grows exponentially past any limit.
  double energy_growth = 0.3;
  double min_spacing_over_dx = 0.5;  // closest same-body pair
  double penetration_over_dx = 0.5;  // deepest overlap between bodies
  // Hourglass indicator (warning only). Measured: 0.2-0.9 on fields that
  // hold (sharp wave fronts at the top), 1.2-1.4 on clumped or zig-zag ones.
  double zigzag = 1.0;
  // Warnings come earlier: at this share of the energy and penetration
  // limits, and 60 % of the way from 1 dx down to the spacing limit.
  double warn_fraction = 0.5;
};

// Reads the job's `health` object (defaults applied by the schema).
HealthLimits read_health_limits(const nlohmann::json& health);

// What the monitor measured, worst over the run.
struct HealthMeasures {
  double energy_growth = 0.0;            // max of (E - E0) / scale
  double min_spacing_over_dx = 1e300;    // min over the run
  double max_penetration_over_dx = 0.0;  // max over the run
  double zigzag = 0.0;                   // max over the run
  double zigzag_final = 0.0;
  double energy_scale = 0.0;  // largest kinetic + elastic + contact [J/m]
};

struct HealthEvent {
  std::string detector;  // energy_growth | particle_disorder | penetration | zigzag
  std::string level;     // warning | stop
  std::int64_t step = 0;
  double time_s = 0.0;
  double value = 0.0, limit = 0.0;
  long particle = -1;
  std::string message;
};

// Thrown when a limit is crossed and the limits say stop; the runner turns
// it into a stopped run like any divergence.
class HealthError : public DivergenceError {
 public:
  HealthError(const HealthEvent& e)
      : DivergenceError(e.message, static_cast<long>(e.step), e.particle, e.detector, e.value),
        event(e) {}
  HealthEvent event;
};

// Zig-zag indicator of the stress field (see the header comment):
// sqrt(sum_i |s_i - <s>_i|^2 / sum_i |s_i|^2) over the in-plane components
// s = (sigma_xx, sigma_yy, sigma_xy), <s>_i the mean over the particle's
// lattice neighbours (reference distance < 1.5 dx, same body).
double zigzag_indicator(const Simulation& sim);

// The pair-loop detectors' pairs and buffers, kept between checks: in a
// total-Lagrangian run the pairs never change, so a check loops over a
// compact list instead of sorting the same-body pairs out of every pair
// again (the check at every tenth step was 5 % of a short run).
struct HealthPairs {
  std::vector<std::uint32_t> i, j;  // same-body pairs, each once
  std::vector<double> dx2;          // their spacing squared
  std::vector<std::uint32_t> near;  // those about one spacing apart (zig-zag)
  std::vector<double> q2, s, sum, count;
  std::size_t particles = 0;
  bool fixed = false;  // built from the reference pairs: valid for the run
};
double zigzag_indicator(const Simulation& sim, HealthPairs& pairs);

// Closest same-body pair distance over dx, and the particle.
struct Spacing {
  double over_dx = 1e300;
  long particle = -1;
};
// `pairs`: kept between calls (HealthPairs).
Spacing min_spacing(const Simulation& sim, HealthPairs& pairs);

// Deepest overlap between bodies over dx (0 with one body).
double penetration_over_dx(const Simulation& sim);

class HealthMonitor {
 public:
  explicit HealthMonitor(HealthLimits limits = {}) : limits_(limits) {}
  // Call after initialisation, then after steps (e.g. at history samples).
  // Throws HealthError on a crossed limit when limits.stop. `full`: also the
  // detectors that loop over pairs (particle spacing, zig-zag); without it,
  // the energy and the contact's penetration only.
  void check(const Simulation& sim, bool full = true);
  // The same with the energy already found (the history row has it).
  void check(const Simulation& sim, const EnergyState& e, bool full);
  const HealthMeasures& measures() const { return measures_; }
  const std::vector<HealthEvent>& events() const { return events_; }
  // "ok", "warning" or "stopped".
  std::string status() const;
  // For summary.json: status, limits, measures, events.
  nlohmann::json report() const;
  // One line per event, for the summary's "warnings".
  std::vector<std::string> warnings() const;

 private:
  void raise(const Simulation& sim, const std::string& detector, double value, double limit,
             bool stop, long particle, const std::string& what);
  HealthLimits limits_;
  HealthMeasures measures_;
  HealthPairs pairs_;
  bool started_ = false;
  double e0_ = 0.0;
  std::vector<HealthEvent> events_;
  std::vector<std::string> warned_;  // detectors that already warned
  bool stopped_ = false;
};

}  // namespace diagnostics
}  // namespace gearsph
