#pragma once
#include <cstddef>
#include <string>

#include "solver/core/material.hpp"

namespace gearsph {

// One elastic body: a contiguous range of particles with one material.
struct Body {
  std::string name;
  Material material;
  std::size_t begin = 0, end = 0;  // particle index range [begin, end)
  // Body-fitted particles (geometry/body_fitted.hpp): a row of them lies on
  // the outline, and it alone carries the surface for contact.
  bool fitted = false;
  std::size_t count() const { return end - begin; }
};

}  // namespace gearsph
