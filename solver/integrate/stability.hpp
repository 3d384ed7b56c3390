#pragma once
// The largest stable time step of a scene, measured on its own discrete
// operator rather than guessed from a Courant number.
//
// Kick-drift-kick is stable for a linear oscillator x'' = -omega^2 x -
// gamma x' (damping evaluated explicitly) when
//   dt <= 2 (sqrt(omega^2 + gamma^2/4) - gamma/2) / omega^2,
// which is 2/omega without damping. omega^2 is the largest eigenvalue of the
// linearised elastic operator (stiffness over mass) and gamma the largest of
// the linearised artificial-viscosity operator; both are found by power
// iteration with the solver's own force routines, on the initial
// configuration, so corners, free surfaces, the gradient correction and the
// kernel all count. The signal speed |v| is added as in the Courant
// condition: dt_limit scales with c_p / (c_p + |v|_max).
namespace gearsph {

struct Simulation;

struct StabilityLimit {
  double omega_max = 0.0;     // [rad/s]
  double damping_rate = 0.0;  // gamma [1/s]
  double dt_limit = 0.0;      // [s]
  int iterations = 0;
};

// Runs on the scene itself and leaves it as it found it; a total-Lagrangian
// scene keeps the reference pairs it builds (physics::total_lagrangian_setup).
StabilityLimit estimate_stability_limit(Simulation& sim);

}  // namespace gearsph
