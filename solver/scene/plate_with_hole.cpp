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

// Heywood's fit holds up to d/W = 0.6, and the plate's loaded ends must be
// far enough from the hole not to change the stress there.
void check_proportions(double W, double L, double a) {
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
}

// Body-fitted (the default): a twentieth of the width in bulk, a tenth of
// the hole's radius at the hole; a lattice: a fifth of the hole's radius.
SceneSpacings hole_spacings(Discretization& d, double W, double a) {
  const bool fitted = particle_layout(d, ParticleLayout::BodyFitted) == ParticleLayout::BodyFitted;
  const SceneSpacings sp = graded_scene_spacings(d, fitted, fitted ? W / 20.0 : a / 5.0, a / 10.0);
  require_fine_within_bulk(sp);
  if (a < 2.0 * sp.fine) {
    throw JobError("/discretization",
                   "the hole needs a spacing of at most a quarter of its "
                   "diameter to be drawn at all");
  }
  return sp;
}

// Fills the plate less the hole; returns the ends' x and the edges' y as
// modelled (a lattice rounds to whole cells).
geometry::Point fill_plate(Simulation& sim, const SceneSpacings& sp, const geometry::Polygon& rect,
                           const geometry::Polygon& hole, double W, double L, double a,
                           const Material& mat) {
  add_body(sim, "plate", mat);
  geometry::Point end{0.5 * L, 0.5 * W};
  if (sp.fitted) {
    geometry::SpacingField field(sp.dx, sp.grading);
    field.add_feature(hole, sp.fine, true);
    add_body_fitted(sim, geometry::make_region(rect, {hole}), field,
                    [](double, double) { return 0; });
  } else {
    const long nx = lattice::cells(L, sp.dx), ny = lattice::cells(W, sp.dx);
    end = {0.5 * nx * sp.dx, 0.5 * ny * sp.dx};
    lattice::fill_rectangle(-end.x, -end.y, nx, ny, sp.dx, [&](double x, double y) {
      if (x * x + y * y > a * a) add_particle(sim, x, y, 0);
    });
  }
  end_body(sim);
  return end;
}

// The traction on both ends: body-fitted particles on the edge, or a
// lattice's end columns (their cells' faces are the edge).
void pull_ends(Simulation& sim, const SceneSpacings& sp, double L, double sigma,
               geometry::Point end) {
  const Particles& p = sim.particles;
  std::vector<std::size_t> left, right;
  const double band = sp.fitted ? 1e-9 * L : sp.dx;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.x[i] > end.x - band) right.push_back(i);
    if (p.x[i] < -end.x + band) left.push_back(i);
  }
  end_traction(sim, right, 1.0, sigma, -end.y, end.y);
  end_traction(sim, left, -1.0, sigma, -end.y, end.y);
}

// Heywood's fit of Howland's finite-width factor: the peak hoop stress of a
// plate of modelled width pulled by sigma.
double howland_peak(double sigma, double width, double a) {
  const double d_over_w = 2.0 * a / width;
  const double kt_net = 2.0 + std::pow(1.0 - d_over_w, 3);
  const double sigma_net = sigma * width / (width - 2.0 * a);
  return kt_net * sigma_net;
}

// Hoop stress t.sigma.t at angle theta, t = (-sin, cos).
double hoop(double xx, double yy, double xy, double theta) {
  const double c = std::cos(theta), sn = std::sin(theta);
  return sn * sn * xx - 2.0 * sn * c * xy + c * c * yy;
}

// The hole's outline, where the stress is recovered, and its stretch is
// read.
struct HoleReadout {
  std::shared_ptr<const diagnostics::StressRecovery> recovery;
  diagnostics::EdgeCurve edge;
  Material material;
  double window = 0.0;  // half-width of the arc differentiated [m]
};

HoleReadout hole_readout(const Simulation& sim, double a, double fine) {
  std::vector<geometry::Point> at;
  for (int k = 0; k < kHolePoints; ++k) {
    const double t = 2.0 * kPi * k / kHolePoints;
    at.push_back({a * std::cos(t), a * std::sin(t)});
  }
  HoleReadout r;
  r.recovery = std::make_shared<const diagnostics::StressRecovery>(sim, 0, at);
  r.edge.reference = at;
  r.edge.closed = true;
  for (int k = 0; k < kHolePoints; ++k) r.edge.arc.push_back(2.0 * kPi * a * k / kHolePoints);
  r.material = sim.bodies[0].material;
  r.window = kEdgeWindow * fine;
  return r;
}

// The peak hoop stress of the traction-free hole from the hole's own
// stretch (diagnostics/edge_stress.hpp), and the outline point where it is.
std::pair<double, int> peak_hoop_stress(const HoleReadout& r, const Simulation& s2) {
  const std::vector<diagnostics::RecoveredStress> rec = r.recovery->recover(s2);
  diagnostics::EdgeCurve now = r.edge;
  for (const diagnostics::RecoveredStress& q : rec) now.displacement.push_back({q.ux, q.uy});
  const std::vector<double> hoop_at =
      diagnostics::edge_tangential_stress(now, r.window, r.material.E, r.material.nu);
  std::pair<double, int> best{-1e300, 0};
  for (int k = 0; k < kHolePoints; ++k) best = std::max(best, {hoop_at[k], k});
  return best;
}

