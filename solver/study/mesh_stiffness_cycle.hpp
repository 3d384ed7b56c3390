#pragma once
// The mesh stiffness over one mesh cycle from quasi-static SPH checks of the
// pair a dynamic rack_pinion job models (docs/dynamics.md, "The measured
// stiffness"): the lumped model's k(s) built from the same particles,
// materials, teeth and load as the dynamic run, not from ISO 6336-1.
//
// Position s in [0, 1) is the fraction of a base pitch p_b that tooth 0's
// contact point has moved along the path of contact from its start: two
// pairs carry the load for s < eps - 1 (tooth 0 entering near its root, the
// tooth ahead of it near its tip), one pair for the rest of the cycle.
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "solver/gear/mesh_dynamics_sdof.hpp"

namespace gearsph::study {

inline constexpr int kDefaultCyclePositions = 8;

// The static checks of one cycle, ready to run.
struct MeshCyclePlan {
  std::vector<double> position;      // s of each check, ascending in (0, 1)
  std::vector<double> radius_m;      // tooth 0's contact radius there
  std::vector<nlohmann::json> jobs;  // quasi-static rack_pinion jobs
  double contact_ratio = 0.0;
  double base_pitch_m = 0.0;
  double face_width_m = 0.0;
};

// The checks at `positions` points s = (k + 1/2) / positions of the cycle
// (the midpoints keep each check off the path's ends, where the rack's tip
// meets the pinion's start of active profile) from a validated dynamic
// rack_pinion job: its particles, materials and rack load; the pinion and
// rack at rest; five pinion teeth (tooth 0, the two pairs' teeth and the rim
// beside their fillets) and four rack teeth (those meeting the two driving
// flanks in either sense of rotation), so that both pairs carry load where
// two are in contact. A plain static check models one rack tooth, which
// loads tooth 0 alone by design (ISO 6336's single pair). Throws
// InvalidJob at /job/... for a job that is not a loaded dynamic rack_pinion
// or a pair whose contact ratio is not between 1 and 2, and at
// /stiffness_positions for fewer than 2 or more than 64 positions.
MeshCyclePlan plan_mesh_stiffness_cycle(const nlohmann::json& dynamic_job, int positions);

// The pair's stiffness along the line of action [N/m] from a static check's
// summary: analysis.mesh_stiffness_N_per_mm_um (the rack's mean lag under
// the load, along the line of action) times the face width.
double static_check_stiffness_N_m(const nlohmann::json& summary, double face_width_m);

// The table from readings k_j at positions s_j: ascending in [0, 1),
// finite positive stiffnesses, at least two. Throws std::invalid_argument
// otherwise.
gear::dynamics::MeshCycleTable mesh_cycle_table(const std::vector<double>& position,
                                                const std::vector<double>& stiffness_N_m);

// The levels the table shows: the mean of the readings inside the
// double-contact part of the cycle (s < eps - 1) and of those outside it.
struct MeshCycleLevels {
  double single_pair_N_m = 0.0;
  double double_pair_N_m = 0.0;  // 0: no reading in the double-contact part
  double mean_N_m = 0.0;         // of the piecewise-linear table
};
MeshCycleLevels mesh_cycle_levels(const gear::dynamics::MeshCycleTable& table,
                                  double contact_ratio);

// The cycle measured: the checks run one after another on `threads`.
struct MeshStiffnessCycle {
  MeshCyclePlan plan;
  gear::dynamics::MeshCycleTable table;
  MeshCycleLevels levels;
  std::vector<double> tooth0_share;  // the share of the load on tooth 0
  double wall_s = 0.0;
  double particle_steps = 0.0;
};
MeshStiffnessCycle mesh_stiffness_cycle(const nlohmann::json& dynamic_job,
                                        int positions = kDefaultCyclePositions, int threads = 0);

// The cycle as speed_sweep.json's stiffness_table.
nlohmann::json describe_stiffness_cycle(const MeshStiffnessCycle& cycle);

}  // namespace gearsph::study
