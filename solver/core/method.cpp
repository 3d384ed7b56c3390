#include "solver/core/method.hpp"

namespace gearsph {

const char* formulation_name(Formulation f) {
  return f == Formulation::TotalLagrangian ? "total_lagrangian" : "updated_lagrangian";
}

}  // namespace gearsph
