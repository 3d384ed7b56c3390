// Lame's problem (validation.md section 10): a ring a..b (a thick cylinder
// in plane strain) under internal pressure p, relaxed to the static state.
// Lame (1852); in plane strain (Timoshenko & Goodier, Theory of
// Elasticity, sec. 28):
//   hoop stress at the bore   sigma_t(a) = p (b^2 + a^2) / (b^2 - a^2)
//   radial displacement       u(r) = (1 + nu) p a^2 / (E (b^2 - a^2)) [(1 - 2 nu) r + b^2 / r]
// The displacement is recovered at points of the bore's true outline
// (diagnostics/stress_recovery.hpp); the hoop stress is read from the bore's
// own stretch with the pressure as its known normal stress
// (diagnostics/edge_stress.hpp), as the fillets and Kirsch's hole are read;
// both averaged round the bore, with their spread. The stress tensor fitted
// from the rows inside, extrapolated to the bore, is reported beside it.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "solver/diagnostics/edge_stress.hpp"
#include "solver/diagnostics/stress_recovery.hpp"
#include "solver/scene/builders.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kBorePoints = 360;
// Half-width of the arc the stretch is differentiated over, in bore
// spacings (plate_with_hole.cpp's).
constexpr double kEdgeWindow = 3.0;

// Body-fitted (the default): a tenth of the wall in bulk, a twenty-fifth of
// the wall or of the bore radius at the bore, whichever is finer: the hoop
// stress falls off as 1/r^2 over the bore's radius, so a thick ring's bore
// (b/a = 4) at a twenty-fifth of its wall had six particles per radian and
// its stress fit read -11 % (docs/validation.md). The wall needs three
// spacings across it.
SceneSpacings wall_spacings(Discretization& d, double a, double b) {
  const bool fitted = particle_layout(d, ParticleLayout::BodyFitted) == ParticleLayout::BodyFitted;
  const SceneSpacings sp =
      graded_scene_spacings(d, fitted, (b - a) / 10.0, std::min(b - a, a) / 25.0);
  require_fine_within_bulk(sp);
  if (b - a < 3.0 * sp.fine) {
    throw JobError("/discretization", "the wall needs at least three spacings across it");
  }
  return sp;
}

// The ring between the bore (radius a) and the rim (b); body-fitted
// particles are fine at the bore, where the hoop stress peaks.
void fill_ring(Simulation& sim, const SceneSpacings& sp, const geometry::Polygon& bore,
               const geometry::Polygon& rim, double a, double b, const Material& mat) {
  add_body(sim, "ring", mat);
  if (sp.fitted) {
    geometry::SpacingField field(sp.dx, sp.grading);
    field.add_feature(bore, sp.fine, true);
    add_body_fitted(sim, geometry::make_region(rim, {bore}), field,
                    [](double, double) { return 0; });
  } else {
    lattice::fill_region(
        -b, -b, b, b, sp.dx, 0.0, 0.0,
        [&](double x, double y) { return x * x + y * y <= b * b && x * x + y * y > a * a; },
        [&](double x, double y) { add_particle(sim, x, y, 0); });
  }
  end_body(sim);
}

// The pressure as loads on the particles standing for the bore, each its
// share of the bore's length, pushing radially out: the body-fitted
// bore row, or a lattice's particles within a spacing of the bore.
// Returns those particles.
std::vector<std::size_t> press_bore(Simulation& sim, const SceneSpacings& sp, double a,
                                    double pressure) {
  Particles& p = sim.particles;
  std::vector<std::size_t> ring;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double r = std::hypot(p.x[i], p.y[i]);
    if (sp.fitted ? r < a * (1.0 + 1e-6) : r < a + sp.dx) ring.push_back(i);
  }
  std::sort(ring.begin(), ring.end(), [&](std::size_t u, std::size_t v) {
    return std::atan2(p.y[u], p.x[u]) < std::atan2(p.y[v], p.x[v]);
  });
  const std::size_t m = ring.size();
  for (std::size_t k = 0; k < m; ++k) {
    const std::size_t i = ring[k];
    const double t = std::atan2(p.y[i], p.x[i]);
    const double t_prev = std::atan2(p.y[ring[(k + m - 1) % m]], p.x[ring[(k + m - 1) % m]]);
    const double t_next = std::atan2(p.y[ring[(k + 1) % m]], p.x[ring[(k + 1) % m]]);
    // Half the angle to either neighbour, wrapped into (0, 2 pi).
    auto gap = [](double from, double to) {
      double g = std::fmod(to - from + 4.0 * kPi, 2.0 * kPi);
      return g;
    };
    const double share = 0.5 * (gap(t_prev, t) + gap(t, t_next)) * a;  // bore length
    const double f = pressure * share;
    p.load_ax[i] = f * std::cos(t) / p.mass[i];
    p.load_ay[i] = f * std::sin(t) / p.mass[i];
  }
  return ring;
}

