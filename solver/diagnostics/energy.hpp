#pragma once
// Conservation diagnostics: kinetic and elastic energy, momentum.
// Energies per metre of thickness [J/m]; momentum [kg m/s per m].
#include <vector>

namespace gearsph {
struct Simulation;
namespace diagnostics {

struct EnergyState {
  double kinetic = 0.0;
  double elastic = 0.0;  // strain energy of the stress state
  double contact = 0.0;  // penalty energy stored in contact pairs
  double dissipated = 0.0;
  double drive_work = 0.0;
  double external_work = 0.0;
  // kinetic + elastic + contact + dissipated - drive work - external work: constant
  // for an exact integrator.
  double total() const {
    return kinetic + elastic + contact + dissipated - drive_work - external_work;
  }
};

EnergyState energy(const Simulation& sim);

struct Momentum {
  double px = 0.0, py = 0.0;
};
// Total momentum of one body's particles (or of all, body = -1).
Momentum momentum(const Simulation& sim, int body = -1);

struct StressPeak {
  double von_mises = 0.0;  // [Pa]
  long particle = -1;
};
StressPeak max_von_mises(const Simulation& sim, int body = -1);

}  // namespace diagnostics
}  // namespace gearsph
