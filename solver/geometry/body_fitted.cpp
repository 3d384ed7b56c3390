#include "solver/geometry/body_fitted.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/core/setup_progress.hpp"
#include "solver/geometry/voronoi_cells.hpp"

namespace gearsph::geometry {

namespace {

constexpr double kPi = std::numbers::pi;

// Vertices of `ring` where it turns by more than `angle` (radians).
std::vector<std::size_t> corners(const Polygon& ring, double angle) {
  std::vector<std::size_t> out;
  const std::size_t n = ring.size();
  for (std::size_t k = 0; k < n; ++k) {
    const Point a = ring[(k + n - 1) % n], b = ring[k], c = ring[(k + 1) % n];
    const Point u = b - a, v = c - b;
    const double turn = std::atan2(std::abs(cross(u, v)), dot(u, v));
    if (turn > angle) out.push_back(k);
  }
  return out;
}

// The polyline with its long edges cut into pieces of at most a quarter of
// the smallest spacing at their ends and middle, so that a spacing graded
// along one straight edge (a rack flank refined at one point) is followed:
// over such a piece a g-Lipschitz spacing changes by g/4 at most.
std::vector<Point> split_for_spacing(const std::vector<Point>& line, const SpacingField& s) {
  std::vector<Point> out;
  if (line.empty()) return out;
  out.push_back(line.front());
  for (std::size_t k = 1; k < line.size(); ++k) {
    const Point a = line[k - 1], b = line[k];
    const double least = std::min({s(a), s(0.5 * (a + b)), s(b)});
    const auto pieces =
        std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(norm(b - a) / (0.25 * least))));
    for (std::size_t m = 1; m < pieces; ++m) {
      out.push_back(a + (static_cast<double>(m) / static_cast<double>(pieces)) * (b - a));
    }
    out.push_back(b);
  }
  return out;
}

// Points along the open polyline `given` at equal steps of tau = int dl / s,
// its first point included and its last excluded; at least `min_points`.
void sample_piece(const std::vector<Point>& given, const SpacingField& s, std::size_t min_points,
                  std::vector<Point>& out) {
  const std::vector<Point> line = split_for_spacing(given, s);
  std::vector<double> tau(line.size(), 0.0);
  for (std::size_t k = 1; k < line.size(); ++k) {
    const double len = norm(line[k] - line[k - 1]);
    tau[k] = tau[k - 1] + len / s(0.5 * (line[k] + line[k - 1]));
  }
  const std::size_t steps =
      std::max<std::size_t>(min_points, static_cast<std::size_t>(std::lround(tau.back())));
  std::size_t k = 1;
  for (std::size_t m = 0; m < steps; ++m) {
    const double t = tau.back() * static_cast<double>(m) / static_cast<double>(steps);
    while (k + 1 < line.size() && tau[k] < t) ++k;
    const double span = tau[k] - tau[k - 1];
    const double f = span > 0.0 ? std::clamp((t - tau[k - 1]) / span, 0.0, 1.0) : 0.0;
    out.push_back(line[k - 1] + f * (line[k] - line[k - 1]));
  }
}

// Step 2: one point per s^2 of leaf area, by error diffusion in the order of
// a depth-first walk of the quadtree (neighbouring leaves share the
// remainder), none outside or within half a spacing of the outline.
class QuadtreeFill {
 public:
  QuadtreeFill(const ClippedVoronoi& region, const SpacingField& s) : region_(region), s_(s) {}

  void visit(Point lo, double size, std::vector<Point>& out) {
    const Point centre{lo.x + 0.5 * size, lo.y + 0.5 * size};
    const double half_diagonal = std::numbers::sqrt2 * 0.5 * size;
    const double d = region_.distance_to_outline(centre);
    const bool inside = region_.contains(centre);
    if (!inside && d > half_diagonal) return;  // wholly outside
    const double s = s_(centre);
    if (size > s) {
      const double h = 0.5 * size;
      visit(lo, h, out);
      visit({lo.x + h, lo.y}, h, out);
      visit({lo.x, lo.y + h}, h, out);
      visit({lo.x + h, lo.y + h}, h, out);
      return;
    }
    if (!inside || d < 0.5 * s) return;
    carry_ += (size / s) * (size / s);
    if (carry_ >= 0.5) {
      out.push_back(centre);
      carry_ -= 1.0;
    }
  }

