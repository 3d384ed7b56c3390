#pragma once
// The numerical method of a run: formulation, kernel, and the optional terms.
// Defaults here are the library's; the job schema documents the user-facing
// defaults and ranges (schemas/job.schema.json), which the job reader applies.
#include <string>

#include "solver/kernels/kernel.hpp"

namespace gearsph {

enum class Formulation { UpdatedLagrangian, TotalLagrangian };

// The order of the kernel-gradient correction (physics/kernel_correction.hpp).
enum class GradientCorrection { None, Linear, Quadratic };

const char* gradient_correction_name(GradientCorrection c);

// How a scene places its particles: on a square lattice (cell centres
// inside the outline, a staircase along curves), or body-fitted (a row on
// the true outline and a relaxed interior, geometry/body_fitted.hpp), which
// may be graded from a fine spacing at the scene's stress raisers to dx.
enum class ParticleLayout { SceneDefault, Lattice, BodyFitted };

struct Discretization {
  double dx = 1e-3;        // lattice spacing, or the bulk spacing of body-fitted particles [m]
  double h_over_dx = 1.0;  // smoothing length h = kappa dx (per particle: kappa times its spacing)
  KernelType kernel = KernelType::SeedQuartic;
  ParticleLayout layout = ParticleLayout::SceneDefault;
  double fine_dx = 0.0;  // body-fitted: spacing at the stress raisers [m] (0: the scene's default)
  double grading = 0.0;  // body-fitted: growth of the spacing per unit distance (0: default)
  // body-fitted static gear checks: spacing at tooth 0's contact, to
  // resolve its Hertz pressure [m] (0: the scene's choice)
  double contact_dx = 0.0;
  double h() const { return h_over_dx * dx; }
};

// Monaghan artificial viscosity (Monaghan 1992, eq. 4.1); the seed paper's Pi_ij.
struct ArtificialViscosity {
  double alpha = 1.0;
  double beta = 1.0;
  double eta_over_h = 0.1;  // eta = 0.1 h keeps phi finite as r -> 0
};

// Monaghan 2000 / Gray, Monaghan & Swift 2001 artificial stress against the
// tensile instability; epsilon = 0 switches it off.
struct ArtificialStress {
  double epsilon = 0.3;
  int n = 4;
  bool enabled() const { return epsilon > 0.0; }
};

// Hourglass (zero-energy mode) control; coefficient 0 switches it off.
// TL: Ganzenmueller 2015 penalty on the non-affine pair stretch.
// UL: damping of the non-affine part of the pair approach speed.
struct HourglassControl {
  double coefficient = 0.0;
  bool enabled() const { return coefficient > 0.0; }
};

struct MethodConfig {
  Formulation formulation = Formulation::UpdatedLagrangian;
  GradientCorrection correction = GradientCorrection::Quadratic;
  ArtificialViscosity viscosity;
  ArtificialStress artificial_stress;
  HourglassControl hourglass;
};

const char* formulation_name(Formulation f);

}  // namespace gearsph
