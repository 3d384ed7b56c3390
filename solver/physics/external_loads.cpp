#include "solver/physics/external_loads.hpp"

#include <algorithm>
#include <type_traits>

#include "solver/physics/simulation.hpp"

namespace gearsph::physics {

double load_ramp(const Simulation& sim) {
  return sim.load_ramp_s > 0.0 ? std::min(1.0, sim.time / sim.load_ramp_s) : 1.0;
}

// One vector loop: raw pointers, and the energy summed as a simd reduction
// (a scalar sum kept the loop scalar).
double external_accelerations(Particles& p, std::size_t lo, std::size_t hi, double ramp,
                              double damping, double dt, bool contact) {
  double *ext_ax = p.ext_ax.data(), *ext_ay = p.ext_ay.data();
  const double *load_ax = p.load_ax.data(), *load_ay = p.load_ay.data();
  const double *vx = p.vx.data(), *vy = p.vy.data(), *mass = p.mass.data();
  const double *contact_ax = p.contact_ax.data(), *contact_ay = p.contact_ay.data();
  double dissipated = 0.0;
  auto run = [&](auto with_contact) {
#pragma omp simd reduction(+ : dissipated)
    for (std::size_t i = lo; i < hi; ++i) {
      const double ax = ramp * load_ax[i] - damping * vx[i],
                   ay = ramp * load_ay[i] - damping * vy[i];
      ext_ax[i] = with_contact ? ax + contact_ax[i] : ax;
      ext_ay[i] = with_contact ? ay + contact_ay[i] : ay;
      dissipated += damping * mass[i] * (vx[i] * vx[i] + vy[i] * vy[i]) * dt;
    }
  };
  if (contact) {
    run(std::true_type{});
  } else {
    run(std::false_type{});
  }
  return dissipated;
}

}  // namespace gearsph::physics
