// The contact's forces on every particle, spread over the surface with the
// couples of the turning normals (contact.cpp), are the gradient of the
// energy it stores, checked by finite differences in the gear's static
// check; and that energy goes only where the overlap goes.
//
// The static check at coarse flanks (fine spacing 0.48 mm, so the flanks'
// particles are 0.72 mm apart) placed at the HPSTC: a rack flank particle
// beside the root fillet is slightly concave there, and the early rejection
// of pairs that are apart once dropped a pair that still overlapped
// (contact_surface.hpp, curved_surface_pair). The balance lost 2.8e-4 J/m
// at step 77 and gained 2.4e-3 J/m at step 82, and the health check stopped
// the run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "solver/diagnostics/energy.hpp"
#include "solver/integrate/integrator.hpp"
#include "solver/job/job.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph {
namespace {

Simulation coarse_flank_check() {
  const nlohmann::json job = {{"scene",
                               {{"type", "rack_pinion"},
                                {"quasi_static", true},
                                {"contact_point", 26.209},
                                {"pinion", {{"omega_rad_s", 0.0}}},
                                {"rack", {{"load_N", 1000.0}, {"velocity_m_s", 0.0}}}}},
                              {"discretization", {{"fine_spacing_m", 0.48e-3}}}};
  PreparedJob prepared = prepare_job(job, 1);
  Simulation sim = prepared.scene.sim;
  sim.threads = 1;
  return sim;
}

TEST(ContactEnergy, ForcesAreTheGradientOfTheStoredEnergyAndItGoesOnlyWithTheOverlap) {
  Simulation sim = coarse_flank_check();
  integrate::initialise(sim);
  // Placed touching; the rack's load presses the flanks into each other
  // within some 420 steps.
  for (int s = 0; s < 1000 && !(diagnostics::energy(sim).contact > 0.0); ++s) integrate::step(sim);
  const double start = diagnostics::energy(sim).total();
  ASSERT_GT(diagnostics::energy(sim).contact, 0.0);
  double drift = 0.0;
  for (int s = 0; s < 120; ++s) {
    integrate::step(sim);
    drift = std::max(drift, std::abs(diagnostics::energy(sim).total() - start));
  }
  // The balance holds to round-off and the step's own error.
  EXPECT_LT(drift, 1e-5) << "energy balance drift, J/m";

  // The contact forces alone, and the energy they come from, at the present
  // positions.
  Particles& p = sim.particles;
  auto contact_energy = [&] {
    std::fill(p.ext_ax.begin(), p.ext_ax.end(), 0.0);
    std::fill(p.ext_ay.begin(), p.ext_ay.end(), 0.0);
    physics::contact_forces(sim, sim.dt);
    return sim.contact_state.stored_energy;
  };
  ASSERT_GT(contact_energy(), 0.0);
  std::vector<double> fx(p.n), fy(p.n);
  double largest = 0.0;
  for (std::size_t k = 0; k < p.n; ++k) {
    fx[k] = p.mass[k] * p.ext_ax[k];
    fy[k] = p.mass[k] * p.ext_ay[k];
    largest = std::max(largest, std::hypot(fx[k], fy[k]));
  }
  ASSERT_GT(largest, 0.0);
  const double eps = 1e-10;  // m: a ten-thousandth of the overlap
  int checked = 0;
  for (std::size_t k = 0; k < p.n; ++k) {
    if (std::hypot(fx[k], fy[k]) < 1e-4 * largest) continue;
    double gradient[2];
    for (int d = 0; d < 2; ++d) {
      double& c = d ? p.y[k] : p.x[k];
      const double c0 = c;
      c = c0 + eps;
      const double up = contact_energy();
      c = c0 - eps;
      const double down = contact_energy();
      c = c0;
      gradient[d] = -(up - down) / (2.0 * eps);
    }
    EXPECT_NEAR(gradient[0], fx[k], 1e-6 * largest) << "particle " << k;
    EXPECT_NEAR(gradient[1], fy[k], 1e-6 * largest) << "particle " << k;
    ++checked;
  }
  // The particles the force is spread over, on both bodies.
  EXPECT_GT(checked, 10);
}

}  // namespace
}  // namespace gearsph
