#include "solver/geometry/voronoi_cells.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

// GCC 12 at -O3 warns "may be used uninitialized" inside Boost.Geometry's
// envelope and rescaling templates as they inline into the clipping loop
// (false positives: the boxes are assigned before use). Silenced for this
// file only, where those templates are instantiated.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/geometry.hpp>
#include <boost/geometry/index/rtree.hpp>
#include <boost/polygon/voronoi.hpp>

#include "solver/core/passes.hpp"

namespace gearsph::geometry {

namespace bg = boost::geometry;
namespace bgi = boost::geometry::index;
namespace bpl = boost::polygon;

namespace {

using BPoint = bg::model::d2::point_xy<double>;
using BPoly = bg::model::polygon<BPoint, /*ClockWise=*/false, /*Closed=*/true>;
using BMulti = bg::model::multi_polygon<BPoly>;
using BBox = bg::model::box<BPoint>;
using BSegment = bg::model::segment<BPoint>;

// Input points live on a grid of 2^29 steps across the region's extent;
// the four guard points at 2^30 beyond put every real point strictly inside
// the diagram's convex hull, so every real cell is bounded.
constexpr double kGridSteps = 536870912.0;  // 2^29
constexpr std::int32_t kGuard = 1 << 30;

// Zeroth and first moments of the density over a ring, by a fan of signed
// triangles from its first vertex, each with the edge-midpoint rule (exact
// for quadratic densities; signs make it right for any simple ring).
struct Moments {
  double m = 0.0, mx = 0.0, my = 0.0, area = 0.0;
  void add_ring(const std::vector<Point>& ring, const std::function<double(Point)>& density) {
    const std::size_t n = ring.size();
    if (n < 3) return;
    const Point a = ring[0];
    for (std::size_t k = 1; k + 1 < n; ++k) {
      const Point b = ring[k], c = ring[k + 1];
      const double A = 0.5 * cross(b - a, c - a);
      area += A;
      if (!density) {
        m += A;
        mx += A * (a.x + b.x + c.x) / 3.0;
        my += A * (a.y + b.y + c.y) / 3.0;
        continue;
      }
      for (const Point q : {0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a)}) {
        const double w = density(q) * A / 3.0;
        m += w;
        mx += w * q.x;
        my += w * q.y;
      }
    }
  }
};

std::vector<Point> ring_points(const BPoly::ring_type& r) {
  std::vector<Point> out;
  for (std::size_t k = 0; k + 1 < r.size(); ++k) out.push_back({r[k].x(), r[k].y()});  // closed
  return out;
}

}  // namespace

struct ClippedVoronoi::Impl {
  BPoly domain;
  std::vector<InsideTest> inside;  // outer ring first, then holes
  bgi::rtree<BSegment, bgi::quadratic<16>> outline;
  Point origin;
  double step = 1.0;  // grid step of the snapped input
  double tile = 1.0;
  long nx = 0, ny = 0;
  std::vector<BMulti> tiles;  // row-major, region cut by each tile's box

  bool contains(Point p) const {
    if (!inside[0](p)) return false;
    for (std::size_t k = 1; k < inside.size(); ++k) {
      if (inside[k](p)) return false;
    }
    return true;
  }
  double distance(Point p) const {
    const BPoint q(p.x, p.y);
    double d = 1e300;
    for (auto it = outline.qbegin(bgi::nearest(q, 1)); it != outline.qend(); ++it) {
      d = bg::distance(q, *it);
    }
    return d;
  }
};

ClippedVoronoi::ClippedVoronoi(const Region& region, double tile)
    : impl_(std::make_unique<Impl>()) {
  Impl& I = *impl_;
  if (region.outer.size() < 3) throw std::invalid_argument("voronoi: region without an outline");
  if (!(tile > 0.0)) throw std::invalid_argument("voronoi: the tile size must be positive");
  for (const Polygon* ring : region.rings()) {
    I.inside.emplace_back(*ring);
    const std::size_t n = ring->size();
    for (std::size_t k = 0; k < n; ++k) {
      const Point a = (*ring)[k], b = (*ring)[(k + 1) % n];
      I.outline.insert(BSegment({a.x, a.y}, {b.x, b.y}));
    }
  }
  auto to_ring = [](const Polygon& p, BPoly::ring_type& r) {
    for (const Point& q : p) r.push_back({q.x, q.y});
    r.push_back({p.front().x, p.front().y});
  };
  to_ring(region.outer, I.domain.outer());
  for (const Polygon& h : region.holes) {
    I.domain.inners().emplace_back();
    to_ring(h, I.domain.inners().back());
  }
  bg::correct(I.domain);

  const Box box = bounding_box(region.outer);
  const double extent = std::max(box.hi.x - box.lo.x, box.hi.y - box.lo.y);
  I.origin = box.lo;
  I.step = extent / kGridSteps;
  I.tile = tile;
  I.nx = std::max(1L, static_cast<long>(std::ceil((box.hi.x - box.lo.x) / tile)));
  I.ny = std::max(1L, static_cast<long>(std::ceil((box.hi.y - box.lo.y) / tile)));
  I.tiles.resize(static_cast<std::size_t>(I.nx * I.ny));
  // The boxes share their edges: the pieces partition the region.
  auto edge_x = [&](long k) { return box.lo.x + static_cast<double>(k) * tile; };
  auto edge_y = [&](long k) { return box.lo.y + static_cast<double>(k) * tile; };
  auto clip_tile = [&](std::size_t t) {
    const long tx = static_cast<long>(t) % I.nx, ty = static_cast<long>(t) / I.nx;
    const BBox b({edge_x(tx), edge_y(ty)}, {edge_x(tx + 1), edge_y(ty + 1)});
    BMulti piece;
    bg::intersection(I.domain, b, piece);
    I.tiles[t] = std::move(piece);
  };
  over_blocks("clip the region to tiles", I.tiles.size(), 1, available_threads(), clip_tile);
}

