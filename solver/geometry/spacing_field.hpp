#pragma once
// A particle spacing that is fine where the stress varies and coarse where
// it does not, graded smoothly in between:
//
//   s(x) = min(s_coarse, min_k (s_k + g d_k(x)))
//
// with d_k the distance to the k-th fine feature (a polyline: a fillet, an
// active flank, the rim of a hole) and g the grading, the growth of the
// spacing per unit distance. With g = 0.25 neighbouring particles differ in
// spacing by at most 25 %, and a 4:1 grading takes about 12 fine spacings.
// s is 1-Lipschitz times g, so a smoothing length h = kappa s varies slowly
// over any kernel support.
#include <memory>
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

class SpacingField {
 public:
  // Uniform spacing s everywhere.
  explicit SpacingField(double coarse, double grading = 0.25);
  ~SpacingField();
  SpacingField(SpacingField&&) noexcept;
  SpacingField& operator=(SpacingField&&) noexcept;

  // Spacing `spacing` on the polyline (closed: the last vertex joins the first).
  void add_feature(const std::vector<Point>& line, double spacing, bool closed = false);

  double operator()(Point p) const;
  double coarse() const { return coarse_; }
  double grading() const { return grading_; }
  // The smallest spacing anywhere (the finest feature's, or the coarse one).
  double finest() const { return finest_; }

 private:
  struct Index;  // segments of the features in an R-tree
  double coarse_;
  double grading_;
  double finest_;
  std::unique_ptr<Index> index_;
};

}  // namespace gearsph::geometry
