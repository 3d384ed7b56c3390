#include "solver/geometry/spacing_field.hpp"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>

#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>

namespace gearsph::geometry {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;

namespace {
using BPoint = bg::model::d2::point_xy<double>;
using BSegment = bg::model::segment<BPoint>;
using Tree = bgi::rtree<BSegment, bgi::quadratic<16>>;
}  // namespace

// One R-tree per distinct feature spacing: the nearest segment of each gives
// that group's candidate s_k + g d_k exactly (a farther feature of the same
// spacing can only give more).
struct SpacingField::Index {
  std::map<double, Tree> by_spacing;
};

SpacingField::SpacingField(double coarse, double grading)
    : coarse_(coarse), grading_(grading), finest_(coarse), index_(std::make_unique<Index>()) {
  if (!(coarse > 0.0)) throw std::invalid_argument("spacing field: the spacing must be positive");
  if (!(grading > 0.0)) throw std::invalid_argument("spacing field: the grading must be positive");
}

SpacingField::~SpacingField() = default;
SpacingField::SpacingField(SpacingField&&) noexcept = default;
SpacingField& SpacingField::operator=(SpacingField&&) noexcept = default;

void SpacingField::add_feature(const std::vector<Point>& line, double spacing, bool closed) {
  if (!(spacing > 0.0))
    throw std::invalid_argument("spacing field: feature spacing must be positive");
  if (line.empty()) return;
  Tree& tree = index_->by_spacing[spacing];
  const std::size_t n = line.size();
  if (n == 1) tree.insert(BSegment({line[0].x, line[0].y}, {line[0].x, line[0].y}));
  const std::size_t segments = closed ? n : n - 1;
  for (std::size_t i = 0; i < segments; ++i) {
    const Point a = line[i], b = line[(i + 1) % n];
    tree.insert(BSegment({a.x, a.y}, {b.x, b.y}));
  }
  finest_ = std::min(finest_, spacing);
}

double SpacingField::operator()(Point p) const {
  double s = std::numeric_limits<double>::infinity();
  const BPoint q(p.x, p.y);
  for (const auto& [spacing, tree] : index_->by_spacing) {
    if (spacing >= s) break;  // ascending: no later group can give less
    for (auto it = tree.qbegin(bgi::nearest(q, 1)); it != tree.qend(); ++it) {
      s = std::min(s, spacing + grading_ * bg::distance(q, *it));
    }
  }
  // The graded spacing meets the coarse one without a kink: a quadratic
  // smooth minimum over a band of width k, C1 and never above either.
  const double k = kSaturationBand * coarse_;
  const double gap = std::max(k - std::abs(s - coarse_), 0.0) / k;
  return std::min(s, coarse_) - 0.25 * k * gap * gap;
}

}  // namespace gearsph::geometry
