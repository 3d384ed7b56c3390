#include "fe/gear_fe_model.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "solver/gear/gear_rating.hpp"

namespace gearsph::fe {

namespace {

using geometry::at_arc;
using geometry::cumulative_arc;
using geometry::Polygon;
constexpr double kPi = std::numbers::pi;
// The generated outline turns by about 1.5 degrees from one sample to the
// next on its tightest curves (a 1 mm radius sampled to a 0.1 um chord
// error); its corners (tooth tips, sector cuts) turn by 20 degrees and more.
constexpr double kCornerRad = 10.0 * kPi / 180.0;
// Vertices of the outline and points of the fillet curves that are one
// point (both come from the same samples of the same curves).
constexpr double kSamePoint = 1e-9;

// Arc length along the half tooth where it first reaches `radius` (its
// radius grows monotonically from the root circle to the tip circle; the
// pieces meet to rounding, hence the relative tolerance).
double arc_at_radius(const std::vector<Point>& half, const std::vector<double>& cum,
                     double radius) {
  for (std::size_t k = 1; k < half.size(); ++k) {
    const double r0 = geometry::norm(half[k - 1]), r1 = geometry::norm(half[k]);
    if (r1 >= radius * (1.0 - 1e-12) && r1 > r0) {
      const double f = std::clamp((radius - r0) / (r1 - r0), 0.0, 1.0);
      return cum[k - 1] + f * (cum[k] - cum[k - 1]);
    }
  }
  return cum.back();
}

std::size_t nearest_vertex(const Polygon& poly, Point p) {
  std::size_t best = 0;
  double d_best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const double d = geometry::norm(poly[i] - p);
    if (d < d_best) d_best = d, best = i;
  }
  if (d_best > kSamePoint) {
    throw std::logic_error("gear FE model: a fillet end is not a vertex of the outline");
  }
  return best;
}

// Arcs of `radius` about the origin from a to b (clockwise if `clockwise`),
// each less than a third of a turn, ending exactly on a and b.
std::vector<Curve> arcs(Point a, Point b, double radius, bool clockwise, const std::string& group) {
  double from = std::atan2(a.y, a.x), to = std::atan2(b.y, b.x);
  double sweep = to - from;
  if (clockwise && sweep >= 0.0) sweep -= 2.0 * kPi;
  if (!clockwise && sweep <= 0.0) sweep += 2.0 * kPi;
  const int n = std::max(1, static_cast<int>(std::ceil(std::abs(sweep) / (0.6 * kPi))));
  std::vector<Curve> out;
  Point start = a;
  for (int k = 1; k <= n; ++k) {
    const double angle = from + sweep * k / n;
    const Point end = k == n ? b : Point{radius * std::cos(angle), radius * std::sin(angle)};
    Curve c;
    c.kind = Curve::Kind::Arc;
    c.points = {start, end};
    c.centre = {0.0, 0.0};
    c.group = group;
    out.push_back(c);
    start = end;
  }
  return out;
}

// The loaded flank of tooth 0 in the gear frame: the generating frame's
// right half tooth (axis +y), mirrored for the +x flank, turned half a turn.
Point to_gear(Point gen, int flank_side) {
  return geometry::rotate(flank_side < 0 ? gen : Point{-gen.x, gen.y}, kPi);
}

GearLoadPatch load_patch(const geometry::PinionGeometry& g, const GearFeCase& c) {
  const std::vector<Point>& half = g.half_tooth();
  const std::vector<double> cum = cumulative_arc(half);
  const double rb = g.base_radius();
  const double s_form = arc_at_radius(half, cum, g.form_radius());
  const double s_tip = arc_at_radius(half, cum, g.tip_radius());
  // Line contact of the involute (radius of curvature sqrt(r^2 - r_b^2)) on
  // the straight rack flank: half-width a = sqrt(4 P' R / (pi E*)), peak
  // p0 = 2 P' / (pi a), 1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2 (Johnson 1985,
  // eqs. 4.43-4.45), with the line load P' = F_n / b.
  const double line_load = c.normal_force_N / c.face_width_m;
  const double e_star =
      1.0 / ((1.0 - c.nu * c.nu) / c.E_Pa + (1.0 - c.rack_nu * c.rack_nu) / c.rack_E_Pa);
  GearLoadPatch p;
  p.requested_radius_m = c.load_radius_m;
  const double radius0 = std::max(c.load_radius_m, rb * (1.0 + 1e-9));
  const double a0 =
      std::sqrt(4.0 * line_load * std::sqrt(radius0 * radius0 - rb * rb) / (kPi * e_star));
  // Keep the patch on the involute: between the form circle and the tip.
  const double s_req = arc_at_radius(half, cum, c.load_radius_m);
  const double s_c = s_tip - s_form > 2.0 * a0 ? std::clamp(s_req, s_form + a0, s_tip - a0)
                                               : 0.5 * (s_form + s_tip);
  const Point gen = at_arc(half, cum, s_c);
  p.centre = to_gear(gen, c.flank_side);
  p.radius_m = geometry::norm(p.centre);
  p.curvature_radius_m = std::sqrt(std::max(0.0, p.radius_m * p.radius_m - rb * rb));
  p.half_width_m = std::sqrt(4.0 * line_load * p.curvature_radius_m / (kPi * e_star));
  p.peak_pressure_Pa = 2.0 * line_load / (kPi * p.half_width_m);
  // Outward normal of the outline there (counter-clockwise outline: to the
  // right of the walk; the mirrored half is walked the other way).
  const double ds = 1e-3 * std::max(p.half_width_m, 1e-6);
  const Point t_gen = at_arc(half, cum, s_c + ds) - at_arc(half, cum, s_c - ds);
  Point n_gen{t_gen.y, -t_gen.x};
  if (c.flank_side > 0) n_gen = {-n_gen.x, n_gen.y};
  const Point n_out = geometry::rotate((1.0 / geometry::norm(n_gen)) * n_gen, kPi);
  // The involute's normal is tangent to the base circle: of the two
  // tangents from the centre point, the one along -n_out (into the tooth).
  const double phi = std::atan2(p.centre.y, p.centre.x);
  const double beta = std::acos(std::min(1.0, rb / p.radius_m));
  double best = -2.0;
  for (double sign : {-1.0, 1.0}) {
    const Point t{rb * std::cos(phi + sign * beta), rb * std::sin(phi + sign * beta)};
    const Point d = (1.0 / geometry::norm(t - p.centre)) * (t - p.centre);
    const double along = -geometry::dot(d, n_out);
    if (along > best) best = along, p.direction = d;
  }
  if (best < 0.99) throw std::logic_error("gear FE model: the line of action misses the flank");
  return p;
}

// The outline of the model (sector or whole gear, gear frame), cut into
// curves with groups for the supports ("fixed"), the load ("loaded_flank")
// and the fillets, and the element sizes around the fillets and the load.
// Sets out.outline, out.holes and out.fillets.
MeshSpec model_region(const geometry::PinionGeometry& g, const GearFeCase& c, double sample_step_m,
                      GearFeResult& out) {
  const bool whole = models_whole_gear(c);
  out.outline =
      whole ? g.outline() : g.sector_outline(c.first_tooth, c.last_tooth, c.fixed_radius_m);
  out.fillets = gear::tooth_fillets(g, 0, geometry::Transform{},
                                    c.normal_force_N * out.load.direction, sample_step_m);
  const Polygon& poly = out.outline;
  const std::size_t t0 = nearest_vertex(poly, out.fillets.tension.points.front());
  const std::size_t t1 = nearest_vertex(poly, out.fillets.tension.points.back());
  const std::size_t c0 = nearest_vertex(poly, out.fillets.compression.points.front());
  const std::size_t c1 = nearest_vertex(poly, out.fillets.compression.points.back());
  const PolygonPieces pieces = polygon_curves(poly, {t0, t1, c0, c1}, kCornerRad);

  CurveLoop loop;
  int tension_curve = -1, compression_curve = -1, flank_curve = -1;
  for (std::size_t i = 0; i < pieces.curves.size(); ++i) {
    Curve piece = pieces.curves[i];
    const std::size_t v0 = pieces.first_vertex[i];
    const std::size_t v1 = pieces.first_vertex[(i + 1) % pieces.curves.size()];
    auto is = [&](std::size_t a, std::size_t b) {
      return (v0 == a && v1 == b) || (v0 == b && v1 == a);
    };
    bool on_fixed = !whole;
    for (const Point& q : piece.points) {
      on_fixed = on_fixed && std::abs(geometry::norm(q) - c.fixed_radius_m) < kSamePoint;
    }
    if (on_fixed) {  // the sector's inner arc, drawn as exact circular arcs
      for (Curve& a :
           arcs(piece.points.front(), piece.points.back(), c.fixed_radius_m, true, "fixed")) {
        loop.push_back(std::move(a));
      }
      continue;
    }
    if (is(t0, t1)) {
      piece.group = "tension_fillet";
      tension_curve = static_cast<int>(loop.size());
    } else if (is(c0, c1)) {
      piece.group = "compression_fillet";
      compression_curve = static_cast<int>(loop.size());
    } else if ((v0 == t1 || v1 == t1) &&
               std::abs(geometry::norm(poly[v0 == t1 ? v1 : v0]) - g.tip_radius()) < 1e-6) {
      piece.group = "loaded_flank";  // form circle to tip corner
      flank_curve = static_cast<int>(loop.size());
    }
    loop.push_back(std::move(piece));
  }
  if (tension_curve < 0 || compression_curve < 0 || flank_curve < 0) {
    throw std::logic_error("gear FE model: tooth 0's fillets or loaded flank not on the outline");
  }
  MeshSpec spec;
  spec.loops.push_back(std::move(loop));
  if (whole) {
    const double r = c.fixed_radius_m;
    CurveLoop bore = arcs({r, 0.0}, {0.0, r}, r, false, "fixed");
    for (Curve& a : arcs({0.0, r}, {r, 0.0}, r, false, "fixed")) bore.push_back(std::move(a));
    spec.loops.push_back(std::move(bore));
    constexpr int kBoreSides = 256;  // for pictures only
    Polygon hole;
    for (int k = 0; k < kBoreSides; ++k) {
      const double a = 2.0 * kPi * k / kBoreSides;
      hole.push_back({r * std::cos(a), r * std::sin(a)});
    }
    out.holes.push_back(hole);
  }
  const GearMeshSizes& sizes = out.sizes;
  spec.size_max = sizes.max;
  SizeZone fillets;
  fillets.curves = {{0, tension_curve}, {0, compression_curve}};
  fillets.size_min = sizes.fillet;
  fillets.size_max = sizes.max;
  fillets.dist_min = sizes.fillet_band;
  fillets.dist_max = sizes.grow_to;
  SizeZone load;
  load.points = {out.load.centre};
  load.size_min = sizes.load;
  load.size_max = sizes.max;
  load.dist_min = sizes.load_band;
  load.dist_max = std::max(sizes.grow_to, 2.0 * sizes.load_band);
  spec.zones = {fillets, load};
  return spec;
}

// The pinion's loaded flank carries the Hertzian pressure of its patch,
// scaled to F_n exactly (hertz_forces). Sets load.applied_N (per gear).
std::vector<Point> flank_forces(const TriMesh& mesh, const std::vector<BoundaryEdge>& boundary,
                                const GearFeCase& c, GearLoadPatch& load) {
  const std::vector<BoundaryEdge> flank = group_edges(mesh, boundary, "loaded_flank");
  const std::vector<Point> forces =
      hertz_forces(mesh, flank, load.centre, load, c.normal_force_N / c.face_width_m);
  Point total;
  for (const Point& f : forces) total = total + f;
  load.applied_N = c.face_width_m * total;
  return forces;
}

// The stress at the fillet curves' samples: along each fillet's boundary
// edges, between their nodes' stresses. Sets out.stress and
// out.curve_to_mesh_m.
void stress_on_fillets(const std::vector<BoundaryEdge>& boundary, GearFeResult& out) {
  std::vector<double> sxx, syy, sxy;
  for (const NodalStress& s : out.solution.stress) {
    sxx.push_back(s.xx);
    syy.push_back(s.yy);
    sxy.push_back(s.xy);
  }
  auto read_curve = [&](const gear::FilletCurve& curve, const std::string& group) {
    const std::vector<BoundaryEdge> edges = group_edges(out.mesh, boundary, group);
    std::vector<gear::PlaneStress> stress;
    for (const Point& p : curve.points) {
      const EdgeHit hit = nearest_edge(out.mesh, edges, p);
      const BoundaryEdge& e = edges[hit.edge];
      out.curve_to_mesh_m = std::max(out.curve_to_mesh_m, hit.distance);
      stress.push_back(
          {along_edge(e, hit.xi, sxx), along_edge(e, hit.xi, syy), along_edge(e, hit.xi, sxy)});
    }
    return stress;
  };
  out.stress = gear::fillet_stress(out.fillets, read_curve(out.fillets.tension, "tension_fillet"),
                                   read_curve(out.fillets.compression, "compression_fillet"));
}

}  // namespace

