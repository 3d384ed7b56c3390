// Elastic wave in a strip (validation.md section 2). A Gaussian bump of
// axial velocity, v_x = v0 exp(-((x - xc)/w)^2), starts at a quarter of the
// length; it splits into two pulses of half amplitude that travel at the
// longitudinal wave speed. Two probe columns further along record v_x; the
// speed is their distance over the difference of the pulse's arrival times
// (centroids of v_x^2), measured before any reflection comes back.
//
//  lateral = "confined": rows of particles above and below, guided so that
//    v_y = 0 (rollers), make the strip laterally confined (1D strain): the
//    pulse travels at c_p = sqrt((K + 4G/3)/rho).
//  lateral = "free": free faces, a thin plane-strain strip:
//    c = sqrt(E / (rho (1 - nu^2))) for pulses much longer than the thickness.
//    Its particles may be body-fitted and graded: fine across the strip
//    halfway between the probes, so that the pulse crosses the grading
//    twice on its way from one probe to the other.
#include <algorithm>
#include <cmath>

#include "solver/diagnostics/signal.hpp"
#include "solver/scene/builders.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

namespace {

// The pulse: at least four spacings wide to be resolved, at most 6 % of
// the strip so that the probes see it before its reflections.
void check_pulse(double w, double dx, double L) {
  if (w < 4 * dx) {
    throw JobError("/scene/pulse_width_m",
                   "the pulse must span at least 4 spacings (pulse_width_m >= 4 dx = " +
                       std::to_string(4 * dx) + " m) to be resolved");
  }
  if (w > 0.06 * L) {
    throw JobError("/scene/pulse_width_m",
                   "the pulse must be at most 6 % of the strip length so that the probes see it "
                   "before its reflections");
  }
}

// The strip as modelled: a lattice rounds to whole cells, body-fitted
// particles keep the outline.
struct Strip {
  long nx = 0, ny = 0;  // lattice cells along and across
  double length = 0.0, thickness = 0.0;
  long guard_rows = 0;  // roller rows above and below (confined)
};

// Refuses a strip thinner than a spacing and a pulse the probes cannot
// resolve.
Strip strip_size(const Discretization& d, const SceneSpacings& sp, double L, double H, double w,
                 bool confined) {
  Strip z;
  z.nx = lattice::cells(L, sp.dx);
  z.ny = lattice::cells(H, sp.dx);
  if (z.ny < 1) throw JobError("/scene/thickness_m", "the strip is thinner than one spacing");
  check_pulse(w, sp.dx, L);
  z.length = sp.fitted ? L : z.nx * sp.dx;
  z.thickness = sp.fitted ? H : z.ny * sp.dx;
  // Roller rows, as many as the kernel reaches.
  z.guard_rows =
      confined ? static_cast<long>(std::ceil(kernel_support(d.kernel) * d.h_over_dx)) : 0;
  return z;
}

// The strip, and for a confined one its roller rows (motion 1) above and
// below. Body-fitted particles are fine across the strip at x_fine.
void fill_strip(Simulation& sim, const SceneSpacings& sp, const Strip& z, double x_fine,
                const Material& mat) {
  const double dx = sp.dx, length = z.length, thickness = z.thickness;
  add_body(sim, "strip", mat);
  if (sp.fitted) {
    geometry::SpacingField field(dx, sp.grading);
    if (sp.fine < dx) {
      field.add_feature({{x_fine, -0.5 * thickness}, {x_fine, 0.5 * thickness}}, sp.fine);
    }
    add_body_fitted(sim,
                    geometry::make_region({{0.0, -0.5 * thickness},
                                           {length, -0.5 * thickness},
                                           {length, 0.5 * thickness},
                                           {0.0, 0.5 * thickness}}),
                    field, [](double, double) { return 0; });
  } else {
    const double y0 = -0.5 * thickness - z.guard_rows * dx;
    lattice::fill_rectangle(0.0, y0, z.nx, z.ny + 2 * z.guard_rows, dx, [&](double x, double y) {
      const bool roller = std::abs(y) > 0.5 * thickness;
      add_particle(sim, x, y, roller ? 1 : 0);
    });
  }
  end_body(sim);
}

// The Gaussian bump of axial velocity, v_x = v0 exp(-((x - xc)/w)^2).
void start_pulse(Particles& p, double v0, double xc, double w) {
  for (std::size_t i = 0; i < p.n; ++i) {
    const double u = (p.x[i] - xc) / w;
    p.vx[i] = v0 * std::exp(-u * u);
  }
}

// A probe column: the strip's own particles (not rollers) nearest x_probe;
// body-fitted, those within half their spacing of the line x = x_probe.
// Returns the column's x and its particles.
std::pair<double, std::vector<std::size_t>> column_at(const Particles& p, const SceneSpacings& sp,
                                                      double x_probe) {
  const double x_col = sp.fitted ? x_probe : (std::floor(x_probe / sp.dx) + 0.5) * sp.dx;
  std::vector<std::size_t> col;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (std::abs(p.x[i] - x_col) < (sp.fitted ? 0.5 : 0.25) * p.spacing[i] && p.motion[i] == 0) {
      col.push_back(i);
    }
  }
  if (col.empty()) throw JobError("/discretization", "no particle stands at a probe");
  return std::make_pair(x_col, col);
}

