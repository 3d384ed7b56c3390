#include "solver/neighbours/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace gearsph {

void CellGrid::build(const double* x, const double* y, std::size_t n, double cell_size) {
  if (n == 0) {
    nx_ = ny_ = 0;
    start_.assign(1, 0);
    members_.clear();
    return;
  }
  double x_max = x[0], y_max = y[0];
  x_min_ = x[0];
  y_min_ = y[0];
  for (std::size_t i = 1; i < n; ++i) {
    x_min_ = std::min(x_min_, x[i]);
    x_max = std::max(x_max, x[i]);
    y_min_ = std::min(y_min_, y[i]);
    y_max = std::max(y_max, y[i]);
  }
  inv_size_ = 1.0 / cell_size;
  const double cells_x = std::floor((x_max - x_min_) * inv_size_) + 1.0;
  const double cells_y = std::floor((y_max - y_min_) * inv_size_) + 1.0;
  // A guard against a scene spread over an absurd area (a particle escaped):
  // the divergence guard normally stops the run before this.
  if (cells_x * cells_y > 5e8) throw std::runtime_error("neighbour grid: particles spread too far");
  nx_ = static_cast<int>(cells_x);
  ny_ = static_cast<int>(cells_y);
  const std::size_t n_cells = static_cast<std::size_t>(nx_) * ny_;

  start_.assign(n_cells + 1, 0);
  cell_of_.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t c =
        static_cast<std::size_t>(cell_coord(y[i], y_min_)) * nx_ + cell_coord(x[i], x_min_);
    cell_of_[i] = static_cast<std::uint32_t>(c);
    ++start_[c + 1];
  }
  for (std::size_t c = 0; c < n_cells; ++c) start_[c + 1] += start_[c];
  members_.resize(n);
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) members_[fill[cell_of_[i]]++] = static_cast<std::uint32_t>(i);
}

}  // namespace gearsph
