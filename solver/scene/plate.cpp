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

#include "solver/diagnostics/signal.hpp"
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

// The plate as modelled: a lattice rounds to whole cells, body-fitted
// particles keep the outline.
struct PlateSize {
  long nx = 0, ny = 0, nc = 0;  // lattice cells along, across, in the clamp
  double length = 0.0, thickness = 0.0, clamp_length = 0.0;
};

// Refuses fewer than three particles across, a plate too short to bend,
// and a clamp shorter than the kernel's reach (the root would not see a
// full clamp).
PlateSize plate_size(const Simulation& sim, const SceneSpacings& sp, double L, double H,
                     double clamp) {
  const double dx = sp.dx;
  PlateSize z;
  z.nx = lattice::cells(L, dx);
  z.ny = lattice::cells(H, dx);
  z.nc = lattice::cells(clamp, dx);
  if (z.ny < 3) {
    throw JobError("/discretization", "the spacing leaves " + std::to_string(z.ny) +
                                          " particles across the plate thickness; use at most " +
                                          "thickness/3");
  }
  if (z.nx < 3 * z.ny / 2) {
    throw JobError("/scene/length_m",
                   "the plate must be longer than its thickness to bend "
                   "(length/thickness >= 1.5)");
  }
  const double support = kernel_support(sim.discretization.kernel) * sim.h();
  if ((sp.fitted ? clamp : z.nc * dx) < support - 1e-12) {
    std::ostringstream m;
    m << "the clamp must be at least the kernel support (" << support
      << " m) long so that the plate root sees a full clamp";
    throw JobError("/scene/clamp_length_m", m.str());
  }
  z.length = sp.fitted ? L : z.nx * dx;
  z.thickness = sp.fitted ? H : z.ny * dx;
  z.clamp_length = sp.fitted ? clamp : z.nc * dx;
  return z;
}

// The plate and its clamp (x < 0, fixed) in one body. Body-fitted particles
// may be graded toward the clamp's face, where the bending moment and its
// gradient peak; the spacing grows toward the tip.
void fill_plate(Simulation& sim, const SceneSpacings& sp, const PlateSize& z, const Material& mat) {
  const double dx = sp.dx;
  add_body(sim, "plate", mat);
  const double y0 = -0.5 * z.thickness;
  auto clamp_motion = [](double x, double) { return x < 0.0 ? 1 : 0; };
  if (sp.fitted) {
    geometry::SpacingField field(dx, sp.grading);
    if (sp.fine < dx) field.add_feature({{0.0, y0}, {0.0, -y0}}, sp.fine);
    add_body_fitted(
        sim,
        geometry::make_region(
            {{-z.clamp_length, y0}, {z.length, y0}, {z.length, -y0}, {-z.clamp_length, -y0}}),
        field, clamp_motion);
  } else {
    lattice::fill_rectangle(-z.nc * dx, y0, z.nc + z.nx, z.ny, dx, [&](double x, double y) {
      add_particle(sim, x, y, clamp_motion(x, y));
    });
  }
  end_body(sim);
}

// Tip probe: the particles of the last column (body-fitted: of the tip's
// outline) closest to mid-thickness (two of them when they straddle it;
// their mean is the mid-plane).
std::vector<std::size_t> tip_probe(const Particles& p, const SceneSpacings& sp, double length) {
  std::vector<std::size_t> tip;
  double best = 1e300;
  const double x_tip = sp.fitted ? length : length - 0.5 * sp.dx;
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
  return tip;
}

// The tip's period and decay against the thin-plate reference.
nlohmann::json analyse_plate(const History& h, double omega_ref, double period_ref) {
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
}

}  // namespace

Scene build_plate(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double L = s.at("length_m").get<double>();
  const double H = s.at("thickness_m").get<double>();
  const double clamp = s.contains("clamp_length_m") ? s.at("clamp_length_m").get<double>() : L / 4;
  const double vf = s.at("Vf").get<double>();
  const Material mat = read_material(s.at("material"));

  Scene scene = start_scene("plate", in);
  Simulation& sim = scene.sim;
  const SceneSpacings sp = lattice_scene_spacings(sim.discretization, H / 10.0);
  const PlateSize z = plate_size(sim, sp, L, H, clamp);
  sim.motions.push_back(Motion::fixed("clamp"));
  fill_plate(sim, sp, z, mat);

  // Initial transverse velocity of the first bending mode (validation.md).
  const double k = kFirstModeKL / z.length;
  const double c0 = mat.bulk_sound_speed();
  Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.x[i] > 0.0) p.vy[i] = vf * c0 * first_mode(k, z.length, p.x[i]);
  }
  sim.domain = grown_bounds(p, z.length);
  long clamp_particles = 0;
  for (std::size_t i = 0; i < p.n; ++i) clamp_particles += p.motion[i] == 1 ? 1 : 0;

  const std::vector<std::size_t> tip = tip_probe(p, sp, z.length);
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
  const double omega_ref = std::sqrt(mat.E * z.thickness * z.thickness * std::pow(k, 4) /
                                     (12.0 * mat.rho0 * (1.0 - mat.nu * mat.nu)));
  const double period_ref = 2.0 * std::numbers::pi / omega_ref;
  // Long enough for five half-cycle peaks (the decay over two periods)
  // even when the SPH period is 10 % long.
  scene.default_end_s = 2.75 * period_ref;

  scene.description = {{"length_m", z.length},
                       {"thickness_m", z.thickness},
                       {"clamp_length_m", z.clamp_length},
                       {"particles_across_thickness", z.ny},
                       {"clamp_particles", clamp_particles},
                       {"tip_probe_particles", tip.size()},
                       {"reference_period_s", period_ref}};
  describe_spacings(scene.description, sp);
  scene.analyse = [=](const History& h, const Simulation&) {
    return analyse_plate(h, omega_ref, period_ref);
  };
  return scene;
}

}  // namespace gearsph::scenes
