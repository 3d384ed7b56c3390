#pragma once
// The speed sweep (docs/dynamics.md): one loaded rack_pinion job run at
// several speeds, given as ratios of the mesh frequency to the lumped
// model's natural frequency, each speed's steady mesh read from its run
// (analysis.dynamics), and the lumped model (gear/mesh_dynamics_sdof.hpp)
// of the same stiffness and masses swept over the same speeds, with ISO
// 6336-1's resonance beside them.
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/gear/mesh_dynamics_sdof.hpp"
#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"
#include "solver/study/mesh_stiffness_cycle.hpp"

namespace gearsph::study {

// What one job of the sweep may be, as a server bounds a run
// (server/config.hpp, Limits: the same defaults).
struct SweepLimits {
  double max_particles = 5e6;
  double max_steps = 1e8;
  double max_particle_steps = 1e12;
  int max_jobs = 100;
};

// A request: {"job": {...}, "ratios": [0.2, ...], "steady_periods": 20,
// "stiffness": "measured" | "iso" | a table, "stiffness_positions": 8}.
struct SpeedSweepRequest {
  nlohmann::json job;  // validated, defaults filled
  std::vector<double> ratios;
  int steady_periods = 20;
  // The lumped model's mesh stiffness over the cycle: from quasi-static
  // checks of the same pair (mesh_stiffness_cycle.hpp) or ISO 6336-1's two
  // levels.
  // Or a table given ("given"): {"position": [...], "stiffness_N_m": [...]},
  // such as a measured cycle's stiffness_cycle.json from an earlier sweep.
  std::string stiffness = "iso";
  gear::dynamics::MeshCycleTable given_stiffness;
  int stiffness_positions = kDefaultCyclePositions;
};

// The ratios a sweep takes when none are given: below, through and above
// the resonance.
std::vector<double> default_sweep_ratios();

// Checks a request before anything runs; throws InvalidJob naming the
// pointer of each refusal: the job's own (under /job), a scene that is not
// a loaded dynamic rack_pinion, ratios that are not positive.
SpeedSweepRequest read_speed_sweep(const nlohmann::json& request);

struct SpeedSweepPlan {
  SpeedSweepRequest request;
  nlohmann::json lumped_model;  // model.lumped_model of the sweep's scene
  // The stiffness the lumped model takes, and its natural frequency on the
  // table's mean, which sets the speeds.
  gear::dynamics::MeshCycleTable stiffness;
  std::string stiffness_from;      // "measured" | "iso" | "given"
  nlohmann::json stiffness_cycle;  // the measured cycle's checks (null for ISO)
  double natural_frequency_Hz = 0.0;
  double iso_resonance_Hz = 0.0;  // 0: not rated
  std::vector<double> mesh_frequency_Hz;
  std::vector<nlohmann::json> jobs;  // one per ratio, runnable with `gearsph run`
  std::vector<double> particle_steps;
  double transient_allowance_s = 0.0;  // of the slowest speed
};

// The speeds' jobs: the pinion held at omega = 2 pi f / z (the rack at the
// pitch-line speed), every pinion tooth and a rack long enough for the
// longest run modelled (so that every speed has the same masses), each run
// as long as a start transient of at most `transient_natural_periods`
// natural periods plus the steady periods and the detector's reference, no
// snapshots. Builds the first speed's scene once for the lumped model;
// throws InvalidJob at /ratios/k for a speed whose job would exceed the
// limits, and at /ratios for more jobs than allowed. A request for the
// measured stiffness runs its static checks here (on `threads`) unless
// `measured` gives them.
SpeedSweepPlan plan_speed_sweep(const SpeedSweepRequest& request, const SweepLimits& limits,
                                double transient_natural_periods = 30.0,
                                const MeshStiffnessCycle* measured = nullptr, int threads = 0);

// The plan as a document and back (a service keeps it with the study, and
// reports from it once the study's jobs have run).
nlohmann::json plan_document(const SpeedSweepPlan& plan);
SpeedSweepPlan plan_from_document(const nlohmann::json& document);

// The lumped model from a scene's model.lumped_model block: ISO's two
// levels, or the given stiffness over the cycle.
gear::dynamics::SdofModel sdof_from_description(const nlohmann::json& lumped_model,
                                                double damping_ratio);
gear::dynamics::SdofModel sdof_from_description(const nlohmann::json& lumped_model,
                                                double damping_ratio,
                                                const gear::dynamics::MeshCycleTable& stiffness);

// speed_sweep.json from the plan, each speed's summary (null: did not
// run) and the lumped model swept with the damping measured from the SPH
// runs' ringing (the median of those measured; `fallback_damping_ratio`
// when none was).
nlohmann::json sweep_report(const SpeedSweepPlan& plan,
                            const std::vector<nlohmann::json>& summaries,
                            double fallback_damping_ratio);

}  // namespace gearsph::study
