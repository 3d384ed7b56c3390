#pragma once
// Uniform cell grid over the particles' bounding box: particles are binned by
// a counting sort, so each cell's members are contiguous in `members`.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace gearsph {

class CellGrid {
 public:
  // Bins n points with cell edge `cell_size` (at least the interaction cutoff).
  void build(const double* x, const double* y, std::size_t n, double cell_size);

  // Calls fn(j) for every point in the 3x3 block of cells around (px, py).
  template <class Fn>
  void for_each_near(double px, double py, Fn&& fn) const {
    const int cx = cell_coord(px, x_min_), cy = cell_coord(py, y_min_);
    for (int dy = -1; dy <= 1; ++dy) {
      const int yy = cy + dy;
      if (yy < 0 || yy >= ny_) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        const int xx = cx + dx;
        if (xx < 0 || xx >= nx_) continue;
        const std::size_t c = static_cast<std::size_t>(yy) * nx_ + xx;
        for (std::uint32_t k = start_[c]; k < start_[c + 1]; ++k) fn(members_[k]);
      }
    }
  }

 private:
  int cell_coord(double v, double lo) const { return static_cast<int>((v - lo) * inv_size_); }

  double x_min_ = 0, y_min_ = 0, inv_size_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<std::uint32_t> start_;    // nx*ny + 1 offsets into members_
  std::vector<std::uint32_t> members_;  // point indices, grouped by cell
  std::vector<std::uint32_t> cell_of_;  // scratch
};

}  // namespace gearsph
