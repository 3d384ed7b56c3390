#pragma once
// Everything a time step reads and writes: particles, bodies, constraints,
// method, neighbour lists and the running energy ledger.
#include <cstdint>
#include <string>
#include <vector>

#include "solver/core/body.hpp"
#include "solver/core/method.hpp"
#include "solver/core/motion.hpp"
#include "solver/core/particles.hpp"
#include "solver/core/pass_times.hpp"
#include "solver/geometry/crack.hpp"
#include "solver/neighbours/neighbour_list.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/total_lagrangian.hpp"

namespace gearsph {

struct Box {
  double x_min = 0, y_min = 0, x_max = 0, y_max = 0;
  bool contains(double x, double y) const {
    return x >= x_min && x <= x_max && y >= y_min && y <= y_max;
  }
};

// Energy that leaves or enters the particles other than as kinetic/elastic
// energy, integrated over the run [J per metre of thickness].
struct EnergyLedger {
  double dissipated = 0.0;     // artificial viscosity and hourglass damping
  double drive_work = 0.0;     // work done on the particles by kinematic constraints
  double external_work = 0.0;  // work of external forces (loads, contact)
};

// The largest J2 of the stress at one step and its particle, found by the
// total-Lagrangian stress pass while the stress is at hand, so that peak
// tracking needs no pass of its own (diagnostics::max_von_mises).
struct LargestJ2 {
  double j2 = 0.0;
  long particle = -1;      // -1: every J2 is zero
  std::int64_t step = -1;  // the step whose stress it describes; -1: none
};

struct Simulation {
  Particles particles;
  std::vector<Body> bodies;
  std::vector<Motion> motions{Motion::free()};
  Discretization discretization;
  MethodConfig method;

  double dt = 0.0;
  double time = 0.0;
  std::int64_t step = 0;
  Box domain;  // leaving it stops the run (divergence guard)
  int threads = 1;

  NeighbourList neighbours;    // kernel interactions (updated Lagrangian)
  ReferencePairs reference;    // fixed pairs (total Lagrangian)
  ContactConfig contact;       // between bodies
  NeighbourList contacts;      // contact candidates: pairs from different bodies
  ContactState contact_state;  // what the contact did in the last step
  // Cracks in the reference configuration: the total-Lagrangian pairs that
  // cross one are cut (physics/crack_cut.hpp).
  std::vector<geometry::Crack> cracks;
  // Mass-proportional damping a = -damping v for quasi-static (dynamic
  // relaxation) scenes; 0 for dynamics [1/s].
  double damping_1_s = 0.0;
  // Applied loads grow linearly from zero over this time (0: at once) [s].
  double load_ramp_s = 0.0;
  EnergyLedger energy;
  LargestJ2 largest_j2;
  PassTimes pass_times;  // where the steps' time went, pass by pass (summary's timing)

  double h() const { return discretization.h(); }
  const Material& material_of(std::size_t i) const { return bodies[particles.body[i]].material; }
};

}  // namespace gearsph
