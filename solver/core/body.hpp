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
  // The contact's spread reaches smoothing_spacings times a particle's
  // spacing times this (contact_smoothing.hpp): a scene whose geometry sets
  // the spacing gives the ratio of its own choice to a finer one the job
  // asked for, so that refining puts more particles across a spread of the
  // same width and the contact's error falls with the spacing
  // (docs/contact.md, "The spread keeps its width on finer particles").
  double contact_spread_scale = 1.0;
  std::size_t count() const { return end - begin; }
};

}  // namespace gearsph
