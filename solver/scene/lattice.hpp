#pragma once
// Square-lattice particle placement: particles sit at cell centres, so a
// body of width W filled with spacing dx has its outer particles dx/2 inside
// the surface and the particle volumes tile the body exactly.
#include <cmath>
#include <cstddef>

namespace gearsph::lattice {

// Number of cells of size dx that fit a length (rounded to the nearest).
inline long cells(double length, double dx) {
  return std::lround(length / dx);
}

// Calls emit(x, y) for every cell centre of the rectangle [x0, x0 + nx dx] x
// [y0, y0 + ny dx], row by row (good memory locality for the pair loops).
template <class Emit>
void fill_rectangle(double x0, double y0, long nx, long ny, double dx, Emit&& emit) {
  for (long b = 0; b < ny; ++b) {
    for (long a = 0; a < nx; ++a) emit(x0 + (a + 0.5) * dx, y0 + (b + 0.5) * dx);
  }
}

// Calls emit(x, y) for every lattice point (cell centres of a grid anchored
// at (ox, oy)) inside the box that satisfies inside(x, y).
template <class Inside, class Emit>
void fill_region(double x_min, double y_min, double x_max, double y_max, double dx, double ox,
                 double oy, Inside&& inside, Emit&& emit) {
  const long a0 = static_cast<long>(std::floor((x_min - ox) / dx)) - 1;
  const long a1 = static_cast<long>(std::ceil((x_max - ox) / dx)) + 1;
  const long b0 = static_cast<long>(std::floor((y_min - oy) / dx)) - 1;
  const long b1 = static_cast<long>(std::ceil((y_max - oy) / dx)) + 1;
  for (long b = b0; b <= b1; ++b) {
    for (long a = a0; a <= a1; ++a) {
      const double x = ox + (a + 0.5) * dx, y = oy + (b + 0.5) * dx;
      if (x < x_min || x > x_max || y < y_min || y > y_max) continue;
      if (inside(x, y)) emit(x, y);
    }
  }
}

}  // namespace gearsph::lattice
