#include "solver/scene/surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"
#include "solver/physics/contact_surface.hpp"

namespace gearsph::scenes {

namespace {

// The largest turn between a chord of the outline and the curve it is drawn
// along (0.1 um from it: 18 mrad on a 2.4 mm fillet radius); a larger one is
// a corner.
constexpr double kChordTurnMax = 0.03;  // rad

// An outline's one-sided contact (Outline::contact_side) keeps the parts
// whose normal turns up to 10 degrees past square to the side: a tip land
// and the rounds beside it stay surfaces, a flank facing the other way
// (cos 14.5-25 degrees, 0.91-0.97, against the side) does not.
constexpr double kSideTolerance = 0.17;  // sin(10 degrees)

struct Closest {
  double distance = std::numeric_limits<double>::infinity();
  double nx = 0.0, ny = 0.0;  // outward normal
  std::size_t edge = 0;       // the closest point lies on edge (edge, edge + 1)
  double t = 0.0;             // at this fraction of it
};

// Closest point of segment (a, b) of a counter-clockwise outline to p, and
// the outward normal there: the edge normal on the open segment, the
// direction from p to the vertex at a corner (smooth across corners).
void closest_on_segment(const std::array<double, 2>& a, const std::array<double, 2>& b, double px,
                        double py, bool ccw, Closest& best) {
  const double ex = b[0] - a[0], ey = b[1] - a[1];
  const double len2 = ex * ex + ey * ey;
  if (len2 <= 0.0) return;
  const double t = std::clamp(((px - a[0]) * ex + (py - a[1]) * ey) / len2, 0.0, 1.0);
  const double qx = a[0] + t * ex, qy = a[1] + t * ey;
  const double d = std::hypot(px - qx, py - qy);
  if (d >= best.distance) return;
  best.distance = d;
  best.t = t;
  if ((t > 0.0 && t < 1.0) || d < 1e-12) {
    const double len = std::sqrt(len2);
    // Right-hand normal of a CCW edge points outward.
    best.nx = (ccw ? ey : -ey) / len;
    best.ny = (ccw ? -ex : ex) / len;
  } else {
    best.nx = (qx - px) / d;
    best.ny = (qy - py) / d;
  }
}

bool counter_clockwise(const Outline& o) {
  double area = 0.0;
  for (std::size_t k = 0; k < o.points.size(); ++k) {
    const auto& a = o.points[k];
    const auto& b = o.points[(k + 1) % o.points.size()];
    area += a[0] * b[1] - b[0] * a[1];
  }
  return area > 0.0;
}

// The outline's direction as a function of arc length, for curvatures
// averaged over a stretch: arc[k] is the arc length at vertex k (arc[m] the
// perimeter), angle[k] the direction of edge k unwrapped, counting turns
// toward the body's outside as convex.
struct Turning {
  static constexpr double kSmoothTurn = 10.0 * std::numbers::pi / 180.0;
  // A kink: a vertex that turns by more than half a degree and four times
  // as much as either neighbour (a smooth curve's chords turn alike), but
  // by less than the contact's corner (contact_surface.hpp, whose test reads
  // a corner's turn from the mean curvature). Where the paper's undercut
  // pinion's fillet cuts its involute the profile turns by 11 degrees at one
  // vertex; a curvature averaged across it was twice the involute's there,
  // and the parabola of the flank particle beside it missed the flank by
  // 11 um half a spacing away (docs/contact.md).
  static constexpr double kKinkTurn = 0.5 * std::numbers::pi / 180.0;
  static constexpr double kKinkOverNeighbours = 4.0;
  std::vector<double> arc, angle;
  std::vector<char> kink;        // per vertex k (between edges k - 1 and k)
  std::vector<double> kink_arc;  // their arc lengths, ascending
  // The arc lengths of the kinks and of the corners (a vertex turning by
  // the contact's corner or more), ascending: where a Hertz radius ends.
  std::vector<double> break_arc;
  double perimeter = 0.0, total_turn = 0.0;