GearMeshSizes gear_mesh_sizes(const geometry::PinionGeometry& pinion, double fillet_size_m) {
  const double m = pinion.spec().tool.module_m;
  GearMeshSizes s;
  s.fillet = fillet_size_m;
  s.load = fillet_size_m;
  // Five times the fillet size elsewhere: the stress there varies over
  // millimetres, and six-node triangles follow that at 1 mm.
  s.max = 5.0 * fillet_size_m;
  // Fine within m/8 of the fillets (a layer of about a fifth of the fillet
  // radius, where the stress falls from its peak) and m/16 of the load,
  // growing over 1.5 m (the size changes by under 15 % from one element
  // to the next).
  s.fillet_band = m / 8.0;
  s.load_band = m / 16.0;
  s.grow_to = 1.5 * m;
  return s;
}

std::vector<double> default_fillet_sizes(const geometry::PinionGeometry& pinion) {
  const double rho_F = gear::iso_tooth_form(pinion, pinion.pitch_radius()).rho_F;
  auto two_digits = [](double v) {
    const double scale = std::pow(10.0, std::floor(std::log10(v)) - 1.0);
    return std::round(v / scale) * scale;
  };
  const double coarse = two_digits(rho_F / 12.0);
  return {coarse, 0.5 * coarse};
}

