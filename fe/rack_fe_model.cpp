#include "fe/rack_fe_model.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "fe/gmsh_mesher.hpp"
#include "fe/tri_mesh.hpp"
#include "solver/geometry/gear_profile.hpp"
#include "solver/geometry/mesh_placement.hpp"
#include "solver/geometry/rack_profile.hpp"

namespace gearsph::fe {

namespace {

constexpr double kCornerRad = 25.0 * 3.141592653589793 / 180.0;

}  // namespace

RackFeResult solve_rack_fe(const GearFeCase& c, const GearLoadPatch& load, double element_size_m,
                           const FeTools& tools, const std::filesystem::path& work_dir,
                           const std::string& name, int threads, double timeout_s) {
  geometry::RackSpec rs;
  // The static check's rack of one tooth (geometry/mesh_placement.hpp): the
  // same root, the same tip.
  rs.teeth = 1;
  const geometry::MatingRackShape shape =
      geometry::mating_rack_shape(geometry::PinionGeometry(c.pinion), rs.teeth);
  rs.profile = shape.profile;
  rs.tip_radius_coef = shape.tip_radius_coef;
  rs.back_thickness_m = c.rack_back_m > 0.0 ? c.rack_back_m : 2.0 * rs.profile.module_m;
  rs.backlash_m = c.rack_backlash_m;
  const geometry::RackGeometry rack(rs);
  const geometry::Polygon& poly = rack.outline();
  const double alpha = rs.profile.pressure_angle_rad;
  const double m = rs.profile.module_m;

  // Where the line of action meets the right flank: the pinion's load
  // radius r lies rho(r) - rho(r_pitch) along it from the pitch point
  // (rho = sqrt(r^2 - r_b^2)), and the line of action is normal to the
  // flank, so the rack's point sits that distance times sin(alpha) below the
  // datum line (the pinion's addendum meets the rack's dedendum).
  const geometry::PinionGeometry pinion(c.pinion);
  const double rb = pinion.base_radius(), rp = pinion.pitch_radius();
  const double along = std::sqrt(std::max(0.0, load.radius_m * load.radius_m - rb * rb)) -
                       std::sqrt(rp * rp - rb * rb);
  const double y = -along * std::sin(alpha);
  const Point centre{0.5 * rack.datum_thickness() - y * std::tan(alpha), y};

  // The back's straight bottom, and the loaded flank.
  double y_low = poly[0].y;
  for (const Point& q : poly) y_low = std::min(y_low, q.y);
  std::vector<std::size_t> cuts;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    if (std::abs(poly[k].y - y_low) < 1e-12) cuts.push_back(k);
  }
  // The flank is straight: the outline's edge nearest the load point.
  std::size_t f0 = 0;
  double nearest = 1e300;
  for (std::size_t k = 0; k < poly.size(); ++k) {
    const Point a = poly[k], b = poly[(k + 1) % poly.size()];
    const Point e = b - a;
    const double t = std::clamp(
        ((centre - a).x * e.x + (centre - a).y * e.y) / (e.x * e.x + e.y * e.y), 0.0, 1.0);
    const double d = geometry::norm(a + t * e - centre);
    if (d < nearest) {
      nearest = d;
      f0 = k;
    }
  }
  const std::size_t f1 = (f0 + 1) % poly.size();
  cuts.push_back(f0);
  cuts.push_back(f1);
  // The rack's straight flank is one chord between its fillet's and its tip
  // rounding's samples (gmsh_mesher.hpp).
  const PolygonPieces pieces = polygon_curves(poly, cuts, kCornerRad, true);
  CurveLoop loop;
  for (std::size_t i = 0; i < pieces.curves.size(); ++i) {
    Curve piece = pieces.curves[i];
    const std::size_t v0 = pieces.first_vertex[i];
    const std::size_t v1 = pieces.first_vertex[(i + 1) % pieces.curves.size()];
    bool bottom = true;
    for (const Point& q : piece.points) bottom = bottom && std::abs(q.y - y_low) < 1e-12;
    if (bottom) {
      piece.group = "back";
    } else if ((v0 == f0 && v1 == f1) || (v0 == f1 && v1 == f0)) {
      piece.group = "loaded_flank";
    }
    loop.push_back(std::move(piece));
  }
  // Elements of `element_size_m` at the load, at most m/16 anywhere (the
  // root fillets' quadratic edges fold at coarser sizes).
  MeshSpec spec;
  spec.loops.push_back(std::move(loop));
  spec.size_max = std::min(5.0 * element_size_m, m / 16.0);
  SizeZone zone;
  zone.points = {centre};
  zone.size_min = std::min(element_size_m, m / 16.0);
  zone.size_max = spec.size_max;
  zone.dist_min = 1.5 * load.half_width_m + m / 16.0;
  zone.dist_max = 1.5 * m;
  spec.zones = {zone};