  Turning(const Outline& o, bool ccw) {
    const std::size_t m = o.points.size();
    arc.assign(m + 1, 0.0);
    angle.assign(m, 0.0);
    for (std::size_t k = 0; k < m; ++k) {
      const auto& a = o.points[k];
      const auto& b = o.points[(k + 1) % m];
      arc[k + 1] = arc[k] + std::hypot(b[0] - a[0], b[1] - a[1]);
      double th = std::atan2(b[1] - a[1], b[0] - a[0]);
      if (!ccw) th = -th;  // a clockwise outline turns the other way
      if (k > 0) {
        while (th - angle[k - 1] > std::numbers::pi) th -= 2.0 * std::numbers::pi;
        while (th - angle[k - 1] < -std::numbers::pi) th += 2.0 * std::numbers::pi;
      }
      angle[k] = th;
    }
    perimeter = arc[m];
    total_turn = 2.0 * std::numbers::pi;  // a simple closed outline turns once
    std::vector<double> turn(m);
    for (std::size_t k = 0; k < m; ++k) {
      turn[k] = k > 0 ? angle[k] - angle[k - 1] : angle[0] + total_turn - angle[m - 1];
    }
    kink.assign(m, 0);
    for (std::size_t k = 0; k < m; ++k) {
      const double t = std::abs(turn[k]);
      const double beside = std::max(std::abs(turn[(k + m - 1) % m]), std::abs(turn[(k + 1) % m]));
      if (t >= kKinkTurn && t < physics::kCornerTurning && t > kKinkOverNeighbours * beside) {
        kink[k] = 1;
        kink_arc.push_back(arc[k]);
      }
      if (kink[k] || t >= physics::kCornerTurning) break_arc.push_back(arc[k]);
    }
  }

  // Direction at arc length s (any real s: the outline repeats): linear
  // across a vertex where edges meet at less than 10 degrees (a polyline
  // drawn along a curve, whose curvature then comes out right whatever the
  // window against the edge length), over half the shorter edge each side:
  // between the midpoints of equal chords, and close to the vertex where a
  // straight edge meets a curve's chords (a rack's flank and its root
  // fillet), so that the straight edge keeps its direction. A step at a
  // kink and at a vertex with a larger turn (a corner of the outline).
  double direction(double s) const {
    const std::size_t m = angle.size();
    const double turns = std::floor(s / perimeter);
    const double r = s - turns * perimeter;
    const std::size_t k = std::min<std::size_t>(
        m - 1, static_cast<std::size_t>(std::upper_bound(arc.begin(), arc.end() - 1, r) -
                                        arc.begin() - 1));
    const double mid = 0.5 * (arc[k] + arc[k + 1]);
    // The neighbouring edge on r's side of the midpoint, and its angle and
    // midpoint continued across the outline's start.
    const bool after = r >= mid;
    const std::size_t n = after ? (k + 1) % m : (k + m - 1) % m;
    double a_n = angle[n], s_n = 0.5 * (arc[n] + arc[n + 1]);
    if (after && n == 0) {
      a_n += total_turn;
      s_n += perimeter;
    }
    if (!after && k == 0) {
      a_n -= total_turn;
      s_n -= perimeter;
    }
    double a = angle[k];
    const bool kinked = kink[after ? (k + 1) % m : k] != 0;
    if (std::abs(a_n - a) < kSmoothTurn && !kinked && s_n != mid) {
      const double half = 0.5 * std::min(arc[k + 1] - arc[k], arc[n + 1] - arc[n]);
      const double from_vertex = std::abs(r - (after ? arc[k + 1] : arc[k]));
      if (from_vertex < half) a += 0.5 * (1.0 - from_vertex / half) * (a_n - a);
    }
    return a + turns * total_turn;
  }

  // The window [lo, hi] cut back to the kinks nearest s on either side
  // (corners stay inside it: a corner's turn is what the contact's corner
  // test reads from the mean curvature).
  void clip_at_kinks(double s, double& lo, double& hi) const {
    if (kink_arc.empty()) return;
    const double turns = std::floor(s / perimeter);
    const double r = s - turns * perimeter;
    const auto above = std::upper_bound(kink_arc.begin(), kink_arc.end(), r);
    const double next = above == kink_arc.end() ? kink_arc.front() + perimeter : *above;  // > r
    const double prev =
        above == kink_arc.begin() ? kink_arc.back() - perimeter : *(above - 1);  // <= r
    const double base = turns * perimeter;
    lo = std::max(lo, base + prev);
    hi = std::min(hi, base + next);
  }

