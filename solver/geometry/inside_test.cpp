// The banded edge table behind InsideTest (polygon.hpp): the ring's
// non-horizontal edges are listed in every horizontal band they overlap, so a
// query only visits the few edges near its height.
#include <algorithm>
#include <cmath>

#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

namespace {
// About four edges per band keeps the table small and the bands short.
constexpr std::size_t kEdgesPerBand = 4;
constexpr std::size_t kMaxBands = 1u << 16;
}  // namespace

InsideTest::InsideTest(const Polygon& poly) : box_(bounding_box(poly)) {
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) {
    const Point a = poly[i], b = poly[(i + 1) % n];
    if (a.y == b.y) continue;  // never counted by edge_crossing
    edges_.push_back(a.y < b.y ? Edge{a, b} : Edge{b, a});
  }
  const std::size_t bands = std::clamp<std::size_t>(edges_.size() / kEdgesPerBand, 1, kMaxBands);
  const double height = box_.hi.y - box_.lo.y;
  band_height_ = height > 0.0 ? height / static_cast<double>(bands) : 1.0;
  band_start_.assign(bands + 1, 0);
  for (const Edge& e : edges_) {
    for (std::size_t b = band_of(e.lo.y), last = band_of(e.hi.y); b <= last; ++b)
      ++band_start_[b + 1];
  }
  for (std::size_t b = 0; b < bands; ++b) band_start_[b + 1] += band_start_[b];
  band_edges_.resize(band_start_[bands]);
  std::vector<std::size_t> fill(band_start_.begin(), band_start_.end() - 1);
  for (std::size_t i = 0; i < edges_.size(); ++i) {
    for (std::size_t b = band_of(edges_[i].lo.y), last = band_of(edges_[i].hi.y); b <= last; ++b) {
      band_edges_[fill[b]++] = static_cast<std::uint32_t>(i);
    }
  }
}

std::size_t InsideTest::band_of(double y) const {
  const double f = std::floor((y - box_.lo.y) / band_height_);
  const double last = static_cast<double>(band_start_.size() - 2);
  return static_cast<std::size_t>(std::clamp(f, 0.0, last));
}

void InsideTest::crossings(double y, std::vector<double>& out) const {
  out.clear();
  if (!(y >= box_.lo.y && y < box_.hi.y)) return;
  const std::size_t b = band_of(y);
  double xc = 0.0;
  for (std::size_t k = band_start_[b]; k < band_start_[b + 1]; ++k) {
    const Edge& e = edges_[band_edges_[k]];
    if (edge_crossing(e.lo, e.hi, y, xc)) out.push_back(xc);
  }
}

bool InsideTest::operator()(Point p) const {
  if (p.x < box_.lo.x || p.x > box_.hi.x || !(p.y >= box_.lo.y && p.y < box_.hi.y)) return false;
  const std::size_t b = band_of(p.y);
  bool inside = false;
  double xc = 0.0;
  for (std::size_t k = band_start_[b]; k < band_start_[b + 1]; ++k) {
    const Edge& e = edges_[band_edges_[k]];
    if (edge_crossing(e.lo, e.hi, p.y, xc) && xc > p.x) inside = !inside;
  }
  return inside;
}

}  // namespace gearsph::geometry
