#pragma once
// The root of every modelled pinion tooth, read where gears break: the
// stress recovered on the tooth's true fillets (gear/fillet.hpp,
// diagnostics/stress_recovery.hpp) and across ISO 6336-3's critical section
// (the chord between the two 30-degree points), at any step of a run.
//
// Fillet curves and section are in reference coordinates; the stress is the
// Cauchy stress in the world, so the section's normal stress is taken along
// the tooth axis turned with the hub.
//
// Body-fitted fillets are read from their own stretch
// (diagnostics/edge_stress.hpp): on the traction-free fillet sigma_tt =
// E/(1 - nu^2) eps_tt, with eps_tt the stretch of the recovered displacements
// along the curve, blind to the pinion's rotation. A fit of the stress
// tensor at the same points reads the peak lower and moves with the
// particles' arrangement by several percent (docs/gears.md); it is kept
// beside it (`fillet_stress_fit`). A lattice has no particles on the curve,
// only a staircase a spacing off it, and no stretch of its own to read: its
// fillets are read by the stress fit.
#include <cstdint>
#include <memory>
#include <vector>

#include "solver/diagnostics/stress_recovery.hpp"
#include "solver/gear/fillet.hpp"

namespace gearsph::scenes {

struct ToothRootState {
  gear::FilletStress fillet;  // tension / compression fillet peaks and curves, from the stretch
  gear::FilletStress fillet_stress_fit;  // the same from the recovered stress tensor
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
  // `fillets` per modelled tooth (in the order of `teeth`), with reach at
  // both ends of at least `window`, the half-width of the arc over which the
  // stretch is differentiated [m]; `hub_motion`: the motion whose angle
  // turns the pinion (its reference frame's rotation); `from_stretch`:
  // body-fitted particles, read by the stretch (else by the stress fit).
  RootMonitor(const Simulation& sim, int body, std::vector<int> teeth,
              std::vector<gear::ToothFillets> fillets, int hub_motion, double window,
              bool from_stretch);
  bool from_stretch() const { return from_stretch_; }

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
  // Per fillet: the curve with its reach (gear::with_reach) and its
  // recovery; the fillet's samples start at `first`.
  struct Edge {
    std::vector<geometry::Point> points;
    std::vector<double> arc;
    std::size_t first = 0;
    std::unique_ptr<diagnostics::StressRecovery> recovery;
  };
  std::vector<Edge> tension_, compression_;
  std::vector<std::unique_ptr<diagnostics::StressRecovery>> section_;
  int hub_motion_ = 0;
  double window_ = 0.0;
  bool from_stretch_ = true;
  double E_ = 0.0, nu_ = 0.0;
  mutable std::int64_t step_ = -1;
  mutable double time_ = -1.0;
  mutable std::vector<ToothRootState> state_;
};

}  // namespace gearsph::scenes
