// Lame's problem (validation.md section 10): a ring a..b (a thick cylinder
// in plane strain) under internal pressure p, relaxed to the static state.
// Lame (1852); in plane strain (Timoshenko & Goodier, Theory of
// Elasticity, sec. 28):
//   hoop stress at the bore   sigma_t(a) = p (b^2 + a^2) / (b^2 - a^2)
//   radial displacement       u(r) = (1 + nu) p a^2 / (E (b^2 - a^2)) [(1 - 2 nu) r + b^2 / r]
// Both are read from the stress and displacement recovered at points of the
// bore's true outline (diagnostics/stress_recovery.hpp), averaged round it;
// their spread round the bore is reported too.
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>

#include "solver/diagnostics/stress_recovery.hpp"
#include "solver/scene/builders.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

namespace {
constexpr double kPi = std::numbers::pi;
constexpr int kBorePoints = 360;
}  // namespace

Scene build_thick_cylinder(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double a = s.at("inner_radius_m").get<double>(), b = s.at("outer_radius_m").get<double>();
  const double pressure = s.at("pressure_Pa").get<double>();
  const Material mat = read_material(s.at("material"));
  if (!(b > a)) throw JobError("/scene/outer_radius_m", "the outer radius must exceed the bore's");

  Scene scene;
  scene.type = "thick_cylinder";
  Simulation& sim = scene.sim;
  sim.discretization = in.discretization;
  const ParticleLayout layout = particle_layout(in.discretization, ParticleLayout::BodyFitted);
  const bool fitted = layout == ParticleLayout::BodyFitted;
  Discretization& d = sim.discretization;
  if (d.dx <= 0) d.dx = (b - a) / 10.0;
  const double fine = fitted ? (d.fine_dx > 0 ? d.fine_dx : std::min(d.dx, (b - a) / 25.0)) : d.dx;
  const double grading = d.grading > 0 ? d.grading : geometry::kDefaultGrading;
  if (fine > d.dx) {
    throw JobError("/discretization/fine_spacing_m",
                   "the fine spacing must not exceed the bulk spacing");
  }
  if (b - a < 3.0 * fine) {
    throw JobError("/discretization", "the wall needs at least three spacings across it");
  }
  add_body(sim, "ring", mat);
  const geometry::Polygon bore = geometry::circle({0.0, 0.0}, a, 1e-5 * a);
  const geometry::Polygon rim = geometry::circle({0.0, 0.0}, b, 1e-5 * b);
  if (fitted) {
    geometry::SpacingField field(d.dx, grading);
    field.add_feature(bore, fine, true);
    add_body_fitted(sim, geometry::make_region(rim, {bore}), field,
                    [](double, double) { return 0; });
  } else {
    lattice::fill_region(
        -b, -b, b, b, d.dx, 0.0, 0.0,
        [&](double x, double y) { return x * x + y * y <= b * b && x * x + y * y > a * a; },
        [&](double x, double y) { add_particle(sim, x, y, 0); });
  }
  end_body(sim);
  Particles& p = sim.particles;

  // The pressure as loads on the particles standing for the bore, each its
  // share of the bore's length, pushing radially out: the body-fitted
  // bore row, or a lattice's particles within a spacing of the bore.
  std::vector<std::size_t> ring;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double r = std::hypot(p.x[i], p.y[i]);
    if (fitted ? r < a * (1.0 + 1e-6) : r < a + d.dx) ring.push_back(i);
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

  scene.outlines.push_back({"ring", 0, {}, true});
  for (const geometry::Point& q : rim) scene.outlines.back().points.push_back({q.x, q.y});
  scene.outlines.push_back({"bore", 0, {}, true});
  for (const geometry::Point& q : bore) scene.outlines.back().points.push_back({q.x, q.y});
  sim.domain = grown_bounds(p, 2.0 * b);

  // Dynamic relaxation of the breathing mode, omega = c / r_mean with the
  // plane-strain bar speed (a thin ring's; the thick one's is near it).
  const double c_bar = std::sqrt(mat.E / (mat.rho0 * (1.0 - mat.nu * mat.nu)));
  const double omega1 = c_bar / (0.5 * (a + b));
  sim.damping_1_s = omega1;
  sim.load_ramp_s = 10.0 * 2.0 * kPi / omega1;
  scene.default_end_s = 2.0 * sim.load_ramp_s;

  const double hoop_ref = pressure * (b * b + a * a) / (b * b - a * a);
  const double u_ref = (1.0 + mat.nu) * pressure * a * a / (mat.E * (b * b - a * a)) *
                       ((1.0 - 2.0 * mat.nu) * a + b * b / a);

  std::vector<geometry::Point> at;
  for (int k = 0; k < kBorePoints; ++k) {
    const double t = 2.0 * kPi * k / kBorePoints;
    at.push_back({a * std::cos(t), a * std::sin(t)});
  }
  // The bore row carries the pressure as forces: its own stress does not
  // see the load (stress_recovery.hpp), so the bore's stress is extrapolated
  // from inside, by a linear fit (a quadratic one extrapolated across a
  // spacing swings); its displacement, which the row has right, from all.
  std::vector<std::uint8_t> loaded(p.n, 0);
  for (std::size_t i : ring) loaded[i] = 1;
  auto recovery = std::make_shared<const diagnostics::StressRecovery>(sim, 0, at, 1, &loaded);
  auto moved = std::make_shared<const diagnostics::StressRecovery>(sim, 0, at);
  // Mean hoop stress and radial displacement round the bore, and their ranges.
  struct Bore {
    double hoop = 0, hoop_min = 1e300, hoop_max = -1e300, u = 0, u_min = 1e300, u_max = -1e300;
  };
  auto read = [recovery, moved](const Simulation& s2) {
    const std::vector<diagnostics::RecoveredStress> r = recovery->recover(s2);
    const std::vector<diagnostics::RecoveredStress> u_at = moved->recover(s2);
    Bore out;
    for (int k = 0; k < kBorePoints; ++k) {
      const double t = 2.0 * kPi * k / kBorePoints, c = std::cos(t), sn = std::sin(t);
      const double hoop = sn * sn * r[k].xx - 2.0 * sn * c * r[k].xy + c * c * r[k].yy;
      const double u = c * u_at[k].ux + sn * u_at[k].uy;
      out.hoop += hoop / kBorePoints;
      out.u += u / kBorePoints;
      out.hoop_min = std::min(out.hoop_min, hoop);
      out.hoop_max = std::max(out.hoop_max, hoop);
      out.u_min = std::min(out.u_min, u);
      out.u_max = std::max(out.u_max, u);
    }
    return out;
  };
  scene.columns.push_back(
      {"bore_hoop_stress_Pa", [read](const Simulation& s2) { return read(s2).hoop; }});
  scene.columns.push_back(
      {"bore_displacement_m", [read](const Simulation& s2) { return read(s2).u; }});
  scene.description = {{"particles", fitted ? "body_fitted" : "lattice"},
                       {"fine_spacing_m", fine},
                       {"bulk_spacing_m", d.dx},
                       {"reference_bore_hoop_stress_Pa", hoop_ref},
                       {"reference_bore_displacement_m", u_ref}};
  scene.analyse = [=](const History&, const Simulation& s2) {
    const Bore r = read(s2);
    nlohmann::json out;
    out["reference"] =
        "Lame, plane strain: sigma_t(a) = p (b^2 + a^2)/(b^2 - a^2), u(a) = (1 + nu) p a^2 / "
        "(E (b^2 - a^2)) [(1 - 2 nu) a + b^2 / a]";
    out["bore_hoop_stress_Pa"] = r.hoop;
    out["reference_bore_hoop_stress_Pa"] = hoop_ref;
    out["bore_hoop_stress_range_Pa"] = {r.hoop_min, r.hoop_max};
    out["bore_displacement_m"] = r.u;
    out["reference_bore_displacement_m"] = u_ref;
    out["bore_displacement_range_m"] = {r.u_min, r.u_max};
    out["hoop_error"] = (r.hoop - hoop_ref) / hoop_ref;
    out["displacement_error"] = (r.u - u_ref) / u_ref;
    return out;
  };
  return scene;
}

}  // namespace gearsph::scenes
