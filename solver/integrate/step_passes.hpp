#pragma once
// What the two steps' pass tables share (step_total_lagrangian.cpp,
// step_updated_lagrangian.cpp): their sums, the clock, the contact list
// and the executor's call with the pass clock. Internal to integrate/.
#include <atomic>
#include <cstddef>
#include <span>

#include "solver/core/passes.hpp"
#include "solver/integrate/motion.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::integrate {

// What a step's passes add up; each thread its own (run_passes adds them in
// thread order).
struct StepSums {
  double viscous = 0.0;  // power the viscosity (and hourglass control) remove [W/m]
  double damped = 0.0;   // energy the mass damping removed over the step
  physics::ContactTally touched;
  KickPowers power;
  StepSums& operator+=(const StepSums& o) {
    viscous += o.viscous;
    damped += o.damped;
    touched += o.touched;
    power += o.power;
    return *this;
  }
};

// The step's ledger, once the passes are done, in the order the terms were
// always added (the same bits as before the table).
inline void book_step(Simulation& sim, const StepSums& sums, bool contact, bool torque) {
  const double dt = sim.dt;
  sim.energy.dissipated += dt * sums.viscous;
  sim.energy.dissipated += sums.damped;
  if (contact) physics::record_contact(sim, sums.touched);
  const double drive = torque ? sums.power.drive + torque_drive_power(sim) : sums.power.drive;
  sim.energy.drive_work += dt * drive;
  sim.energy.external_work += dt * sums.power.load;
}

// Whether the bodies touch through the contact list (a penalty law).
bool penalty_contact(const Simulation& sim);
// t += dt, step += 1: the step's one clock.
inline void advance_clock(Simulation& sim) {
  sim.time += sim.dt;
  ++sim.step;
}
// Particles lo .. hi that moved beyond half the contact list's skin.
std::size_t contacts_moved(const Simulation& sim, std::size_t lo, std::size_t hi);
// The contact list, rebuilt if `moved` or never built (integrator.cpp).
void refresh_contacts(Simulation& sim, bool moved);
// Both lists: the kernel's (updated Lagrangian) if its skin is used up,
// and the contact list.
void refresh_neighbours(Simulation& sim, bool contacts_moved);

// Adds n to a count the threads share; nonzero only when a particle left
// the domain or the contact list needs a rebuild (a few steps in thousands).
inline void add_shared(std::size_t& count, std::size_t n) {
  if (n > 0) std::atomic_ref<std::size_t>(count).fetch_add(n, std::memory_order_relaxed);
}

// A step's table through the executor, timed on one step in
// PassTimes::kTimedEvery. `apart`: each run of passes between two barriers
// in a parallel region of its own, the reference a table's barriers are
// tested against (tests/test_one_region_step.cpp); the same bits on one
// thread, the totals in another order on several.
template <class Sums>
Sums run_step_passes(Simulation& sim, std::span<const Pass<Sums>> passes, int threads,
                     const std::size_t& stop, bool apart) {
  PassTimes* const times = PassTimes::timed(sim.step) ? &sim.pass_times : nullptr;
  if (times != nullptr) times->count_step();
  if (!apart) return run_passes<Sums>(passes, threads, stop, times);
  Sums total{};
  for (std::size_t k = 0; k < passes.size() && !(k > 0 && stop > 0);) {
    std::size_t end = k + 1;
    while (end < passes.size() && passes[end].sync == Sync::Continues &&
           passes[end].runs != Runs::OnCallingThread) {
      ++end;
    }
    total += run_passes<Sums>(passes.subspan(k, end - k), threads, stop, times);
    k = end;
  }
  return total;
}

}  // namespace gearsph::integrate
