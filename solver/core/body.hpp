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
  std::size_t count() const { return end - begin; }
};

}  // namespace gearsph
