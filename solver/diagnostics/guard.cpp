#include "solver/diagnostics/guard.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/diagnostics/divergence.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::diagnostics {

namespace {

struct Quantity {
  const char* name;
  const Column<double>* values;
};

[[noreturn]] void fail(const Simulation& sim, std::size_t i, const std::string& quantity,
                       double value, const std::string& what, const char* found_by) {
  const Particles& p = sim.particles;
  std::ostringstream msg;
  msg.precision(6);
  msg << "diverged at step " << sim.step << " (t = " << sim.time << " s): particle " << i
      << " of body '" << sim.bodies[p.body[i]].name << "' " << what << " (" << quantity << " = "
      << value << ") at (" << p.x[i] << ", " << p.y[i] << ") m";
  if (found_by != nullptr) msg << ", found by the pass '" << found_by << "'";
  throw DivergenceError(msg.str(), sim.step, static_cast<long>(i), quantity, value);
}

// Non-finite values first: they are the cause, the escape the symptom.
bool find_non_finite(const Simulation& sim, const char* found_by) {
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
      if (!std::isfinite(v)) fail(sim, i, q.name, v, "became non-finite", found_by);
    }
    if (!(p.rho[i] > 0.0)) fail(sim, i, "density", p.rho[i], "has non-positive density", found_by);
  }
  return false;
}

}  // namespace

void check_health(const Simulation& sim, const char* found_by) {
  find_non_finite(sim, found_by);
  const Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (!sim.domain.contains(p.x[i], p.y[i])) {
      const double r = std::hypot(p.vx[i], p.vy[i]);
      fail(sim, i, "speed", r, "left the domain", found_by);
    }
  }
}

std::size_t outside_domain(const Simulation& sim, std::size_t lo, std::size_t hi) {
  // NaN fails every comparison, so a non-finite position counts as outside.
  const Box box = sim.domain;
  const double *x = sim.particles.x.data(), *y = sim.particles.y.data();
  std::size_t outside = 0;
#pragma omp simd reduction(+ : outside)
  for (std::size_t i = lo; i < hi; ++i) {
    const bool inside =
        x[i] >= box.x_min && x[i] <= box.x_max && y[i] >= box.y_min && y[i] <= box.y_max;
    outside += inside ? 0 : 1;
  }
  return outside;
}

void throw_divergence(const Simulation& sim, const char* found_by) {
  check_health(sim, found_by);
  // check_health throws whenever the domain check saw a particle outside;
  // reaching here means the two disagree, which is a bug worth reporting plainly.
  throw DivergenceError("divergence guard: a particle left the domain but none was found", sim.step,
                        -1, "position", 0.0);
}

}  // namespace gearsph::diagnostics
