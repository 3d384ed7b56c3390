// Hertz line contact (validation.md section 6): an elastic cylinder of radius
// R pressed on a flat block by a line load P' (plane strain). Theory
// (Johnson 1985, sec. 4.2): 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2,
//   half-width a = sqrt(4 P' R / (pi E*)),  peak pressure p0 = 2 P' / (pi a),
//   p(x) = p0 sqrt(1 - x^2/a^2).
// Only a cap of the cylinder is modelled (its height a multiple of a: the
// contact stresses decay within a few a), loaded by a uniform traction on
// its flat top; the block's bottom rows are fixed. The load is ramped up and
// the motion damped (dynamic relaxation) to reach the static state, where the
// contact pressure is read from the contact forces on the block's top row
// and fitted with the Hertz ellipse. On body-fitted particles
// ("particles": "body_fitted") both bodies get a row on their true outline,
// fine within 2a of the contact and graded to the bulk, and the pressure is
// read from the block's outline row (docs/contact.md, "A resolved contact").
#include <algorithm>
#include <cmath>
#include <numbers>

#include "solver/diagnostics/hertz_fit.hpp"
#include "solver/physics/contact.hpp"
#include "solver/scene/builders.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

namespace {

// A row of particles along x (an outline row): sorted by x, and the stretch
// of [lo, hi] each stands for, halfway to its neighbours.
std::vector<double> sort_and_span(std::vector<std::size_t>& row, const Particles& p, double lo,
                                  double hi) {
  std::sort(row.begin(), row.end(), [&](std::size_t u, std::size_t v) { return p.x[u] < p.x[v]; });
  std::vector<double> span(row.size());
  for (std::size_t k = 0; k < row.size(); ++k) {
    const double left = k == 0 ? lo : 0.5 * (p.x[row[k - 1]] + p.x[row[k]]);
    const double right = k + 1 == row.size() ? hi : 0.5 * (p.x[row[k]] + p.x[row[k + 1]]);
    span[k] = right - left;
  }
  return span;
}

// Johnson 1985, sec. 4.2: the contact modulus E*, the half-width a and the
// peak pressure p0 of a line load P' on a cylinder of radius R.
struct HertzReference {
  double e_star = 0.0, a = 0.0, p0 = 0.0;
};
HertzReference hertz_reference(double R, double load, const Material& mat_c,
                               const Material& mat_b) {
  HertzReference ref;
  ref.e_star = 1.0 / ((1 - mat_c.nu * mat_c.nu) / mat_c.E + (1 - mat_b.nu * mat_b.nu) / mat_b.E);
  ref.a = std::sqrt(4.0 * load * R / (std::numbers::pi * ref.e_star));
  ref.p0 = 2.0 * load / (std::numbers::pi * ref.a);
  return ref;
}

// Spacings: a lattice of a/6, or body-fitted particles whose fine spacing
// (the job's, else the lattice's) is a quarter of the bulk one by default.
// Body-fitted (graded) particles are a variant: fine at the contact, a
// row on each true outline, coarse far from it (docs/contact.md).
SceneSpacings hertz_spacings(Discretization& d, double a_ref) {
  SceneSpacings sp;
  sp.fitted = particle_layout(d, ParticleLayout::Lattice) == ParticleLayout::BodyFitted;
  sp.fine = sp.fitted && d.fine_dx > 0 ? d.fine_dx : (d.dx > 0 ? d.dx : a_ref / 6.0);
  if (d.dx <= 0) d.dx = sp.fitted ? 4.0 * sp.fine : a_ref / 6.0;
  sp.dx = d.dx;
  sp.grading = d.grading > 0 ? d.grading : geometry::kDefaultGrading;
  require_fine_within_bulk(sp);
  if (a_ref < 3.0 * sp.fine) {
    throw JobError("/discretization", "the Hertz half-width a = " + std::to_string(a_ref) +
                                          " m spans fewer than 3 spacings; use a spacing of at "
                                          "most a/3 (several particles across a are needed)");
  }
  return sp;
}

struct HertzBodies {
  double R = 0.0;           // the cylinder's radius
  double cap_height = 0.0;  // of the modelled cap, at most R
  double block_half = 0.0, block_depth = 0.0;
  double fixed_depth = 0.0;  // the block base's fixed rows
};

// Cap and block sizes in units of a: large against the contact zone.
HertzBodies hertz_bodies(const nlohmann::json& s, double R, double a_ref, const Discretization& d) {
  HertzBodies g;
  g.R = R;
  g.cap_height = std::min(g.R, s.at("cap_height_over_a").get<double>() * a_ref);
  g.block_half = s.at("block_half_width_over_a").get<double>() * a_ref;
  g.block_depth = s.at("block_depth_over_a").get<double>() * a_ref;
  g.fixed_depth = std::ceil(kernel_support(d.kernel) * d.h_over_dx) * d.dx;
  return g;
}

// The cap's outline: its circular arc closed by its top chord.
Outline cap_outline(const HertzBodies& g) {
  const double R = g.R;
  Outline cap{"cylinder", 0, {}, true};
  const double a_top = std::asin(std::clamp((g.cap_height - R) / R, -1.0, 1.0));
  const int n_arc = 720;
  for (int k = 0; k <= n_arc; ++k) {
    // From the right end of the chord, down around the bottom, to the left end.
    const double t = a_top - (std::numbers::pi + 2.0 * a_top) * k / n_arc;
    cap.points.push_back({R * std::cos(t), R + R * std::sin(t)});
  }
  std::reverse(cap.points.begin(), cap.points.end());  // counter-clockwise
  return cap;
}

// The block as filled: its width and its bottom's y (its top is y = 0).
struct BlockExtent {
  double width = 0.0, bottom = 0.0;
};

// Body-fitted: fine within 2a of the contact on both outlines, graded to
// the bulk.
BlockExtent fill_body_fitted(Simulation& sim, const Outline& cap, const HertzBodies& g,
                             const SceneSpacings& sp, double a_ref, const Material& mat_c,
                             const Material& mat_b) {
  geometry::Polygon cap_poly;
  std::vector<geometry::Point> arc;
  for (const auto& q : cap.points) {
    cap_poly.push_back({q[0], q[1]});
    if (std::abs(q[0]) <= 2.0 * a_ref && q[1] < g.R) arc.push_back({q[0], q[1]});
  }
  add_body(sim, "cylinder", mat_c);
  geometry::SpacingField cap_field(sp.dx, sp.grading);
  cap_field.add_feature(arc, sp.fine);
  add_body_fitted(sim, geometry::make_region(cap_poly), cap_field,
                  [](double, double) { return 0; });
  end_body(sim);
  add_body(sim, "block", mat_b);
  geometry::SpacingField block_field(sp.dx, sp.grading);
  block_field.add_feature({{-2.0 * a_ref, 0.0}, {2.0 * a_ref, 0.0}}, sp.fine);
  // The top edge as many short edges: the outline row is spaced edge by
  // edge, so one long edge would take the finest spacing along all of it.
  geometry::Polygon rect = {{-g.block_half, -g.block_depth}, {g.block_half, -g.block_depth}};
  const int top_edges = static_cast<int>(std::ceil(2.0 * g.block_half / sp.fine));
  for (int k = 0; k <= top_edges; ++k) {
    rect.push_back({g.block_half - 2.0 * g.block_half * k / top_edges, 0.0});
  }
  add_body_fitted(sim, geometry::make_region(rect), block_field,
                  [&](double, double y) { return y < -g.block_depth + g.fixed_depth ? 1 : 0; });
  end_body(sim);
  return {2.0 * g.block_half, -g.block_depth};
}

// Lattice: the cylinder cap, centre (0, R), filled with concentric rings of
// particles so that its surface is the circle itself: on a square lattice
// the bottom row would be flat over |x| < sqrt(R dx), wider than the
// contact (a^2/2R is a fraction of dx), and the block would feel a flat
// punch. The lowest particle sits at y = dx/2, one spacing above the
// block's top row at -dx/2 (touching, zero force).
BlockExtent fill_lattice(Simulation& sim, const HertzBodies& g, double dx, const Material& mat_c,
                         const Material& mat_b) {
  const double R = g.R;
  add_body(sim, "cylinder", mat_c);
  for (double r = R - 0.5 * dx; r > R - g.cap_height && r > 0.5 * dx; r -= dx) {
    const long count = std::lround(2.0 * std::numbers::pi * r / dx);
    const double ring_volume = 2.0 * std::numbers::pi * r * dx / static_cast<double>(count);
    for (long k = 0; k < count; ++k) {
      // Start at the bottom point (0, R - r) so every ring has a particle on
      // the axis of symmetry.
      const double angle = -0.5 * std::numbers::pi + 2.0 * std::numbers::pi * k / count;
      const double x = r * std::cos(angle), y = R + r * std::sin(angle);
      if (y <= g.cap_height) add_particle(sim, x, y, 0, ring_volume);
    }
  }
  end_body(sim);
  add_body(sim, "block", mat_b);
  const long bx = lattice::cells(2 * g.block_half, dx), by = lattice::cells(g.block_depth, dx);
  lattice::fill_rectangle(-0.5 * bx * dx, -by * dx, bx, by, dx, [&](double x, double y) {
    add_particle(sim, x, y, y < -by * dx + g.fixed_depth ? 1 : 0);
  });
  end_body(sim);
  return {bx * dx, -by * dx};
}

// Uniform traction P' on the cap's top: the lattice's top row in equal
// shares, or the outline particles on the chord, each its share of the
// chord's length.
void load_cap_top(Simulation& sim, bool fitted, double R, double dx, double load) {
  Particles& p = sim.particles;
  const Body& cyl = sim.bodies[0];
  double top = -1e300;
  for (std::size_t i = cyl.begin; i < cyl.end; ++i) top = std::max(top, p.y[i]);
  std::vector<std::size_t> top_row;
  for (std::size_t i = cyl.begin; i < cyl.end; ++i) {
    if (p.y[i] > top - (fitted ? 1e-9 * R : 0.5 * dx)) top_row.push_back(i);
  }
  const auto [chord_lo, chord_hi] =
      std::minmax_element(top_row.begin(), top_row.end(),
                          [&](std::size_t u, std::size_t v) { return p.x[u] < p.x[v]; });
  const double x_lo = p.x[*chord_lo], x_hi = p.x[*chord_hi];
  const std::vector<double> span = sort_and_span(top_row, p, x_lo, x_hi);
  for (std::size_t k = 0; k < top_row.size(); ++k) {
    const double share =
        fitted ? span[k] / (x_hi - x_lo) : 1.0 / static_cast<double>(top_row.size());
    p.load_ay[top_row[k]] = -load * share / p.mass[top_row[k]];
  }
}

// Where the pressure is read: the block particles whose contact forces are
// summed, the column (point of the profile) each adds to, and the
// profile's points and widths.
struct PressureReadout {
  std::vector<std::size_t> surface;
  std::vector<long> column;
  std::vector<double> xs, widths;
};

// Lattice: every block particle that can take contact forces (the surface
// model spreads a pair's force over the particles within a spacing of the
// surface, so the top row alone misses part of it), summed per lattice
// column. Body-fitted: the outline row, each particle's force over its
// share of the surface.
PressureReadout pressure_readout(const Simulation& sim, bool fitted, double R, double dx,
                                 double block_width) {
  const Particles& p = sim.particles;
  PressureReadout out;
  const Body& blk = sim.bodies[1];
  const double x_left = -0.5 * block_width;
  if (fitted) {
    for (std::size_t i = blk.begin; i < blk.end; ++i) {
      if (p.y[i] > -1e-9 * R) out.surface.push_back(i);
    }
    out.widths = sort_and_span(out.surface, p, x_left, -x_left);
    for (std::size_t k = 0; k < out.surface.size(); ++k) {
      out.column.push_back(static_cast<long>(k));
      out.xs.push_back(p.x[out.surface[k]]);
    }
  } else {
    const long bx = std::lround(block_width / dx);
    for (std::size_t i = blk.begin; i < blk.end; ++i) {
      if (p.y[i] > -2.5 * dx) {
        out.surface.push_back(i);
        out.column.push_back(std::lround((p.x[i] - x_left) / dx - 0.5));
      }
    }
    for (long k = 0; k < bx; ++k) {
      out.xs.push_back(x_left + (static_cast<double>(k) + 0.5) * dx);
      out.widths.push_back(dx);
    }
  }
  return out;
}

// The static contact pressure profile, fitted with the Hertz ellipse,
// against the theory.
nlohmann::json analyse_hertz(const PressureReadout& r, const HertzReference& ref, double load,
                             const Simulation& s2) {
  nlohmann::json a;
  const Particles& q = s2.particles;
  std::vector<double> ps(r.xs.size(), 0.0);
  double total = 0.0;
  for (std::size_t n = 0; n < r.surface.size(); ++n) {
    const std::size_t i = r.surface[n];
    const double f = -q.mass[i] * q.contact_ay[i];  // downward push on the block
    const auto col = static_cast<std::size_t>(r.column[n]);
    ps[col] += f / r.widths[col];  // pressure over the column's (or particle's) width
    total += f;
  }
  const diagnostics::HertzEllipseFit fit = diagnostics::fit_hertz_ellipse(r.xs, ps, ref.a);
  double peak = 0.0;
  for (double v : ps) peak = std::max(peak, v);
  a["reference"] = "Hertz line contact: a = sqrt(4 P' R / (pi E*)), p0 = 2 P' / (pi a)";
  a["reference_half_width_m"] = ref.a;
  a["reference_peak_pressure_Pa"] = ref.p0;
  a["half_width_m"] = fit.a;
  a["peak_pressure_Pa"] = fit.p0;
  a["max_particle_pressure_Pa"] = peak;
  a["half_width_error"] = (fit.a - ref.a) / ref.a;
  a["peak_pressure_error"] = (fit.p0 - ref.p0) / ref.p0;
  a["fit_rms_Pa"] = fit.rms;
  a["transmitted_load_fraction"] = total / load;
  nlohmann::json profile = nlohmann::json::array();
  for (std::size_t k = 0; k < r.xs.size(); ++k) {
    if (ps[k] > 0.0) profile.push_back({r.xs[k], ps[k]});
  }
  a["pressure_profile_x_m_p_Pa"] = profile;
  return a;
}

}  // namespace

