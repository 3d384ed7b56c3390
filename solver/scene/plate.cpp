// Oscillating cantilever plate (Gray, Monaghan & Swift 2001; validation.md
// section 5). A plate of free length L and thickness H, clamped over an
// insert of length `clamp_length_m` behind x = 0, starts with the velocity
// of its first bending mode. The clamp is rigid: its particles are fixed and
// belong to the plate, so the root sees a full kernel support. Particles on
// a lattice (the default) or body-fitted, optionally graded from a fine
// spacing at the clamp's face (the validation suite's graded variant).
#include <cmath>
#include <numbers>
#include <sstream>

#include "solver/run/signal.hpp"
#include "solver/scene/builders.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

namespace {

constexpr double kFirstModeKL = 1.875;  // root of 1 + cos(kL) cosh(kL) = 0

// Mode shape of the first bending mode of a clamped-free beam, as written in
// validation.md (Gray et al. 2001, eq. 38), scaled so that the tip moves at
// about 2 Vf c0 (the shape is ~2 at x = L).
double first_mode(double k, double L, double x) {
  const double kl = k * L;
  const double M = std::sin(kl) + std::sinh(kl);
  const double N = std::cos(kl) + std::cosh(kl);
  const double Q = 2.0 * (std::cos(kl) * std::sinh(kl) - std::sin(kl) * std::cosh(kl));
  return (M * (std::cos(k * x) - std::cosh(k * x)) - N * (std::sin(k * x) - std::sinh(k * x))) / Q;
}

}  // namespace

