#pragma once
// The root of every modelled pinion tooth, read where gears break: the
// stress recovered on the tooth's true fillets (gear/fillet.hpp,
// diagnostics/stress_recovery.hpp) and across ISO 6336-3's critical section
// (the chord between the two 30-degree points), at any step of a run.
//
// Fillet curves and section are in reference coordinates; the stress is the
// Cauchy stress in the world, so the fillets are read by their principal
// stresses (invariant as the pinion turns) and the section's normal stress
// along the tooth axis turned with the hub.
#include <cstdint>
#include <memory>
#include <vector>

#include "solver/diagnostics/stress_recovery.hpp"
#include "solver/gear/fillet.hpp"

namespace gearsph::scenes {

struct ToothRootState {
  gear::FilletStress fillet;  // tension / compression fillet peaks and curves
  // The larger sigma_1 at the two 30-degree points (either flank may be
  // loaded: rattle in the backlash), the history's root_stress_t<k>_Pa.
  double root_stress_Pa = 0.0;
  // Across the critical section, per unit face width: normal force, bending
  // moment and the nominal bending stress 6 |M| / s_Fn^2 that ISO's Y_F
  // describes.
  double section_normal_force_N_per_m = 0.0;
  double section_bending_moment_N = 0.0;
  double section_nominal_bending_Pa = 0.0;
};

class RootMonitor {
 public:
  // `fillets` per modelled tooth (in the order of `teeth`); `hub_motion`:
  // the motion whose angle turns the pinion (its reference frame's rotation).
  RootMonitor(const Simulation& sim, int body, std::vector<int> teeth,
              std::vector<gear::ToothFillets> fillets, int hub_motion);

  const std::vector<int>& teeth() const { return teeth_; }
  const gear::ToothFillets& fillets(std::size_t t) const { return fillets_[t]; }
  double section_width(std::size_t t) const { return sections_[t].width; }
  // The state of every tooth at the simulation's present step (computed
  // once a step, whatever number of history columns ask).
  const std::vector<ToothRootState>& at(const Simulation& sim) const;

 private:
  struct Section {
    geometry::Point centre, along;  // reference chord: centre and unit direction
    double width = 0.0;
    std::vector<double> s;  // positions along the chord of the recovery points
  };
  std::vector<int> teeth_;
  std::vector<gear::ToothFillets> fillets_;
  std::vector<Section> sections_;
  std::vector<std::unique_ptr<diagnostics::StressRecovery>> tension_, compression_, section_;
  int hub_motion_ = 0;
  mutable std::int64_t step_ = -1;
  mutable double time_ = -1.0;
  mutable std::vector<ToothRootState> state_;
};

}  // namespace gearsph::scenes
