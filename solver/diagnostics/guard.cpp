#include "solver/diagnostics/guard.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/core/simulation.hpp"
#include "solver/integrate/integrator.hpp"

namespace gearsph::diagnostics {

namespace {

struct Quantity {
  const char* name;
  const Column<double>* values;
};

[[noreturn]] void fail(const Simulation& sim, std::size_t i, const std::string& quantity,
                       double value, const std::string& what) {
  const Particles& p = sim.particles;
  std::ostringstream msg;
  msg.precision(6);
  msg << "diverged at step " << sim.step << " (t = " << sim.time << " s): particle " << i
      << " of body '" << sim.bodies[p.body[i]].name << "' " << what << " (" << quantity << " = "
      << value << ") at (" << p.x[i] << ", " << p.y[i] << ") m";
  throw DivergenceError(msg.str(), sim.step, static_cast<long>(i), quantity, value);
}

// Non-finite values first: they are the cause, the escape the symptom.
bool find_non_finite(const Simulation& sim) {
  const Particles& p = sim.particles;
  const Quantity quantities[] = {
      {"stress_xx", &p.sxx},     {"stress_yy", &p.syy},     {"stress_xy", &p.sxy},
      {"stress_zz", &p.szz},     {"pressure", &p.p},        {"density", &p.rho},
      {"acceleration_x", &p.ax}, {"acceleration_y", &p.ay}, {"velocity_x", &p.vx},
      {"velocity_y", &p.vy},     {"position_x", &p.x},      {"position_y", &p.y}};
  // A vector scan first (v - v is 0 for a finite v and NaN otherwise): the
  // look-up per particle and quantity below was 2 % of a short run that
  // checks every step; it runs only to name what went wrong.
  double any = 0.0, lowest_rho = 1.0;
  for (const Quantity& q : quantities) {
    const double* v = q.values->data();
#pragma omp simd reduction(+ : any)
    for (std::size_t i = 0; i < p.n; ++i) any += v[i] - v[i];
  }
  const double* rho = p.rho.data();
#pragma omp simd reduction(min : lowest_rho)
  for (std::size_t i = 0; i < p.n; ++i) lowest_rho = std::min(lowest_rho, rho[i]);
  if (any == 0.0 && lowest_rho > 0.0) return false;
  for (std::size_t i = 0; i < p.n; ++i) {
    for (const Quantity& q : quantities) {
      const double v = (*q.values)[i];
      if (!std::isfinite(v)) fail(sim, i, q.name, v, "became non-finite");
    }
    if (!(p.rho[i] > 0.0)) fail(sim, i, "density", p.rho[i], "has non-positive density");
  }
  return false;
}

}  // namespace

void check_health(const Simulation& sim) {
  find_non_finite(sim);
  const Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (!sim.domain.contains(p.x[i], p.y[i])) {
      const double r = std::hypot(p.vx[i], p.vy[i]);
      fail(sim, i, "speed", r, "left the domain");
    }
  }
}

void throw_divergence(const Simulation& sim) {
  check_health(sim);
  // check_health throws whenever kick_drift() saw a particle outside; reaching
  // here means the two disagree, which is a bug worth reporting plainly.
  throw DivergenceError("divergence guard: a particle left the domain but none was found", sim.step,
                        -1, "position", 0.0);
}

}  // namespace gearsph::diagnostics
