#include "solver/core/method.hpp"

namespace gearsph {

const char* formulation_name(Formulation f) {
  return f == Formulation::TotalLagrangian ? "total_lagrangian" : "updated_lagrangian";
}

const char* gradient_correction_name(GradientCorrection c) {
  switch (c) {
    case GradientCorrection::None:
      return "none";
    case GradientCorrection::Linear:
      return "linear";
    case GradientCorrection::Quadratic:
      break;
  }
  return "quadratic";
}

}  // namespace gearsph