  // The mean curvature over [lo, hi], a stretch without a kink inside: the
  // turn of the direction across it (just inside it: the direction steps at
  // a kink).
  double turn_rate(double lo, double hi) const {
    const double width = hi - lo;
    if (!(width > 0.0)) return 0.0;
    const double in = 1e-9 * width;
    return (direction(hi - in) - direction(lo + in)) / (width - 2.0 * in);
  }

  // Mean curvature over [s - w/2, s + w/2], not across a kink.
  double mean_curvature(double s, double w) const {
    double lo = s - 0.5 * w, hi = s + 0.5 * w;
    clip_at_kinks(s, lo, hi);
    return hi - lo > 1e-3 * w ? turn_rate(lo, hi) : 0.0;
  }

  // The curvature a Hertz contact at s meets: the mean over
  // [s - w/2, s + w/2] cut back at the kinks and corners on either side,
  // without the step of one at s itself (a corner's particle: the mean of
  // its two sides).
  double hertz_curvature(double s, double w) const {
    double lo = s - 0.5 * w, hi = s + 0.5 * w;
    const double in = 1e-9 * w;
    bool own = false;  // a break at s
    if (!break_arc.empty()) {
      const double turns = std::floor(s / perimeter);
      const double r = s - turns * perimeter, base = turns * perimeter;
      // The last break before s and the first after it, continued across
      // the outline's start; a break within `in` of s is s's own.
      const auto after = std::upper_bound(break_arc.begin(), break_arc.end(), r + in);
      const double next = after == break_arc.end() ? break_arc.front() + perimeter : *after;
      const auto before = std::lower_bound(break_arc.begin(), break_arc.end(), r - in);
      const double prev =
          before == break_arc.begin() ? break_arc.back() - perimeter : *(before - 1);
      lo = std::max(lo, base + prev);
      hi = std::min(hi, base + next);
      own = after != before;
    }
    if (!(hi - lo > 1e-3 * w)) return 0.0;
    if (!own) return turn_rate(lo, hi);
    const double turn =
        (direction(s - in) - direction(lo + in)) + (direction(hi - in) - direction(s + in));
    return turn / (hi - lo);
  }

