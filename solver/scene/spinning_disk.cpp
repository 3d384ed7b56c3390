// Rigidly spinning disk (validation.md section 4): objectivity.
//  - free (default): a stress-free disk set spinning at omega. The only
//    physical stress is the centrifugal one, of order rho omega^2 R^2
//    (plane strain, steady: von Mises at most ~0.17 rho omega^2 R^2 for
//    nu = 0.3; starting unstressed, the dynamic peak is up to about twice
//    that). Spurious strain rates from a non-objective rate or an inexact
//    velocity gradient would instead build stress of order G omega t.
//  - driven: every particle follows the rigid rotation exactly and the disk
//    carries a uniform initial deviatoric stress S0; the Jaumann rate must
//    give S(t) = R(omega t) S0 R(omega t)^T. Catches spin sign errors.
// Particles on a lattice (the default; the rim a staircase) or body-fitted
// on the true circle, optionally graded from a fine spacing at the centre,
// where the centrifugal stress peaks.
#include <cmath>
#include <numbers>

#include "solver/scene/builders.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

namespace {

// A uniform deviatoric stress in the plane (S_zz = -(S_xx + S_yy)).
struct PlaneDeviator {
  double xx = 0, yy = 0, xy = 0;
};

PlaneDeviator read_initial_stress(const nlohmann::json& s) {
  PlaneDeviator s0;
  if (s.contains("initial_stress_Pa")) {
    const auto& st = s.at("initial_stress_Pa");
    s0.xx = st.at("xx").get<double>();
    s0.yy = st.at("yy").get<double>();
    s0.xy = st.at("xy").get<double>();
  }
  return s0;
}

// The disk, its particles following `motion` (driven: the rigid rotation).
// Body-fitted particles may be fine at the centre, where the centrifugal
// stress peaks.
void fill_disk(Simulation& sim, const SceneSpacings& sp, double R, int motion,
               const Material& mat) {
  const double dx = sp.dx;
  add_body(sim, "disk", mat);
  if (sp.fitted) {
    geometry::SpacingField field(dx, sp.grading);
    if (sp.fine < dx) field.add_feature({{-0.5 * sp.fine, 0.0}, {0.5 * sp.fine, 0.0}}, sp.fine);
    add_body_fitted(sim, geometry::make_region(geometry::circle({0.0, 0.0}, R, 1e-5 * R)), field,
                    [motion](double, double) { return motion; });
  } else {
    lattice::fill_region(
        -R, -R, R, R, dx, -R, -R, [&](double x, double y) { return x * x + y * y <= R * R; },
        [&](double x, double y) { add_particle(sim, x, y, motion); });
  }
  end_body(sim);
}

// The rigid rotation at omega and the initial deviatoric stress S0.
void set_initial_state(Particles& p, double omega, const PlaneDeviator& s0) {
  for (std::size_t i = 0; i < p.n; ++i) {
    p.vx[i] = -omega * p.y[i];
    p.vy[i] = omega * p.x[i];
    p.sxx[i] = s0.xx;
    p.syy[i] = s0.yy;
    p.sxy[i] = s0.xy;
    p.szz[i] = -(s0.xx + s0.yy);  // S0 is a deviator
  }
}

// What the Jaumann rate must give: S(t) = R(omega t) S0 R(omega t)^T,
// checked on the particles more than a kernel support inside the rim.
struct RotatedStress {
  PlaneDeviator s0;
  double s0_norm = 0.0;
  double omega = 0.0;
  double R = 0.0, support = 0.0;  // the disk's radius, the kernel's reach
};

// Largest deviation of interior particles from R S0 R^T, relative to |S0|.
double stress_rotation_error(const RotatedStress& check, const Simulation& s2) {
  if (check.s0_norm == 0.0) return 0.0;
  const double s0xx = check.s0.xx, s0yy = check.s0.yy, s0xy = check.s0.xy;
  const Particles& q = s2.particles;
  const double c = std::cos(check.omega * s2.time), sn = std::sin(check.omega * s2.time);
  // R S0 R^T with R the counter-clockwise rotation by omega t.
  const double exx = c * c * s0xx - 2 * c * sn * s0xy + sn * sn * s0yy;
  const double eyy = sn * sn * s0xx + 2 * c * sn * s0xy + c * c * s0yy;
  const double exy = c * sn * (s0xx - s0yy) + (c * c - sn * sn) * s0xy;
  double worst = 0.0;
  for (std::size_t i = 0; i < q.n; ++i) {
    if (std::hypot(q.x[i], q.y[i]) > check.R - check.support) continue;
    const double dev = std::sqrt(std::pow(q.sxx[i] - exx, 2) + std::pow(q.syy[i] - eyy, 2) +
                                 2 * std::pow(q.sxy[i] - exy, 2));
    worst = std::max(worst, dev / check.s0_norm);
  }
  return worst;
}

// The peak von Mises stress against the centrifugal scale, and the worst
// stress rotation error.
nlohmann::json analyse_spinning_disk(const History& h, double scale, double nu) {
  nlohmann::json a;
  const std::vector<double> vm = h.column("max_von_mises_Pa");
  double peak = 0;
  for (double v : vm) peak = std::max(peak, v);
  a["centrifugal_scale_Pa"] = scale;
  a["max_von_mises_Pa"] = peak;
  a["von_mises_over_scale"] = scale > 0 ? peak / scale : 0.0;
  // Steady plane-strain spinning disk, centre: |sigma_r - sigma_z| =
  // (3 - 2nu)/(8(1 - nu)) (1 - 2nu) rho omega^2 R^2 (Timoshenko & Goodier, sec. 32).
  a["steady_centre_von_mises_Pa"] = (3 - 2 * nu) / (8 * (1 - nu)) * (1 - 2 * nu) * scale;
  const std::vector<double> err = h.column("stress_rotation_error");
  double worst = 0;
  for (double e : err) worst = std::max(worst, e);
  a["max_stress_rotation_error"] = worst;
  return a;
}

}  // namespace