Scene build_hertz(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double R = s.at("radius_m").get<double>();
  const double load = s.at("load_N_per_m").get<double>();
  const Material mat_c = read_material(s.at("cylinder_material"));
  const Material mat_b = read_material(s.at("block_material"));
  const HertzReference ref = hertz_reference(R, load, mat_c, mat_b);

  Scene scene = start_scene("hertz", in);
  Simulation& sim = scene.sim;
  const SceneSpacings sp = hertz_spacings(sim.discretization, ref.a);
  const HertzBodies g = hertz_bodies(s, R, ref.a, sim.discretization);
  const Outline cap = cap_outline(g);
  sim.motions.push_back(Motion::fixed("block base"));
  const BlockExtent block = sp.fitted ? fill_body_fitted(sim, cap, g, sp, ref.a, mat_c, mat_b)
                                      : fill_lattice(sim, g, sp.dx, mat_c, mat_b);
  scene.outlines.push_back(cap);
  const double hx = 0.5 * block.width;
  scene.outlines.push_back(
      {"block", 1, {{-hx, block.bottom}, {hx, block.bottom}, {hx, 0.0}, {-hx, 0.0}}, true});
  load_cap_top(sim, sp.fitted, R, sp.dx, load);
  sim.domain = grown_bounds(sim.particles, 2 * R);

  // Dynamic relaxation of the slowest mode: a quarter wave through cap and
  // block at the faster P-wave speed.
  const double height = g.cap_height + g.block_depth;
  const double c = std::max(mat_c.p_wave_speed(), mat_b.p_wave_speed());
  relax_to_static(scene, std::numbers::pi * c / (2.0 * height));
  // The contact is resolved (a over several spacings): the pressure is read
  // from single pairs, not smoothed over the surface.
  scene.contact_smoothing_spacings = 0.0;

  const PressureReadout readout = pressure_readout(sim, sp.fitted, R, sp.dx, block.width);
  scene.columns.push_back(
      {"contact_load_fraction", [surface = readout.surface, load](const Simulation& s2) {
         double f = 0.0;
         for (std::size_t i : surface) f += s2.particles.mass[i] * s2.particles.contact_ay[i];
         return -f / load;  // the block is pushed down
       }});
  scene.description = {{"reference_half_width_m", ref.a},
                       {"reference_peak_pressure_Pa", ref.p0},
                       {"contact_modulus_Pa", ref.e_star},
                       {"cap_height_m", g.cap_height},
                       {"block_width_m", block.width},
                       {"block_depth_m", -block.bottom},
                       {"particles", layout_name(sp.fitted)},
                       {"contact_spacing_m", sp.fine},
                       {"particles_across_half_width", ref.a / sp.fine}};
  scene.analyse = [readout, ref, load](const History&, const Simulation& s2) {
    return analyse_hertz(readout, ref, load, s2);
  };
  return scene;
}

}  // namespace gearsph::scenes
