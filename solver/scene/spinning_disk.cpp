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

Scene build_spinning_disk(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double R = s.at("radius_m").get<double>();
  const double omega = s.at("omega_rad_s").get<double>();
  const bool driven = s.at("driven").get<bool>();
  const Material mat = read_material(s.at("material"));
  double s0xx = 0, s0yy = 0, s0xy = 0;
  if (s.contains("initial_stress_Pa")) {
    const auto& st = s.at("initial_stress_Pa");
    s0xx = st.at("xx").get<double>();
    s0yy = st.at("yy").get<double>();
    s0xy = st.at("xy").get<double>();
  }

  Scene scene;
  scene.type = "spinning_disk";
  Simulation& sim = scene.sim;
  sim.discretization = in.discretization;
  Discretization& d = sim.discretization;
  const auto [fitted, dx, fine] = lattice_scene_spacings(d, R / 15.0);
  if (R < 3 * dx)
    throw JobError("/scene/radius_m", "the disk must be at least 3 spacings in radius");

  int motion = 0;
  if (driven) {
    sim.motions.push_back(Motion::rotation("rigid rotation", 0.0, 0.0, omega));
    motion = 1;
  }
  add_body(sim, "disk", mat);
  if (fitted) {
    geometry::SpacingField field(dx, d.grading > 0 ? d.grading : geometry::kDefaultGrading);
    if (fine < dx) field.add_feature({{-0.5 * fine, 0.0}, {0.5 * fine, 0.0}}, fine);
    add_body_fitted(sim, geometry::make_region(geometry::circle({0.0, 0.0}, R, 1e-5 * R)), field,
                    [motion](double, double) { return motion; });
  } else {
    lattice::fill_region(
        -R, -R, R, R, dx, -R, -R, [&](double x, double y) { return x * x + y * y <= R * R; },
        [&](double x, double y) { add_particle(sim, x, y, motion); });
  }
  end_body(sim);

  Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) {
    p.vx[i] = -omega * p.y[i];
    p.vy[i] = omega * p.x[i];
    p.sxx[i] = s0xx;
    p.syy[i] = s0yy;
    p.sxy[i] = s0xy;
    p.szz[i] = -(s0xx + s0yy);  // S0 is a deviator
  }
  sim.domain = grown_bounds(p, R);

  const double scale = mat.rho0 * omega * omega * R * R;
  const double support = kernel_support(sim.discretization.kernel) * sim.h();
  const double s0_norm = std::sqrt(s0xx * s0xx + s0yy * s0yy + 2 * s0xy * s0xy);
  // Largest deviation of interior particles from R S0 R^T, relative to |S0|.
  auto rotation_error = [=](const Simulation& s2) {
    if (s0_norm == 0.0) return 0.0;
    const Particles& q = s2.particles;
    const double c = std::cos(omega * s2.time), sn = std::sin(omega * s2.time);
    // R S0 R^T with R the counter-clockwise rotation by omega t.
    const double exx = c * c * s0xx - 2 * c * sn * s0xy + sn * sn * s0yy;
    const double eyy = sn * sn * s0xx + 2 * c * sn * s0xy + c * c * s0yy;
    const double exy = c * sn * (s0xx - s0yy) + (c * c - sn * sn) * s0xy;
    double worst = 0.0;
    for (std::size_t i = 0; i < q.n; ++i) {
      if (std::hypot(q.x[i], q.y[i]) > R - support) continue;
      const double dev = std::sqrt(std::pow(q.sxx[i] - exx, 2) + std::pow(q.syy[i] - eyy, 2) +
                                   2 * std::pow(q.sxy[i] - exy, 2));
      worst = std::max(worst, dev / s0_norm);
    }
    return worst;
  };
  scene.columns.push_back({"stress_rotation_error", rotation_error});

  scene.default_end_s = 2.0 * std::numbers::pi / std::abs(omega);  // one revolution
  scene.description = {{"radius_m", R},
                       {"driven", driven},
                       {"particles", fitted ? "body_fitted" : "lattice"},
                       {"fine_spacing_m", fine},
                       {"bulk_spacing_m", dx},
                       {"centrifugal_scale_Pa", scale},
                       {"initial_stress_norm_Pa", s0_norm}};
  scene.analyse = [=](const History& h, const Simulation&) {
    nlohmann::json a;
    const std::vector<double> vm = h.column("max_von_mises_Pa");
    double peak = 0;
    for (double v : vm) peak = std::max(peak, v);
    a["centrifugal_scale_Pa"] = scale;
    a["max_von_mises_Pa"] = peak;
    a["von_mises_over_scale"] = scale > 0 ? peak / scale : 0.0;
    // Steady plane-strain spinning disk, centre: |sigma_r - sigma_z| =
    // (3 - 2nu)/(8(1 - nu)) (1 - 2nu) rho omega^2 R^2 (Timoshenko & Goodier, sec. 32).
    a["steady_centre_von_mises_Pa"] =
        (3 - 2 * mat.nu) / (8 * (1 - mat.nu)) * (1 - 2 * mat.nu) * scale;
    const std::vector<double> err = h.column("stress_rotation_error");
    double worst = 0;
    for (double e : err) worst = std::max(worst, e);
    a["max_stress_rotation_error"] = worst;
    return a;
  };
  return scene;
}

}  // namespace gearsph::scenes
