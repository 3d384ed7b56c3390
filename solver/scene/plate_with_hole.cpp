// Kirsch's problem (validation.md section 10): a plate W x L with a central
// hole of radius a, pulled by a uniform traction sigma on its two short
// ends and relaxed to the static state (load ramp and mass-proportional
// damping of the slowest mode, as the Hertz scene does). At the hole's
// edge, across the load, the hoop stress peaks at Kt sigma: Kt = 3 for a
// small hole in a wide plate (Kirsch 1898); for a finite width the net-
// section factor of Howland's solution, in Heywood's fit
//   Kt_net = 2 + (1 - d/W)^3,  sigma_max = Kt_net sigma W / (W - d)
// (Pilkey & Pilkey, Peterson's Stress Concentration Factors, 3rd ed., chart
// 4.1 and eq. 4.3), within about 1 % of Howland's values for d/W <= 0.5.
// The stress is the same in plane strain and plane stress (tractions only).
//
// The peak is read from the stress recovered at points of the hole's true
// outline (diagnostics/stress_recovery.hpp), not from one particle; the
// largest hoop stress of a single particle at the hole is reported beside
// it, for contrast.
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
// Points on the hole's outline where the stress is recovered.
constexpr int kHolePoints = 720;
// Half-width of the arc over which the hole's stretch is differentiated, in
// fine spacings.
constexpr double kEdgeWindow = 3.0;

// The traction sigma on the end x = end_x (outward normal +-x) as loads on
// the particles standing for that edge, each its share of the edge's length
// (half the distance to either neighbour along it).
void end_traction(Simulation& sim, const std::vector<std::size_t>& edge, double sign, double sigma,
                  double y_lo, double y_hi) {
  Particles& p = sim.particles;
  std::vector<std::size_t> by_y = edge;
  std::sort(by_y.begin(), by_y.end(),
            [&](std::size_t a, std::size_t b) { return p.y[a] < p.y[b]; });
  for (std::size_t k = 0; k < by_y.size(); ++k) {
    const double below = k == 0 ? y_lo : 0.5 * (p.y[by_y[k - 1]] + p.y[by_y[k]]);
    const double above = k + 1 == by_y.size() ? y_hi : 0.5 * (p.y[by_y[k]] + p.y[by_y[k + 1]]);
    const std::size_t i = by_y[k];
    p.load_ax[i] = sign * sigma * (above - below) / p.mass[i];  // force per unit thickness / mass
  }
}

}  // namespace

