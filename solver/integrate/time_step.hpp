#pragma once
// Time step selection. The Courant form dt = C h / max_i (c_i + |v_i|) uses
// the P-wave speed c = sqrt((K + 4G/3)/rho) (method.md; sqrt(K/rho) would
// let waves outrun the step by 25 % at nu = 0.3). The stable limit itself is
// measured on the scene's discrete operator (stability.hpp): free surfaces,
// corners, the gradient correction and the viscosity all lower it below
// what a lattice estimate says, and a user deserves the true number.
#include <optional>
#include <stdexcept>
#include <string>

#include "solver/kernels/kernel.hpp"

namespace gearsph {

struct Simulation;

// Interior-lattice Courant limit of a kernel: for the two-pass SPH operator a
// plane wave sees the derivative symbol G(k) = sum_j V_j sin(k.(x_j - x_i))
// grad_i W_ij, so kick-drift-kick needs c |G| dt <= 2, C_lattice =
// 2 / (h max_k |G(k)|). An upper bound: real scenes are lower.
double lattice_courant_limit(KernelType kernel, double h_over_dx);

// max_i (c_i + |v_i|) over all particles.
double max_signal_speed(const Simulation& sim);

// Default step when the job gives neither dt nor a Courant number.
constexpr double kAutoStepFraction = 0.8;

struct TimeStepChoice {
  double dt = 0.0;             // the step used [s]
  double dt_limit = 0.0;       // the largest stable step [s]
  double courant = 0.0;        // C of the step used
  double courant_limit = 0.0;  // C of dt_limit
  double signal_speed = 0.0;   // max (c + |v|) [m/s]
  std::string limited_by;      // what sets dt_limit
  std::string chosen_by;       // "dt_s", "cfl" or "auto"
};

class TimeStepError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TimeStepRequest {
  std::optional<double> dt_s;  // fixed step
  std::optional<double> cfl;   // Courant number
  double extra_limit_s = 0.0;  // a further bound, e.g. contact stiffness (0 = none)
  std::string extra_name;
  bool allow_unstable = false;  // stability studies only: run above the limit
};

// Refuses (TimeStepError, with the limit in the message) a dt or Courant
// number above the stable limit unless allow_unstable is set. The estimate
// runs on sim itself and puts it back (estimate_stability_limit).
TimeStepChoice choose_time_step(Simulation& sim, const TimeStepRequest& request);

}  // namespace gearsph