std::array<double, 2> root_image_range_Pa(const GearFeResult& r) {
  const double cap = 1.25 * std::max(std::abs(r.stress.tension.stress_Pa),
                                     std::abs(r.stress.compression.stress_Pa));
  return {-cap, cap};
}

std::vector<Point> hertz_forces(const TriMesh& mesh, const std::vector<BoundaryEdge>& edges,
                                Point centre, const GearLoadPatch& patch, double line_load) {
  const Traction hertz = [&](Point x, Point normal) {
    const double d = geometry::norm(x - centre) / patch.half_width_m;
    const double p = d < 1.0 ? patch.peak_pressure_Pa * std::sqrt(1.0 - d * d) : 0.0;
    return -p * normal;
  };
  std::vector<Point> forces = traction_forces(mesh, edges, hertz, 64);
  Point total;
  for (const Point& f : forces) total = total + f;
  const double scale = line_load / geometry::norm(total);
  for (Point& f : forces) f = scale * f;
  return forces;
}

double boundary_displacement(const TriMesh& mesh, const std::vector<BoundaryEdge>& edges,
                             const FeSolution& solution, Point point, Point direction) {
  const EdgeHit hit = nearest_edge(mesh, edges, point);
  std::vector<double> along(solution.displacement.size());
  for (std::size_t k = 0; k < along.size(); ++k) {
    along[k] = solution.displacement[k].x * direction.x + solution.displacement[k].y * direction.y;
  }
  return along_edge(edges[hit.edge], hit.xi, along);
}