// A mean round the bore and its range.
struct RoundTheBore {
  double mean = 0, min = 1e300, max = -1e300;
  void add(double v) {
    mean += v / kBorePoints;
    min = std::min(min, v);
    max = std::max(max, v);
  }
};

// Hoop stress (from the stretch, and from the stress fit) and radial
// displacement round the bore.
struct Bore {
  RoundTheBore hoop, hoop_fit, u;
};

// The bore's displacement, recovered at points of its outline from every
// particle (the bore row has it right), its hoop stress from its stretch
// under the known normal stress -p, and, for contrast, the stress tensor
// fitted from inside: the bore row carries the pressure as forces, so its
// own stress does not see the load (stress_recovery.hpp), and the fit
// extrapolates linearly from the rows inside (a quadratic one extrapolated
// across a spacing swings).
struct BoreReadout {
  std::shared_ptr<const diagnostics::StressRecovery> stress, displacement;
  diagnostics::EdgeCurve edge;
  std::vector<double> normal_stress;  // -p round the bore
  Material material;
  double window = 0.0;  // half-width of the arc differentiated [m]
};

BoreReadout bore_readout(const Simulation& sim, double a, double fine, double pressure,
                         const std::vector<std::size_t>& ring) {
  std::vector<geometry::Point> at;
  for (int k = 0; k < kBorePoints; ++k) {
    const double t = 2.0 * kPi * k / kBorePoints;
    at.push_back({a * std::cos(t), a * std::sin(t)});
  }
  std::vector<std::uint8_t> loaded(sim.particles.n, 0);
  for (std::size_t i : ring) loaded[i] = 1;
  BoreReadout r;
  r.stress = std::make_shared<const diagnostics::StressRecovery>(sim, 0, at, 1, &loaded);
  r.displacement = std::make_shared<const diagnostics::StressRecovery>(sim, 0, at);
  r.edge.reference = at;
  r.edge.closed = true;
  for (int k = 0; k < kBorePoints; ++k) r.edge.arc.push_back(2.0 * kPi * a * k / kBorePoints);
  r.normal_stress.assign(kBorePoints, -pressure);
  r.material = sim.bodies[0].material;
  r.window = kEdgeWindow * fine;
  return r;
}

Bore read_bore(const BoreReadout& readout, const Simulation& s2) {
  const std::vector<diagnostics::RecoveredStress> r = readout.stress->recover(s2);
  const std::vector<diagnostics::RecoveredStress> u_at = readout.displacement->recover(s2);
  diagnostics::EdgeCurve now = readout.edge;
  for (const diagnostics::RecoveredStress& q : u_at) now.displacement.push_back({q.ux, q.uy});
  const std::vector<double> stretch_hoop = diagnostics::edge_tangential_stress(
      now, readout.window, readout.material.E, readout.material.nu, &readout.normal_stress);
  Bore out;
  for (int k = 0; k < kBorePoints; ++k) {
    const double t = 2.0 * kPi * k / kBorePoints, c = std::cos(t), sn = std::sin(t);
    out.hoop.add(stretch_hoop[k]);
    out.hoop_fit.add(sn * sn * r[k].xx - 2.0 * sn * c * r[k].xy + c * c * r[k].yy);
    out.u.add(c * u_at[k].ux + sn * u_at[k].uy);
  }
  return out;
}

