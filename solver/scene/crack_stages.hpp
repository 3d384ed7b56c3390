#pragma once
// Quasi-static growth of a crack in stages (docs/cracks.md), shared by every
// scene that grows one (cracked_plate, rack_pinion): at each stage K_I and
// K_II are read at every tip by the interaction integral on a ring that
// leaves the tip's support and the other boundaries out, recorded, and
// unless a stop rule holds each tip advances by one increment in its
// direction of maximum tangential stress (physics/crack_growth.hpp); the
// reference pairs are then cut and built again, whole.
//
// What the scenes differ in is handed in: how far a tip is from the other
// boundaries of its body (the ring's size and the stop), and what a stop
// at a boundary means (the plate's "free_surface", the gear's "tooth" or
// "rim").
#include <chrono>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/diagnostics/stress_intensity.hpp"
#include "solver/geometry/crack.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::scenes {

// The ring of the domain integral, as fractions of the distance rho from the
// tip to the nearest other boundary: wide enough to hold many particles,
// clear of the tip's support inside and of the other boundaries outside.
inline constexpr double kCrackRingOuter = 0.8;
inline constexpr double kCrackRingInner = 0.3;
// The least rho, in spacings, for the ring to leave the tip's support out.
inline constexpr double kCrackLeastClearSpacings = 8.0;
// After an increment the body is held at its full load for this many periods
// of its slowest mode: the mass-proportional damping at that mode's frequency
// omega takes every mode's amplitude down by exp(-omega t / 2), exp(-3 pi) =
// 8e-5 of the jump the cut gave.
inline constexpr double kCrackSettlePeriods = 3.0;

struct CrackGrowthInput {
  double increment = 0.0;  // [m]
  int max_increments = 0;
  double K_I_threshold = 0.0;  // [Pa m^0.5]
};

struct CrackTipReadout {
  diagnostics::CrackTip tip;
  diagnostics::DomainRing ring;
  double clear = 0.0;  // rho [m]
};

// The distance from a tip to the nearest boundary of the body other than
// the crack's own faces near the tip (edges, the mouth, the other tip) [m].
using CrackClearance = std::function<double(geometry::Point tip, const geometry::Crack& crack)>;

struct CrackStages {
  CrackGrowthInput in;
  double dx = 0.0;        // the spacing at the crack, for the stop rule [m]
  double settle_s = 0.0;  // the hold after each increment
  CrackClearance clearance;
  // A stop because the next tip would come within the ring's reach of a
  // boundary: the outcome's name (default "free_surface").
  std::function<std::string(const geometry::Crack& grown, geometry::Point next)> boundary_outcome;
  // Called once, at the first stage, with the tips as drawn (the plate keeps
  // its analysis of the drawn crack).
  std::function<void(const std::vector<CrackTipReadout>&, const Simulation&)> on_first_stage;

  std::vector<std::vector<geometry::Point>> paths;  // per tip, its positions
  std::vector<double> K_I, K_II, kink_deg;          // per stage (the tips' mean)
  std::vector<double> rebuild_s, stage_s;           // the pairs' rebuild, the stage's wall time
  std::string outcome, stop;
  bool first_done = false;
  std::chrono::steady_clock::time_point stage_start = std::chrono::steady_clock::now();
};

// The crack's tips as they are now: its end, advancing along its last
// segment, and for a crack inside the body its front too.
std::vector<CrackTipReadout> crack_tips(const geometry::Crack& crack,
                                        const CrackClearance& clearance);

// One stage (Scene::next_stage): returns the hold to run on, 0 to end.
double grow_crack_stage(CrackStages& g, Simulation& sim);

// analysis.crack: increment_m, increments, path_m (the first tip's
// positions), tip_paths_m, K_I_Pa_sqrt_m, K_II_Pa_sqrt_m and kink_deg per
// stage, outcome, stop, pair_rebuild_s, stage_wall_s.
nlohmann::json crack_growth_json(const CrackStages& g);

}  // namespace gearsph::scenes