Scene build_plate(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double L = s.at("length_m").get<double>();
  const double H = s.at("thickness_m").get<double>();
  const double clamp = s.contains("clamp_length_m") ? s.at("clamp_length_m").get<double>() : L / 4;
  const double vf = s.at("Vf").get<double>();
  const Material mat = read_material(s.at("material"));

  Scene scene;
  scene.type = "plate";
  Simulation& sim = scene.sim;
  sim.discretization = in.discretization;
  Discretization& d = sim.discretization;
  // Body-fitted particles may be graded toward the clamp's face, where the
  // bending moment and its gradient peak; the spacing grows toward the tip.
  const auto [fitted, dx, fine] = lattice_scene_spacings(d, H / 10.0);

  const long nx = lattice::cells(L, dx), ny = lattice::cells(H, dx);
  const long nc = lattice::cells(clamp, dx);
  if (ny < 3) {
    throw JobError("/discretization", "the spacing leaves " + std::to_string(ny) +
                                          " particles across the plate thickness; use at most " +
                                          "thickness/3");
  }
  if (nx < 3 * ny / 2) {
    throw JobError("/scene/length_m",
                   "the plate must be longer than its thickness to bend "
                   "(length/thickness >= 1.5)");
  }
  const double support = kernel_support(d.kernel) * sim.h();
  if ((fitted ? clamp : nc * dx) < support - 1e-12) {
    std::ostringstream m;
    m << "the clamp must be at least the kernel support (" << support
      << " m) long so that the plate root sees a full clamp";
    throw JobError("/scene/clamp_length_m", m.str());
  }
  // As modelled: a lattice rounds to whole cells, body-fitted particles
  // keep the outline.
  const double length = fitted ? L : nx * dx, thickness = fitted ? H : ny * dx;
  const double clamp_length = fitted ? clamp : nc * dx;

  sim.motions.push_back(Motion::fixed("clamp"));
  add_body(sim, "plate", mat);
  const double y0 = -0.5 * thickness;
  auto clamp_motion = [](double x, double) { return x < 0.0 ? 1 : 0; };
  if (fitted) {
    geometry::SpacingField field(dx, d.grading > 0 ? d.grading : geometry::kDefaultGrading);
    if (fine < dx) field.add_feature({{0.0, y0}, {0.0, -y0}}, fine);
    add_body_fitted(sim,
                    geometry::make_region(
                        {{-clamp_length, y0}, {length, y0}, {length, -y0}, {-clamp_length, -y0}}),
                    field, clamp_motion);
  } else {
    lattice::fill_rectangle(-nc * dx, y0, nc + nx, ny, dx, [&](double x, double y) {
      add_particle(sim, x, y, clamp_motion(x, y));
    });
  }
  end_body(sim);

  // Initial transverse velocity of the first bending mode (validation.md).
  const double k = kFirstModeKL / length;
  const double c0 = mat.bulk_sound_speed();
  Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.x[i] > 0.0) p.vy[i] = vf * c0 * first_mode(k, length, p.x[i]);
  }
  sim.domain = grown_bounds(p, length);
  long clamp_particles = 0;
  for (std::size_t i = 0; i < p.n; ++i) clamp_particles += p.motion[i] == 1 ? 1 : 0;

  // Tip probe: the particles of the last column (body-fitted: of the tip's
  // outline) closest to mid-thickness (two of them when they straddle it;
  // their mean is the mid-plane).
  std::vector<std::size_t> tip;
  double best = 1e300;
  const double x_tip = fitted ? length : length - 0.5 * dx;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double s_i = p.spacing[i];
    if (std::abs(p.x[i] - x_tip) > 0.25 * s_i) continue;
    const double dist = std::abs(p.y[i]);
    if (dist < best - 0.25 * s_i) {
      tip.clear();
      best = dist;
    }
    if (dist < best + 0.25 * s_i) tip.push_back(i);
  }
  auto mean_of = [tip](const Column<double>& v) {
    double sum = 0;
    for (std::size_t i : tip) sum += v[i];
    return sum / static_cast<double>(tip.size());
  };
  scene.columns.push_back(
      {"tip_y_m", [=](const Simulation& s2) { return mean_of(s2.particles.y); }});
  scene.columns.push_back(
      {"tip_vy_m_s", [=](const Simulation& s2) { return mean_of(s2.particles.vy); }});

  // Thin-plate (Euler-Bernoulli, plane strain) reference frequency.
  const double omega_ref = std::sqrt(mat.E * thickness * thickness * std::pow(k, 4) /
                                     (12.0 * mat.rho0 * (1.0 - mat.nu * mat.nu)));
  const double period_ref = 2.0 * std::numbers::pi / omega_ref;
  // Long enough for five half-cycle peaks (the decay over two periods)
  // even when the SPH period is 10 % long.
  scene.default_end_s = 2.75 * period_ref;

  scene.description = {{"length_m", length},
                       {"thickness_m", thickness},
                       {"clamp_length_m", clamp_length},
                       {"particles", fitted ? "body_fitted" : "lattice"},
                       {"fine_spacing_m", fine},
                       {"bulk_spacing_m", dx},
                       {"particles_across_thickness", ny},
                       {"clamp_particles", clamp_particles},
                       {"tip_probe_particles", tip.size()},
                       {"reference_period_s", period_ref}};

  scene.analyse = [=](const History& h, const Simulation&) {
    nlohmann::json a;
    a["reference_period_s"] = period_ref;
    a["reference_omega_rad_s"] = omega_ref;
    a["reference"] = "thin plate: omega^2 = E H^2 k^4 / (12 rho (1 - nu^2)), kL = 1.875";
    const std::vector<double> t = h.column("time_s");
    std::vector<double> y = h.column("tip_y_m");
    const double y_start = y.empty() ? 0.0 : y.front();
    for (double& v : y) v -= y_start;
    const signal::Oscillation osc = signal::analyse_oscillation(t, y);
    if (osc.period > 0) {
      a["period_s"] = osc.period;
      a["period_error"] = (osc.period - period_ref) / period_ref;
    } else {
      a["period_s"] = nullptr;
      a["period_error"] = nullptr;
      a["note"] = "fewer than two zero crossings of the tip displacement: run longer";
    }
    a["zero_crossings"] = osc.crossings.size();
    a["first_amplitude_m"] = osc.amplitudes.empty() ? 0.0 : osc.amplitudes.front();
    if (osc.amplitudes.size() >= 5) {
      // Half-cycle peaks 0 and 4 are two periods apart.
      a["amplitude_decay_2_periods"] = 1.0 - osc.amplitudes[4] / osc.amplitudes[0];
    } else {
      a["amplitude_decay_2_periods"] = nullptr;
    }
    return a;
  };
  return scene;
}

}  // namespace gearsph::scenes