ClippedVoronoi::~ClippedVoronoi() = default;

double ClippedVoronoi::distance_to_outline(Point p) const {
  return impl_->distance(p);
}

bool ClippedVoronoi::contains(Point p) const {
  return impl_->contains(p);
}

std::vector<ClippedVoronoi::Cell> ClippedVoronoi::cells(
    const std::vector<Point>& points, const std::function<double(Point)>& density) const {
  const Impl& I = *impl_;
  const std::size_t n = points.size();
  std::vector<bpl::point_data<std::int32_t>> input;
  input.reserve(n + 4);
  for (const Point& p : points) {
    const double gx = std::round((p.x - I.origin.x) / I.step);
    const double gy = std::round((p.y - I.origin.y) / I.step);
    if (!(gx >= -kGridSteps && gx <= 2 * kGridSteps && gy >= -kGridSteps && gy <= 2 * kGridSteps)) {
      throw std::invalid_argument("voronoi: a point lies far outside the region");
    }
    input.emplace_back(static_cast<std::int32_t>(gx), static_cast<std::int32_t>(gy));
  }
  const std::int32_t lo = -kGuard, hi = static_cast<std::int32_t>(kGridSteps) + kGuard;
  for (auto [gx, gy] : {std::pair{lo, lo}, {hi, lo}, {hi, hi}, {lo, hi}})
    input.emplace_back(gx, gy);
  bpl::voronoi_diagram<double> vd;
  bpl::construct_voronoi(input.begin(), input.end(), &vd);

  // Each input point's cell (duplicates share one cell and are refused).
  std::vector<const bpl::voronoi_diagram<double>::cell_type*> cell_of(n, nullptr);
  for (const auto& c : vd.cells()) {
    if (c.source_index() < n) cell_of[c.source_index()] = &c;
  }
  for (std::size_t i = 0; i < n; ++i) {
    if (!cell_of[i]) throw std::invalid_argument("voronoi: two points coincide");
  }

  std::vector<Cell> out(n);
  // A cell by the outline is clipped, one inside is not: blocks as threads come free.
  over_blocks("clip the Voronoi cells", n, 64, available_threads(), [&](std::size_t i) {
    std::vector<Point> poly;
    const auto* e0 = cell_of[i]->incident_edge();
    const auto* e = e0;
    do {
      if (!e->vertex0()) throw std::logic_error("voronoi: an unbounded cell");
      poly.push_back(
          {I.origin.x + e->vertex0()->x() * I.step, I.origin.y + e->vertex0()->y() * I.step});
      e = e->next();
    } while (e != e0);
    const Point g = points[i];
    double reach = 0.0;
    for (const Point& q : poly) reach = std::max(reach, norm(q - g));
    Moments mom;
    if (I.distance(g) > reach && I.contains(g)) {
      mom.add_ring(poly, density);  // wholly inside: no clipping
    } else {
      BPoly cell;
      for (const Point& q : poly) cell.outer().push_back({q.x, q.y});
      cell.outer().push_back({poly.front().x, poly.front().y});
      bg::correct(cell);
      Box b = bounding_box(poly);
      const long tx0 = std::max(0L, static_cast<long>(std::floor((b.lo.x - I.origin.x) / I.tile)));
      const long ty0 = std::max(0L, static_cast<long>(std::floor((b.lo.y - I.origin.y) / I.tile)));
      const long tx1 =
          std::min(I.nx - 1, static_cast<long>(std::floor((b.hi.x - I.origin.x) / I.tile)));
      const long ty1 =
          std::min(I.ny - 1, static_cast<long>(std::floor((b.hi.y - I.origin.y) / I.tile)));
      for (long ty = ty0; ty <= ty1; ++ty) {
        for (long tx = tx0; tx <= tx1; ++tx) {
          const BMulti& piece = I.tiles[static_cast<std::size_t>(ty * I.nx + tx)];
          if (piece.empty()) continue;
          BMulti clipped;
          bg::intersection(cell, piece, clipped);
          for (const BPoly& part : clipped) {
            mom.add_ring(ring_points(part.outer()), density);
            for (const auto& inner : part.inners()) mom.add_ring(ring_points(inner), density);
          }
        }
      }
    }
    out[i].area = mom.area;
    out[i].centroid = mom.m > 0.0 ? Point{mom.mx / mom.m, mom.my / mom.m} : g;
  });
  return out;
}

}  // namespace gearsph::geometry
