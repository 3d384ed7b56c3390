#include "solver/scene/surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "solver/neighbours/cell_grid.hpp"

namespace gearsph::scenes {

namespace {

struct Closest {
  double distance = std::numeric_limits<double>::infinity();
  double nx = 0.0, ny = 0.0;  // outward normal
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

void from_outline(Simulation& sim, const Body& body, const Outline& o) {
  Particles& p = sim.particles;
  // Body-fitted particles: the outline row alone (its particles lie on the
  // outline's chords, within a hair of it).
  const double dx = sim.discretization.dx;
  const double reach = body.fitted ? 1e-6 * dx : kSurfaceReachOverDx * dx;
  const bool ccw = counter_clockwise(o);
  const std::size_t m = o.points.size();
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
      closest_on_segment(o.points[k], o.points[(k + 1) % m], p.x0[i], p.y0[i], ccw, best);
    });
    if (best.distance <= reach) {
      p.surf_depth[i] = body.fitted ? 0.0 : best.distance;
      p.surf_nx[i] = best.nx;
      p.surf_ny[i] = best.ny;
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
