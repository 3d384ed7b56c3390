#include "solver/integrate/integrator.hpp"

#include <malloc.h>

#include <algorithm>
#include <cmath>

#include "solver/integrate/step_passes.hpp"
#include "solver/physics/contact.hpp"
#include "solver/physics/crack_face_contact.hpp"
#include "solver/physics/external_loads.hpp"
#include "solver/physics/momentum.hpp"
#include "solver/physics/simulation.hpp"
#include "solver/physics/stress_rate.hpp"
#include "solver/physics/total_lagrangian.hpp"
#include "solver/physics/velocity_gradient.hpp"

namespace gearsph::integrate {

// The tables themselves (step_total_lagrangian.cpp, step_updated_lagrangian.cpp).
void total_lagrangian_step(Simulation& sim, bool apart);
void updated_lagrangian_step(Simulation& sim, bool apart);

namespace {

// Verlet skin: a tenth of the spacing lasts thousands of steps.
constexpr double kSkinOverDx = 0.1;

bool total_lagrangian(const Simulation& sim) {
  return sim.method.formulation == Formulation::TotalLagrangian;
}

// How far apart two contact candidates may be. Lattice surfaces reach 1.5
// spacings into each body, plus the hat's spacing across; body-fitted
// surfaces are their outline rows (depth 0), so twice the coarsest spacing
// of a surface particle covers the hat and a slanted approach.
double contact_reach(const Simulation& sim) {
  const double dx = sim.discretization.dx;
  if (sim.contact.model != ContactModel::Surface) return sim.contact.r0_over_dx * dx;
  const bool fitted =
      std::any_of(sim.bodies.begin(), sim.bodies.end(), [](const Body& b) { return b.fitted; });
  if (!fitted) return (2.0 * kSurfaceReachOverDx + 1.0) * dx;
  const Particles& p = sim.particles;
  double reach = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (std::isfinite(p.surf_depth[i]))
      reach = std::max(reach, 2.0 * (p.surf_depth[i] + p.spacing[i]));
  }
  return reach;
}

// Rates and accelerations at t = 0, stress unchanged, each term over the
// whole set of particles (the tables start from these).
void first_forces(Simulation& sim) {
  if (total_lagrangian(sim)) {
    physics::total_lagrangian_forces(sim, 0.0);
  } else {
    physics::velocity_gradient(sim, 0.0);
    physics::update_stress(sim, 0.0);
    physics::momentum(sim, 0.0);
  }
  Particles& p = sim.particles;
  const double damping = sim.damping_1_s, ramp = physics::load_ramp(sim);
  sim.energy.dissipated += over_shares<double>(
      "external forces", p.n, sim.threads, [&](std::size_t lo, std::size_t hi, double& s) {
        s += physics::external_accelerations(p, lo, hi, ramp, damping, 0.0, false);
      });
  if (penalty_contact(sim)) physics::contact_forces(sim, 0.0);  // adds to ext
  if (total_lagrangian(sim)) physics::crack_face_contact(sim);  // adds to ext
}

}  // namespace

bool penalty_contact(const Simulation& sim) {
  return sim.bodies.size() > 1 && physics::is_penalty(sim.contact.model);
}

std::size_t contacts_moved(const Simulation& sim, std::size_t lo, std::size_t hi) {
  if (!sim.contacts.built_for(sim.particles.n)) return 0;
  return sim.contacts.moved_too_far(lo, hi, sim.particles.x.data(), sim.particles.y.data());
}

void refresh_contacts(Simulation& sim, bool moved) {
  if (!penalty_contact(sim) || (!moved && sim.contacts.built_for(sim.particles.n))) return;
  const double skin = kSkinOverDx * sim.discretization.dx;
  sim.contacts.set_skin(skin);
  const double reach = contact_reach(sim);
  sim.contacts.build(sim.particles, reach + skin, PairSelection::OtherBody,
                     /*reference=*/false, sim.threads, physics::contact_eligible(sim));
  physics::prepare_contact(sim);  // normals' scratch and candidates, before any stress pass
}

void refresh_neighbours(Simulation& sim, bool moved) {
  if (!total_lagrangian(sim) &&
      (sim.neighbours.builds() == 0 || sim.neighbours.needs_rebuild(sim.particles))) {
    // Kernel interactions stay inside a body unless the contact model is the
    // kernel itself (the coupling whose adhesion the seed paper avoids).
    const PairSelection selection = sim.contact.model == ContactModel::Kernel
                                        ? PairSelection::AnyBody
                                        : PairSelection::SameBody;
    const double skin = kSkinOverDx * sim.discretization.dx;
    const double radius = kernel_support(sim.discretization.kernel) * sim.h();
    sim.neighbours.set_skin(skin);
    sim.neighbours.build(sim.particles, radius + skin, selection, /*reference=*/false, sim.threads);
  }
  refresh_contacts(sim, moved);
}

void initialise(Simulation& sim) {
  if (total_lagrangian(sim)) {
    physics::total_lagrangian_setup(sim);        // keeps the pairs the stable-step estimate built
    sim.particles.release_updated_lagrangian();  // this run never takes a UL step
  }
  refresh_neighbours(sim, sim.contacts.needs_rebuild(sim.particles));
  first_forces(sim);
  // The setup's temporaries (moment matrices, the stable-step estimate's
  // vectors) went back to the heap in pieces the allocator keeps;
  // return them to the system, so that a long run holds only what it uses
  // (~22 % of the resident memory at 1e6 particles; docs/speed-accuracy-history.md).
  malloc_trim(0);
}

void step(Simulation& sim) {
  if (total_lagrangian(sim)) {
    total_lagrangian_step(sim, false);
  } else {
    updated_lagrangian_step(sim, false);
  }
}

void step_by_terms(Simulation& sim) {
  if (total_lagrangian(sim)) {
    total_lagrangian_step(sim, true);
  } else {
    updated_lagrangian_step(sim, true);
  }
}

}  // namespace gearsph::integrate