// The mean x velocity of a probe column.
auto mean_vx(const std::vector<std::size_t>& col) {
  return [col](const Simulation& s2) {
    double sum = 0;
    for (std::size_t i : col) sum += s2.particles.vx[i];
    return sum / static_cast<double>(col.size());
  };
}

// The speed from the pulse's arrival times at the two probes, at x_a and
// x_b, against the reference c_ref.
nlohmann::json analyse_strip_wave(const History& h, bool confined, double c_ref, double x_a,
                                  double x_b) {
  nlohmann::json a;
  const std::vector<double> t = h.column("time_s");
  const double ta = signal::energy_centroid(t, h.column("probe_a_vx_m_s"));
  const double tb = signal::energy_centroid(t, h.column("probe_b_vx_m_s"));
  a["reference_speed_m_s"] = c_ref;
  a["reference"] = confined ? "P-wave speed sqrt((K + 4G/3)/rho), laterally confined"
                            : "thin plane-strain strip sqrt(E / (rho (1 - nu^2)))";
  a["arrival_a_s"] = ta;
  a["arrival_b_s"] = tb;
  // What reaches probe b of the pulse probe a saw: below 1 by dissipation
  // and by reflections, e.g. where graded particles change their spacing.
  auto peak = [](const std::vector<double>& v) {
    double m = 0.0;
    for (double q : v) m = std::max(m, std::abs(q));
    return m;
  };
  const double peak_a = peak(h.column("probe_a_vx_m_s"));
  a["transmitted_peak_ratio"] = peak_a > 0 ? peak(h.column("probe_b_vx_m_s")) / peak_a : 0.0;
  if (tb > ta) {
    const double c = (x_b - x_a) / (tb - ta);
    a["wave_speed_m_s"] = c;
    a["speed_error"] = (c - c_ref) / c_ref;
  } else {
    a["wave_speed_m_s"] = nullptr;
    a["speed_error"] = nullptr;
    a["note"] = "the pulse did not reach both probes: run longer";
  }
  return a;
}

}  // namespace

Scene build_strip_wave(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double L = s.at("length_m").get<double>();
  const double H = s.at("thickness_m").get<double>();
  const bool confined = s.at("lateral").get<std::string>() == "confined";
  const double v0 = s.at("velocity_m_s").get<double>();
  const Material mat = read_material(s.at("material"));

  Scene scene = start_scene("strip_wave", in);
  scene.history_every_step = true;  // the pulse's arrival times and peaks
  Simulation& sim = scene.sim;
  const SceneSpacings sp = lattice_scene_spacings(sim.discretization, L / 400.0);
  const double w = s.contains("pulse_width_m") ? s.at("pulse_width_m").get<double>() : 0.04 * L;
  if (sp.fitted && confined) {
    throw JobError("/discretization/particles",
                   "a confined strip is held by roller rows on its lattice; body-fitted "
                   "particles need \"lateral\": \"free\"");
  }
  const Strip strip = strip_size(sim.discretization, sp, L, H, w, confined);
  const double length = strip.length;

  sim.motions.push_back(Motion::guided_x("rollers"));
  const double xa = 0.45 * length, xb = 0.65 * length;
  fill_strip(sim, sp, strip, 0.5 * (xa + xb), mat);
  const double xc = 0.25 * length;
  start_pulse(sim.particles, v0, xc, w);
  sim.domain = grown_bounds(sim.particles, length);

  const auto [xa_col, col_a] = column_at(sim.particles, sp, xa);
  const auto [xb_col, col_b] = column_at(sim.particles, sp, xb);
  scene.columns.push_back({"probe_a_vx_m_s", mean_vx(col_a)});
  scene.columns.push_back({"probe_b_vx_m_s", mean_vx(col_b)});

  const double c_ref = confined ? mat.p_wave_speed() : mat.strip_wave_speed();
  // Until the right-going pulse has passed probe b by 4 widths; the first
  // reflection reaches probe b only after 0.9 L of travel.
  scene.default_end_s = (xb_col - xc + 4.0 * w) / c_ref;
  scene.description = {{"length_m", length},
                       {"thickness_m", strip.thickness},
                       {"lateral", confined ? "confined" : "free"},
                       {"roller_rows_each_side", strip.guard_rows},
                       {"pulse_width_m", w},
                       {"probe_a_x_m", xa_col},
                       {"probe_b_x_m", xb_col}};
  describe_spacings(scene.description, sp);
  scene.analyse = [confined, c_ref, xa_col, xb_col](const History& h, const Simulation&) {
    return analyse_strip_wave(h, confined, c_ref, xa_col, xb_col);
  };
  return scene;
}

}  // namespace gearsph::scenes