 private:
  const ClippedVoronoi& region_;
  const SpacingField& s_;
  double carry_ = 0.0;
};

}  // namespace

std::vector<Point> sample_outline(const Polygon& ring, const SpacingField& spacing,
                                  double corner_angle_deg) {
  std::vector<Point> out;
  const std::size_t n = ring.size();
  if (n < 3) throw std::invalid_argument("body-fitted particles: a ring needs three vertices");
  const std::vector<std::size_t> c = corners(ring, corner_angle_deg * kPi / 180.0);
  if (c.empty()) {
    std::vector<Point> line(ring.begin(), ring.end());
    line.push_back(ring.front());
    sample_piece(line, spacing, 3, out);
    return out;
  }
  for (std::size_t a = 0; a < c.size(); ++a) {
    const std::size_t from = c[a], to = c[(a + 1) % c.size()];
    std::vector<Point> line;
    for (std::size_t k = from;; k = (k + 1) % n) {
      line.push_back(ring[k]);
      if (k == to && line.size() > 1) break;
    }
    sample_piece(line, spacing, 1, out);
  }
  return out;
}

BodyFittedParticles fill_body_fitted(const Region& region, const SpacingField& spacing,
                                     const BodyFittedOptions& options) {
  const Box box = bounding_box(region.outer);
  const double extent = std::max(box.hi.x - box.lo.x, box.hi.y - box.lo.y);
  // Tiles a few coarse cells wide: each clip sees a short stretch of outline.
  const ClippedVoronoi voronoi(region, std::min(extent, 4.0 * spacing.coarse()));

  BodyFittedParticles out;
  for (const Polygon* ring : region.rings()) {
    for (const Point& p : sample_outline(*ring, spacing, options.corner_angle_deg)) {
      out.points.push_back(p);
      out.outline.push_back(1);
    }
  }
  const std::size_t n_outline = out.points.size();
  {
    std::vector<Point> inner;
    QuadtreeFill fill(voronoi, spacing);
    fill.visit(box.lo, extent * (1.0 + 1e-9), inner);
    for (const Point& p : inner) {
      out.points.push_back(p);
      out.outline.push_back(0);
    }
  }
  const std::size_t n = out.points.size();
  for (const Point& p : out.points) out.spacing.push_back(spacing(p));

  // Lloyd's iteration, density s^-4, outline row held.
  const std::function<double(Point)> density = [&spacing](Point p) {
    const double s = spacing(p);
    return 1.0 / (s * s * s * s);
  };
  for (int it = 0; it < options.max_iterations; ++it) {
    setup_progress("relaxing particles", double(it) / options.max_iterations);
    const std::vector<ClippedVoronoi::Cell> cells = voronoi.cells(out.points, density);
    double largest = 0.0;
    for (std::size_t i = n_outline; i < n; ++i) {
      const Point c = cells[i].centroid;
      // A clipped cell is not always convex: a centroid outside the body, or
      // on its outline row's band, keeps the point where it was.
      if (!voronoi.contains(c) || voronoi.distance_to_outline(c) < 0.25 * out.spacing[i]) continue;
      largest = std::max(largest, norm(c - out.points[i]) / out.spacing[i]);
      out.points[i] = c;
      out.spacing[i] = spacing(c);
    }
    out.iterations = it + 1;
    out.last_move = largest;
    if (largest < options.tolerance) break;
  }
  for (const ClippedVoronoi::Cell& c : voronoi.cells(out.points)) out.volume.push_back(c.area);
  return out;
}

}  // namespace gearsph::geometry