Scene build_plate_with_hole(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double W = s.at("width_m").get<double>(), L = s.at("length_m").get<double>();
  const double a = s.at("hole_radius_m").get<double>();
  const double sigma = s.at("tension_Pa").get<double>();
  const Material mat = read_material(s.at("material"));
  if (2.0 * a > 0.6 * W) {
    throw JobError("/scene/hole_radius_m",
                   "the hole's diameter must be at most 0.6 of the width (Heywood's fit of the "
                   "finite-width factor holds up to d/W = 0.6)");
  }
  if (L < 2.0 * W) {
    throw JobError("/scene/length_m",
                   "the plate must be at least twice as long as it is wide, or its loaded ends "
                   "change the stress at the hole");
  }

  Scene scene;
  scene.type = "plate_with_hole";
  Simulation& sim = scene.sim;
  sim.discretization = in.discretization;
  const ParticleLayout layout = particle_layout(in.discretization, ParticleLayout::BodyFitted);
  const bool fitted = layout == ParticleLayout::BodyFitted;
  Discretization& d = sim.discretization;
  if (d.dx <= 0) d.dx = fitted ? W / 20.0 : a / 5.0;
  const double fine = fitted ? (d.fine_dx > 0 ? d.fine_dx : std::min(d.dx, a / 10.0)) : d.dx;
  const double grading = d.grading > 0 ? d.grading : geometry::kDefaultGrading;
  if (fine > d.dx) {
    throw JobError("/discretization/fine_spacing_m",
                   "the fine spacing must not exceed the bulk spacing");
  }
  if (a < 2.0 * fine) {
    throw JobError("/discretization",
                   "the hole needs a spacing of at most a quarter of its "
                   "diameter to be drawn at all");
  }
  add_body(sim, "plate", mat);
  const geometry::Polygon hole = geometry::circle({0.0, 0.0}, a, 1e-5 * a);
  const geometry::Polygon rect = {
      {-0.5 * L, -0.5 * W}, {0.5 * L, -0.5 * W}, {0.5 * L, 0.5 * W}, {-0.5 * L, 0.5 * W}};
  double x_end = 0.5 * L, y_end = 0.5 * W;
  if (fitted) {
    geometry::SpacingField field(d.dx, grading);
    field.add_feature(hole, fine, true);
    add_body_fitted(sim, geometry::make_region(rect, {hole}), field,
                    [](double, double) { return 0; });
  } else {
    const long nx = lattice::cells(L, d.dx), ny = lattice::cells(W, d.dx);
    x_end = 0.5 * nx * d.dx;
    y_end = 0.5 * ny * d.dx;
    lattice::fill_rectangle(-x_end, -y_end, nx, ny, d.dx, [&](double x, double y) {
      if (x * x + y * y > a * a) add_particle(sim, x, y, 0);
    });
  }
  end_body(sim);
  Particles& p = sim.particles;

  // The traction on both ends: body-fitted particles on the edge, or a
  // lattice's end columns (their cells' faces are the edge).
  std::vector<std::size_t> left, right;
  const double band = fitted ? 1e-9 * L : d.dx;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.x[i] > x_end - band) right.push_back(i);
    if (p.x[i] < -x_end + band) left.push_back(i);
  }
  end_traction(sim, right, 1.0, sigma, -y_end, y_end);
  end_traction(sim, left, -1.0, sigma, -y_end, y_end);

  scene.outlines.push_back({"plate", 0, {}, true});
  for (const geometry::Point& q : rect) scene.outlines.back().points.push_back({q.x, q.y});
  scene.outlines.push_back({"hole", 0, {}, true});
  for (const geometry::Point& q : hole) scene.outlines.back().points.push_back({q.x, q.y});
  sim.domain = grown_bounds(p, L);

  // Dynamic relaxation: the slowest mode loaded is the plate's stretch along
  // its length, omega = pi c / L with the plane-strain bar speed.
  const double c_bar = std::sqrt(mat.E / (mat.rho0 * (1.0 - mat.nu * mat.nu)));
  const double omega1 = kPi * c_bar / (2.0 * x_end);
  sim.damping_1_s = omega1;
  sim.load_ramp_s = 10.0 * 2.0 * kPi / omega1;
  scene.default_end_s = 2.0 * sim.load_ramp_s;

  // References: Heywood's fit of Howland's finite-width factor.
  const double width = 2.0 * y_end, d_over_w = 2.0 * a / width;
  const double kt_net = 2.0 + std::pow(1.0 - d_over_w, 3);
  const double sigma_net = sigma * width / (width - 2.0 * a);
  const double reference = kt_net * sigma_net;

  // The hole's outline, where the stress is recovered, and the particles
  // nearest it (the contrast: one particle's stress).
  std::vector<geometry::Point> at;
  for (int k = 0; k < kHolePoints; ++k) {
    const double t = 2.0 * kPi * k / kHolePoints;
    at.push_back({a * std::cos(t), a * std::sin(t)});
  }
  auto recovery = std::make_shared<const diagnostics::StressRecovery>(sim, 0, at);
  std::vector<std::size_t> rim;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (std::hypot(p.x[i], p.y[i]) < a + 0.75 * p.spacing[i]) rim.push_back(i);
  }
  // Hoop stress t.sigma.t at angle theta, t = (-sin, cos).
  auto hoop = [](double xx, double yy, double xy, double theta) {
    const double c = std::cos(theta), sn = std::sin(theta);
    return sn * sn * xx - 2.0 * sn * c * xy + c * c * yy;
  };
  // The hoop stress of the traction-free hole from the hole's own stretch
  // (diagnostics/edge_stress.hpp), over a window of two fine spacings.
  diagnostics::EdgeCurve edge;
  edge.reference = at;
  edge.closed = true;
  for (int k = 0; k < kHolePoints; ++k) edge.arc.push_back(2.0 * kPi * a * k / kHolePoints);
  const Material steel = sim.bodies[0].material;
  const double window = kEdgeWindow * fine;
  auto peak = [recovery, edge, steel, window](const Simulation& s2) {
    const std::vector<diagnostics::RecoveredStress> r = recovery->recover(s2);
    diagnostics::EdgeCurve now = edge;
    for (const diagnostics::RecoveredStress& q : r) now.displacement.push_back({q.ux, q.uy});
    const std::vector<double> hoop_at =
        diagnostics::edge_tangential_stress(now, window, steel.E, steel.nu);
    std::pair<double, int> best{-1e300, 0};
    for (int k = 0; k < kHolePoints; ++k) best = std::max(best, {hoop_at[k], k});
    return best;
  };
  // The same from the recovered stress tensor, for contrast.
  auto tensor_peak = [recovery, hoop](const Simulation& s2) {
    const std::vector<diagnostics::RecoveredStress> r = recovery->recover(s2);
    double best = -1e300;
    for (int k = 0; k < kHolePoints; ++k) {
      const double t = 2.0 * kPi * k / kHolePoints;
      best = std::max(best, hoop(r[k].xx, r[k].yy, r[k].xy, t));
    }
    return best;
  };
  scene.columns.push_back(
      {"hole_peak_hoop_stress_Pa", [peak](const Simulation& s2) { return peak(s2).first; }});

  std::size_t n_fine = 0;
  for (std::size_t i = 0; i < p.n; ++i) n_fine += p.spacing[i] < 1.5 * fine;
  scene.description = {{"particles", fitted ? "body_fitted" : "lattice"},
                       {"fine_spacing_m", fine},
                       {"bulk_spacing_m", d.dx},
                       {"plate_m", {2.0 * x_end, width}},
                       {"d_over_W", d_over_w},
                       {"reference_peak_hoop_stress_Pa", reference}};

  scene.analyse = [=](const History&, const Simulation& s2) {
    nlohmann::json out;
    const auto [value, k] = peak(s2);
    double particle_peak = -1e300;
    for (std::size_t i : rim) {
      const Particles& q = s2.particles;
      particle_peak = std::max(particle_peak, hoop(q.sigma_xx(i), q.sigma_yy(i), q.sigma_xy(i),
                                                   std::atan2(q.y0[i], q.x0[i])));
    }
    out["reference"] =
        "Howland's finite-width plate, Heywood's fit: Kt_net = 2 + (1 - d/W)^3 on the net "
        "section stress sigma W / (W - d)";
    out["peak_hoop_stress_Pa"] = value;
    out["peak_angle_deg"] = 360.0 * k / kHolePoints;
    out["reference_peak_hoop_stress_Pa"] = reference;
    out["error"] = (value - reference) / reference;
    out["stress_concentration_gross"] = value / sigma;
    out["reference_stress_concentration_gross"] = reference / sigma;
    out["kirsch_infinite_plate_Pa"] = 3.0 * sigma;
    out["largest_particle_hoop_stress_Pa"] = particle_peak;
    out["peak_hoop_stress_from_stress_fit_Pa"] = tensor_peak(s2);
    out["fine_particles"] = n_fine;
    return out;
  };
  return scene;
}

}  // namespace gearsph::scenes
