// A strip pulled apart at a steady rate: the tensile-instability case of the
// stability study (docs/stability.md). Grips one kernel support wide at
// each end move apart at +-v_end; the strip starts with the matching linear
// velocity field v_x = v_end (2x/L - 1), so it stretches uniformly from the
// first step (no wave front), and the tension grows until the mean axial
// strain reaches peak_strain at the end of the run. Updated-Lagrangian SPH
// without artificial stress is unstable under tension (Swegle, Hicks &
// Attaway 1995): particles pair up and clump across the strip, which the
// health check's particle-disorder detector sees long before anything is
// NaN. Total Lagrangian, whose kernel lives on the reference configuration,
// has no such instability.
//
// The stretch takes `stretch_periods` transit periods 2 L / c (c the
// thin-strip wave speed sqrt(E / (rho (1 - nu^2)))): slow enough to be
// quasi-static, short enough to run in seconds.
#include <algorithm>
#include <cmath>

#include "solver/scene/builders.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

namespace {

// Mean axial strain of the free part of the strip: the grips' inner faces.
double axial_strain(const Simulation& sim, double span0) {
  const Particles& p = sim.particles;
  double lo = -1e300, hi = 1e300;  // innermost column of each grip
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.motion[i] == 1) lo = std::max(lo, p.x[i]);
    if (p.motion[i] == 2) hi = std::min(hi, p.x[i]);
  }
  return (hi - lo) / span0 - 1.0;
}

}  // namespace

Scene build_tension_strip(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double L = s.at("length_m").get<double>();
  const double H = s.at("thickness_m").get<double>();
  const double eps = s.at("peak_strain").get<double>();
  const double periods = s.at("stretch_periods").get<double>();
  const Material mat = read_material(s.at("material"));

  Scene scene = start_scene("tension_strip", in);
  Simulation& sim = scene.sim;
  particle_layout(in.discretization, ParticleLayout::Lattice, /*fitted_ok=*/false);
  if (sim.discretization.dx <= 0) sim.discretization.dx = H / 10.0;
  const double dx = sim.discretization.dx;
  const long nx = lattice::cells(L, dx), ny = lattice::cells(H, dx);
  const long grip = static_cast<long>(
      std::ceil(kernel_support(sim.discretization.kernel) * sim.discretization.h_over_dx));
  if (ny < 2) throw JobError("/scene/thickness_m", "the strip needs at least two spacings across");
  if (nx < 2 * grip + 4) {
    throw JobError("/scene/length_m", "the strip needs at least four spacings between its grips");
  }
  const double length = nx * dx, thickness = ny * dx;
  const double c = mat.strip_wave_speed();
  const double t_end = periods * 2.0 * length / c;
  const double v_end = eps * length / (2.0 * t_end);

  sim.motions.push_back(Motion::velocity("left grip", -v_end, 0.0));
  sim.motions.push_back(Motion::velocity("right grip", v_end, 0.0));
  add_body(sim, "strip", mat);
  lattice::fill_rectangle(0.0, -0.5 * thickness, nx, ny, dx, [&](double x, double y) {
    const long column = std::lround(x / dx - 0.5);
    const int motion = column < grip ? 1 : column >= nx - grip ? 2 : 0;
    add_particle(sim, x, y, motion);
  });
  end_body(sim);

  Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) {
    p.vx[i] = std::clamp(v_end * (2.0 * p.x[i] / length - 1.0), -v_end, v_end);
  }
  sim.domain = grown_bounds(p, length);

  // Between the grips' inner columns.
  const double span = static_cast<double>(nx - 2 * grip + 1) * dx;
  scene.columns.push_back(
      {"axial_strain", [span](const Simulation& s2) { return axial_strain(s2, span); }});
  scene.default_end_s = t_end;
  scene.description = {{"length_m", length},        {"thickness_m", thickness},
                       {"grip_columns", grip},      {"grip_velocity_m_s", v_end},
                       {"strip_wave_speed_m_s", c}, {"stretch_time_s", t_end}};
  scene.analyse = [=](const History& h, const Simulation&) {
    nlohmann::json a;
    const std::vector<double> strain = h.column("axial_strain");
    a["target_peak_strain"] = eps;
    a["final_strain"] = strain.empty() ? 0.0 : strain.back();
    a["reference"] = "grips at +-v_end: strain 2 v_end t / L";
    return a;
  };
  return scene;
}

}  // namespace gearsph::scenes