Scene build_spinning_disk(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double R = s.at("radius_m").get<double>();
  const double omega = s.at("omega_rad_s").get<double>();
  const bool driven = s.at("driven").get<bool>();
  const Material mat = read_material(s.at("material"));
  const PlaneDeviator s0 = read_initial_stress(s);

  Scene scene = start_scene("spinning_disk", in);
  scene.history_every_step = true;  // the peak stress and rotation error over the turn
  Simulation& sim = scene.sim;
  const SceneSpacings sp = lattice_scene_spacings(sim.discretization, R / 15.0);
  if (R < 3 * sp.dx)
    throw JobError("/scene/radius_m", "the disk must be at least 3 spacings in radius");
  int motion = 0;
  if (driven) {
    sim.motions.push_back(Motion::rotation("rigid rotation", 0.0, 0.0, omega));
    motion = 1;
  }
  fill_disk(sim, sp, R, motion, mat);
  set_initial_state(sim.particles, omega, s0);
  sim.domain = grown_bounds(sim.particles, R);

  const double scale = mat.rho0 * omega * omega * R * R;
  RotatedStress check;
  check.s0 = s0;
  check.s0_norm = std::sqrt(s0.xx * s0.xx + s0.yy * s0.yy + 2 * s0.xy * s0.xy);
  check.omega = omega;
  check.R = R;
  check.support = kernel_support(sim.discretization.kernel) * sim.h();
  scene.columns.push_back({"stress_rotation_error", [check](const Simulation& s2) {
                             return stress_rotation_error(check, s2);
                           }});

  scene.default_end_s = 2.0 * std::numbers::pi / std::abs(omega);  // one revolution
  scene.description = {{"radius_m", R},
                       {"driven", driven},
                       {"centrifugal_scale_Pa", scale},
                       {"initial_stress_norm_Pa", check.s0_norm}};
  describe_spacings(scene.description, sp);
  scene.analyse = [scale, nu = mat.nu](const History& h, const Simulation&) {
    return analyse_spinning_disk(h, scale, nu);
  };
  return scene;
}

}  // namespace gearsph::scenes