  RackFeResult out;
  out.load_point = centre;
  FeModel model =
      meshed_model(spec, c.rack_E_Pa, c.rack_nu, tools, work_dir, name, timeout_s, out.mesh_s);
  const std::vector<BoundaryEdge> boundary = boundary_edges(model.mesh);
  const std::vector<BoundaryEdge> flank = group_edges(model.mesh, boundary, "loaded_flank");
  const std::vector<BoundaryEdge> back = group_edges(model.mesh, boundary, "back");
  if (flank.empty() || back.empty()) {
    throw std::logic_error("rack FE model: the loaded flank or the back is not on the outline");
  }
  // The pinion's Hertz pressure on the rack's flank, scaled to F_n / b.
  const double line_load = c.normal_force_N / c.face_width_m;
  const std::vector<Point> hertz = hertz_forces(model.mesh, flank, centre, load, line_load);
  Point total;
  for (const Point& f : hertz) total = total + f;
  // The back: held in y, pushed in x against the load's x part; one node
  // holds x (the rigid slide only).
  const double width = rack.pitch();
  std::vector<Point> push = traction_forces(
      model.mesh, back,
      [&](Point, Point) {
        return Point{-total.x / width, 0.0};
      },
      8);
  model.nodal_forces = hertz;
  for (std::size_t k = 0; k < push.size(); ++k)
    model.nodal_forces[k] = model.nodal_forces[k] + push[k];
  const std::vector<int> back_nodes = group_nodes(model.mesh, "back");
  model.supports.push_back({back_nodes, false, true});
  model.supports.push_back({{back_nodes.front()}, true, false});

  out.solution = solve_with_calculix(model, tools, work_dir, name, threads, timeout_s);
  out.solve_s = out.solution.wall_s;
  out.load_displacement_m = load_displacement(hertz, out.solution);
  // The area mean along the load: over a six-node triangle a quadratic
  // field's mean is that of its three mid-side nodes.
  const Point dir = (1.0 / geometry::norm(total)) * total;
  double area = 0.0, mean = 0.0;
  for (const auto& e : model.mesh.elements) {
    const Point a = model.mesh.nodes[e[0]], b = model.mesh.nodes[e[1]], d = model.mesh.nodes[e[2]];
    const double ar = 0.5 * std::abs((b.x - a.x) * (d.y - a.y) - (d.x - a.x) * (b.y - a.y));
    double u = 0.0;
    for (int q = 3; q < 6; ++q) {
      const Point v = out.solution.displacement[e[q]];
      u += v.x * dir.x + v.y * dir.y;
    }
    area += ar;
    mean += ar * u / 3.0;
  }
  out.mean_displacement_m = mean / area;
  out.compliance_m2_per_N = (out.load_displacement_m - out.mean_displacement_m) / line_load;
  out.centre_displacement_m = boundary_displacement(model.mesh, flank, out.solution, centre, dir);
  out.centre_compliance_m2_per_N =
      (out.centre_displacement_m - out.mean_displacement_m) / line_load;
  out.mesh = std::move(model.mesh);
  return out;
}

}  // namespace gearsph::fe