// The same from the recovered stress tensor, for contrast.
double peak_tensor_hoop_stress(const HoleReadout& r, const Simulation& s2) {
  const std::vector<diagnostics::RecoveredStress> rec = r.recovery->recover(s2);
  double best = -1e300;
  for (int k = 0; k < kHolePoints; ++k) {
    const double t = 2.0 * kPi * k / kHolePoints;
    best = std::max(best, hoop(rec[k].xx, rec[k].yy, rec[k].xy, t));
  }
  return best;
}

// The particles nearest the hole (the contrast: one particle's stress).
std::vector<std::size_t> hole_rim(const Particles& p, double a) {
  std::vector<std::size_t> rim;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (std::hypot(p.x[i], p.y[i]) < a + 0.75 * p.spacing[i]) rim.push_back(i);
  }
  return rim;
}

double largest_particle_hoop_stress(const Particles& q, const std::vector<std::size_t>& rim) {
  double particle_peak = -1e300;
  for (std::size_t i : rim) {
    particle_peak = std::max(particle_peak, hoop(q.sigma_xx(i), q.sigma_yy(i), q.sigma_xy(i),
                                                 std::atan2(q.y0[i], q.x0[i])));
  }
  return particle_peak;
}

// The peak hoop stress at the hole against Howland's (Heywood's fit), with
// two contrasts: the recovered stress tensor's, and the largest of a
// single particle next to the hole.
nlohmann::json analyse_plate_with_hole(const HoleReadout& readout,
                                       const std::vector<std::size_t>& rim, double reference,
                                       double sigma, std::size_t n_fine, const Simulation& s2) {
  nlohmann::json out;
  const auto [value, k] = peak_hoop_stress(readout, s2);
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
  out["largest_particle_hoop_stress_Pa"] = largest_particle_hoop_stress(s2.particles, rim);
  out["peak_hoop_stress_from_stress_fit_Pa"] = peak_tensor_hoop_stress(readout, s2);
  out["fine_particles"] = n_fine;
  return out;
}

// Particles at the fine spacing (graded: near the hole).
std::size_t fine_particles(const Particles& p, double fine) {
  std::size_t n_fine = 0;
  for (std::size_t i = 0; i < p.n; ++i) n_fine += p.spacing[i] < 1.5 * fine;
  return n_fine;
}

}  // namespace

Scene build_plate_with_hole(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double W = s.at("width_m").get<double>(), L = s.at("length_m").get<double>();
  const double a = s.at("hole_radius_m").get<double>();
  const double sigma = s.at("tension_Pa").get<double>();
  const Material mat = read_material(s.at("material"));
  check_proportions(W, L, a);

  Scene scene = start_scene("plate_with_hole", in);
  Simulation& sim = scene.sim;
  const SceneSpacings sp = hole_spacings(sim.discretization, W, a);
  const geometry::Polygon hole = geometry::circle({0.0, 0.0}, a, 1e-5 * a);
  const geometry::Polygon rect = {
      {-0.5 * L, -0.5 * W}, {0.5 * L, -0.5 * W}, {0.5 * L, 0.5 * W}, {-0.5 * L, 0.5 * W}};
  const geometry::Point end = fill_plate(sim, sp, rect, hole, W, L, a, mat);
  pull_ends(sim, sp, L, sigma, end);
  scene.outlines.push_back(polygon_outline("plate", 0, rect));
  scene.outlines.push_back(polygon_outline("hole", 0, hole));
  sim.domain = grown_bounds(sim.particles, L);

  // Dynamic relaxation: the slowest mode loaded is the plate's stretch along
  // its length, omega = pi c / L with the plane-strain bar speed.
  const double c_bar = std::sqrt(mat.E / (mat.rho0 * (1.0 - mat.nu * mat.nu)));
  relax_to_static(scene, kPi * c_bar / (2.0 * end.x));

  const double width = 2.0 * end.y;
  const double reference = howland_peak(sigma, width, a);
  const HoleReadout readout = hole_readout(sim, a, sp.fine);
  scene.columns.push_back({"hole_peak_hoop_stress_Pa", [readout](const Simulation& s2) {
                             return peak_hoop_stress(readout, s2).first;
                           }});

  const std::vector<std::size_t> rim = hole_rim(sim.particles, a);
  const std::size_t n_fine = fine_particles(sim.particles, sp.fine);
  scene.description = {{"plate_m", {2.0 * end.x, width}},
                       {"d_over_W", 2.0 * a / width},
                       {"reference_peak_hoop_stress_Pa", reference}};
  describe_spacings(scene.description, sp);

  scene.analyse = [=](const History&, const Simulation& s2) {
    return analyse_plate_with_hole(readout, rim, reference, sigma, n_fine, s2);
  };
  return scene;
}

}  // namespace gearsph::scenes