  // The rate of change of the mean curvature along the travel at s: the
  // windows [s - w, s] and [s, s + w], each cut back at kinks on s's side,
  // between their middles.
  double curvature_rate(double s, double w) const {
    double lo = s - w, hi = s + w;
    clip_at_kinks(s, lo, hi);
    const double up_centre = 0.5 * (s + hi), down_centre = 0.5 * (lo + s);
    const double span = up_centre - down_centre;
    if (!(span > 0.25 * w)) return 0.0;
    return (turn_rate(s, hi) - turn_rate(lo, s)) / span;
  }
};

void from_outline(Simulation& sim, const Body& body, const Outline& o) {
  Particles& p = sim.particles;
  // Body-fitted particles: the outline row alone (its particles lie on the
  // outline's chords, within a hair of it).
  const double dx = sim.discretization.dx;
  const double reach = body.fitted ? 1e-6 * dx : kSurfaceReachOverDx * dx;
  const bool ccw = counter_clockwise(o);
  const std::size_t m = o.points.size();
  const Turning turning(o, ccw);
  // Bin the outline's edges by their midpoints on a grid of cells larger
  // than any edge plus the reach, so each particle checks a few cells only.
  double longest = 0.0;
  std::vector<double> mx(m), my(m);
  for (std::size_t k = 0; k < m; ++k) {
    const auto& a = o.points[k];
    const auto& b = o.points[(k + 1) % m];
    mx[k] = 0.5 * (a[0] + b[0]);
    my[k] = 0.5 * (a[1] + b[1]);
    longest = std::max(longest, std::hypot(b[0] - a[0], b[1] - a[1]));
  }
  CellGrid grid;
  grid.build(mx.data(), my.data(), m, std::max(reach + 0.5 * longest, dx));
  for (std::size_t i = body.begin; i < body.end; ++i) {
    Closest best;
    grid.for_each_near(p.x0[i], p.y0[i], [&](std::uint32_t k) {
      const double before = best.distance;
      closest_on_segment(o.points[k], o.points[(k + 1) % m], p.x0[i], p.y0[i], ccw, best);
      if (best.distance < before) best.edge = k;
    });
    if (best.distance <= reach) {
      const double s =
          turning.arc[best.edge] + best.t * (turning.arc[best.edge + 1] - turning.arc[best.edge]);
      // The normal of the curve the outline's chords are drawn along, not
      // of the nearest chord: a chord 0.1 um from an 8 mm radius is 0.08 mm
      // long and turns by 5 mrad, which put neighbouring flank particles'
      // surfaces a micron apart half a spacing away (docs/contact.md).
      // Travel along a counter-clockwise outline has the body on its left.
      // At a corner (the curve's direction steps) the nearest edge's normal
      // stays.
      const double travel = ccw ? turning.direction(s) : -turning.direction(s);
      const double nx = ccw ? std::sin(travel) : -std::sin(travel);
      const double ny = ccw ? -std::cos(travel) : std::cos(travel);
      const bool corner = nx * best.nx + ny * best.ny < std::cos(kChordTurnMax);
      const double ox = corner ? best.nx : nx, oy = corner ? best.ny : ny;
      if (ox * o.contact_side[0] + oy * o.contact_side[1] < -kSideTolerance) continue;
      p.surf_depth[i] = body.fitted ? 0.0 : best.distance;
      p.surf_nx[i] = ox;
      p.surf_ny[i] = oy;
      const double w = p.spacing[i];
      const double kappa = turning.mean_curvature(s, w);
      p.surf_curvature[i] = kappa;
      p.surf_hertz_curvature[i] = turning.hertz_curvature(s, w);
      // The particle's tangent runs with the travel on a counter-clockwise
      // outline. The rate is bounded by half the curvature over a spacing,
      // so that the surface stays convex where the parabola's was (near an
      // involute's base circle the curvature changes by more than itself over
      // a spacing).
      const double rate = turning.curvature_rate(s, w);
      const double bound = 0.5 * std::abs(kappa) / w;
      p.surf_curvature_rate[i] = (ccw ? 1.0 : -1.0) * std::clamp(rate, -bound, bound);
    }
  }
}

// No outline: the colour-gradient normal of the SPH neighbourhood.
void from_colour_gradient(Simulation& sim, const Body& body) {
  Particles& p = sim.particles;
  const double h = sim.h(), dx = sim.discretization.dx;
  with_kernel(sim.discretization.kernel, h, [&](const auto& kernel) {
    for (std::size_t i = body.begin; i < body.end; ++i) {
      double cx = 0.0, cy = 0.0;
      for (std::size_t j = body.begin; j < body.end; ++j) {
        const double rx = p.x0[i] - p.x0[j], ry = p.y0[i] - p.y0[j];
        const double r = std::hypot(rx, ry);
        if (r == 0.0 || r >= kernel.radius) continue;
        const double g = kernel.dW(r) / r * (p.mass[j] / p.rho0[j]);
        cx += g * rx;
        cy += g * ry;
      }
      // In a full interior the sum vanishes; at a surface it is of order 1/h
      // and points into the body.
      const double len = std::hypot(cx, cy);
      if (len * h > 0.25) {
        p.surf_depth[i] = 0.5 * dx;
        p.surf_nx[i] = -cx / len;
        p.surf_ny[i] = -cy / len;
      }
    }
  });
}

}  // namespace

void assign_surfaces(Scene& scene) {
  Simulation& sim = scene.sim;
  for (std::size_t b = 0; b < sim.bodies.size(); ++b) {
    const Outline* outline = nullptr;
    for (const Outline& o : scene.outlines) {
      if (o.body == static_cast<int>(b) && o.closed) outline = &o;
    }
    if (outline) {
      from_outline(sim, sim.bodies[b], *outline);
    } else {
      from_colour_gradient(sim, sim.bodies[b]);
    }
  }
}

}  // namespace gearsph::scenes
