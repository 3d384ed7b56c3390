#pragma once
// The steady mesh of a dynamic gear run, read from its histories
// (docs/dynamics.md): where the start transient ends, detected from the
// run itself, and over the steady periods the mesh force's mean and peak
// (per tooth and overall), the dynamic factor K_v = peak / mean, the
// dynamic transmission error's peak to peak and RMS, and the fraction of
// time no tooth touches. Also the damping of a free ringing, by the
// logarithmic decrement.
#include <string>
#include <utility>
#include <vector>

namespace gearsph::diagnostics {

struct MeshHistories {
  std::vector<double> t;              // [s]
  std::vector<double> total_force_N;  // the mesh force, all teeth
  std::vector<double> dte_m;          // transmission error along the line of action
  std::vector<std::pair<int, std::vector<double>>> tooth_force_N;  // per modelled tooth
  double mesh_frequency_Hz = 0.0;
};

struct SteadyMeshOptions {
  // Steady from the first mesh period after which every period's mean and
  // peak mesh force stay within `tolerance` of the last `reference_periods`
  // periods' (their means).
  double tolerance = 0.05;
  int reference_periods = 3;
  int min_steady_periods = 3;
  // No tooth in contact: the mesh force below this share of its mean.
  double contact_threshold = 0.01;
};

struct ToothLoad {
  int tooth = 0;
  double mean_N = 0.0;  // time mean over the steady window
  double peak_N = 0.0;
  double loaded_fraction = 0.0;  // of the window with this tooth carrying > 5 % of the total
};

struct SteadyMesh {
  bool steady = false;
  std::string note;  // why not, in words
  double mesh_frequency_Hz = 0.0;
  int periods_in_run = 0;
  double steady_from_s = -1.0;  // start of the window (the run's second half when not steady)
  int steady_periods = 0;
  double window_s = 0.0;
  double mean_force_N = 0.0, peak_force_N = 0.0, K_v = 0.0;
  double dte_mean_m = 0.0, dte_pp_m = 0.0, dte_rms_m = 0.0;
  double contact_loss_fraction = 0.0;
  std::vector<ToothLoad> teeth;
};

// Mesh periods of 1 / mesh_frequency_Hz from t.front(); the window's numbers
// are read over whole periods.
SteadyMesh steady_mesh(const MeshHistories& h, const SteadyMeshOptions& opt = {});

// The damping ratio of a free ringing about its final value: successive
// extremes of |v - v_end| (v_end the mean of the last quarter) after t_from,
// zeta = delta / sqrt(4 pi^2 + delta^2) with delta the mean logarithmic
// decrement per cycle from a least-squares line through ln|extreme| against
// the half-cycle count (half cycles: extremes alternate in sign). Returns
// the ratio and the number of extremes used (< 3: not measured, ratio -1).
struct RingDown {
  double damping_ratio = -1.0;
  double frequency_Hz = 0.0;  // from the extremes' spacing
  int extremes = 0;
};
RingDown ring_down(const std::vector<double>& t, const std::vector<double>& v, double t_from,
                   double t_to);

}  // namespace gearsph::diagnostics
