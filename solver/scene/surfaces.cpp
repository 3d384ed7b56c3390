#include "solver/scene/surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "solver/neighbours/cell_grid.hpp"

namespace gearsph::scenes {

namespace {

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
  std::vector<double> arc, angle;
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
  }

  // Direction at arc length s (any real s: the outline repeats): linear
  // between the midpoints of edges that meet at less than 10 degrees (a
  // polyline drawn along a curve, whose curvature then comes out right
  // whatever the window against the edge length), a step at a vertex with a
  // larger turn (a corner of the outline).
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
    if (std::abs(a_n - a) < kSmoothTurn && s_n != mid) a += (r - mid) / (s_n - mid) * (a_n - a);
    return a + turns * total_turn;
  }

  // Mean curvature over [s - w/2, s + w/2]: the turn of the direction across it.
  double mean_curvature(double s, double w) const {
    return (direction(s + 0.5 * w) - direction(s - 0.5 * w)) / w;
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
      p.surf_depth[i] = body.fitted ? 0.0 : best.distance;
      p.surf_nx[i] = best.nx;
      p.surf_ny[i] = best.ny;
      const double s =
          turning.arc[best.edge] + best.t * (turning.arc[best.edge + 1] - turning.arc[best.edge]);
      p.surf_curvature[i] = turning.mean_curvature(s, p.spacing[i]);
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