double load_displacement(const std::vector<Point>& forces, const FeSolution& solution) {
  double work = 0.0;
  Point total;
  for (std::size_t k = 0; k < forces.size(); ++k) {
    const Point f = forces[k], u = solution.displacement[k];
    work += f.x * u.x + f.y * u.y;
    total = total + f;
  }
  return work / geometry::norm(total);
}

FeModel meshed_model(const MeshSpec& spec, double E_Pa, double nu, const FeTools& tools,
                     const std::filesystem::path& work_dir, const std::string& name,
                     double timeout_s, double& mesh_s) {
  const auto start = std::chrono::steady_clock::now();
  FeModel model;
  model.mesh = mesh_with_gmsh(spec, tools, work_dir, name, timeout_s);
  mesh_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  model.E_Pa = E_Pa;
  model.nu = nu;
  return model;
}

GearFeResult solve_gear_fe(const GearFeCase& c, const GearMeshSizes& sizes, double sample_step_m,
                           const FeTools& tools, const std::filesystem::path& work_dir,
                           const std::string& name, int threads, double timeout_s) {
  if (!(c.normal_force_N > 0.0)) throw std::invalid_argument("gear FE model: no load");
  if (!(c.face_width_m > 0.0)) throw std::invalid_argument("gear FE model: no face width");
  const geometry::PinionGeometry g(c.pinion);
  if (!(c.load_radius_m >= g.form_radius() - 1e-9 && c.load_radius_m <= g.tip_radius() + 1e-9)) {
    throw std::invalid_argument("gear FE model: the load radius is not on the active flank (" +
                                std::to_string(g.form_radius()) + " to " +
                                std::to_string(g.tip_radius()) + " m)");
  }
  if (!(c.fixed_radius_m > 0.0 && c.fixed_radius_m < g.root_radius())) {
    throw std::invalid_argument("gear FE model: the held radius must lie inside the root circle");
  }
  GearFeResult out;
  out.sizes = sizes;
  out.load = load_patch(g, c);
  out.sizes.load_band = std::max(sizes.load_band, 1.5 * out.load.half_width_m);
  const MeshSpec region = model_region(g, c, sample_step_m, out);

  FeModel model = meshed_model(region, c.E_Pa, c.nu, tools, work_dir, name, timeout_s, out.mesh_s);
  model.supports.push_back({group_nodes(model.mesh, "fixed"), true, true});
  const std::vector<BoundaryEdge> boundary = boundary_edges(model.mesh);
  model.nodal_forces = flank_forces(model.mesh, boundary, c, out.load);

  out.solution = solve_with_calculix(model, tools, work_dir, name, threads, timeout_s);
  out.solve_s = out.solution.wall_s;
  out.reaction_N = c.face_width_m * out.solution.reaction;
  out.mesh = std::move(model.mesh);
  out.load_displacement_m = load_displacement(model.nodal_forces, out.solution);
  out.centre_displacement_m =
      boundary_displacement(out.mesh, group_edges(out.mesh, boundary, "loaded_flank"), out.solution,
                            out.load.centre, out.load.direction);
  stress_on_fillets(boundary, out);
  return out;
}

}  // namespace gearsph::fe