// The bore's mean hoop stress and displacement against Lame's.
nlohmann::json analyse_thick_cylinder(const Bore& r, double hoop_ref, double u_ref) {
  nlohmann::json out;
  out["reference"] =
      "Lame, plane strain: sigma_t(a) = p (b^2 + a^2)/(b^2 - a^2), u(a) = (1 + nu) p a^2 / "
      "(E (b^2 - a^2)) [(1 - 2 nu) a + b^2 / a]";
  out["bore_hoop_stress_Pa"] = r.hoop.mean;
  out["reference_bore_hoop_stress_Pa"] = hoop_ref;
  out["bore_hoop_stress_range_Pa"] = {r.hoop.min, r.hoop.max};
  out["bore_hoop_stress_method"] =
      "the bore's stretch under its known normal stress -p (diagnostics/edge_stress.hpp)";
  out["bore_hoop_stress_fit_Pa"] = r.hoop_fit.mean;
  out["bore_hoop_stress_fit_range_Pa"] = {r.hoop_fit.min, r.hoop_fit.max};
  out["bore_hoop_stress_fit_error"] = (r.hoop_fit.mean - hoop_ref) / hoop_ref;
  out["bore_displacement_m"] = r.u.mean;
  out["reference_bore_displacement_m"] = u_ref;
  out["bore_displacement_range_m"] = {r.u.min, r.u.max};
  out["hoop_error"] = (r.hoop.mean - hoop_ref) / hoop_ref;
  out["displacement_error"] = (r.u.mean - u_ref) / u_ref;
  return out;
}

}  // namespace

Scene build_thick_cylinder(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double a = s.at("inner_radius_m").get<double>(), b = s.at("outer_radius_m").get<double>();
  const double pressure = s.at("pressure_Pa").get<double>();
  const Material mat = read_material(s.at("material"));
  if (!(b > a)) throw JobError("/scene/outer_radius_m", "the outer radius must exceed the bore's");

  Scene scene = start_scene("thick_cylinder", in);
  Simulation& sim = scene.sim;
  const SceneSpacings sp = wall_spacings(sim.discretization, a, b);
  const geometry::Polygon bore = geometry::circle({0.0, 0.0}, a, 1e-5 * a);
  const geometry::Polygon rim = geometry::circle({0.0, 0.0}, b, 1e-5 * b);
  fill_ring(sim, sp, bore, rim, a, b, mat);
  const std::vector<std::size_t> ring = press_bore(sim, sp, a, pressure);
  scene.outlines.push_back(polygon_outline("ring", 0, rim));
  scene.outlines.push_back(polygon_outline("bore", 0, bore));
  sim.domain = grown_bounds(sim.particles, 2.0 * b);

  // Dynamic relaxation of the breathing mode, omega = c / r_mean with the
  // plane-strain bar speed (a thin ring's; the thick one's is near it).
  const double c_bar = std::sqrt(mat.E / (mat.rho0 * (1.0 - mat.nu * mat.nu)));
  relax_to_static(scene, c_bar / (0.5 * (a + b)));

  const double hoop_ref = pressure * (b * b + a * a) / (b * b - a * a);
  const double u_ref = (1.0 + mat.nu) * pressure * a * a / (mat.E * (b * b - a * a)) *
                       ((1.0 - 2.0 * mat.nu) * a + b * b / a);
  const BoreReadout readout = bore_readout(sim, a, sp.fine, pressure, ring);
  scene.columns.push_back({"bore_hoop_stress_Pa", [readout](const Simulation& s2) {
                             return read_bore(readout, s2).hoop.mean;
                           }});
  scene.columns.push_back({"bore_displacement_m", [readout](const Simulation& s2) {
                             return read_bore(readout, s2).u.mean;
                           }});
  scene.description = {{"reference_bore_hoop_stress_Pa", hoop_ref},
                       {"reference_bore_displacement_m", u_ref}};
  describe_spacings(scene.description, sp);
  scene.analyse = [=](const History&, const Simulation& s2) {
    return analyse_thick_cylinder(read_bore(readout, s2), hoop_ref, u_ref);
  };
  return scene;
}

}  // namespace gearsph::scenes
