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

#include "solver/run/signal.hpp"
#include "solver/scene/builders.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

Scene build_strip_wave(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double L = s.at("length_m").get<double>();
  const double H = s.at("thickness_m").get<double>();
  const bool confined = s.at("lateral").get<std::string>() == "confined";
  const double v0 = s.at("velocity_m_s").get<double>();
  const Material mat = read_material(s.at("material"));

  Scene scene;
  scene.type = "strip_wave";
  Simulation& sim = scene.sim;
  sim.discretization = in.discretization;
  Discretization& d = sim.discretization;
  const auto [fitted, dx, fine] = lattice_scene_spacings(d, L / 400.0);
  const double w = s.contains("pulse_width_m") ? s.at("pulse_width_m").get<double>() : 0.04 * L;
  if (fitted && confined) {
    throw JobError("/discretization/particles",
                   "a confined strip is held by roller rows on its lattice; body-fitted "
                   "particles need \"lateral\": \"free\"");
  }

  const long nx = lattice::cells(L, dx), ny = lattice::cells(H, dx);
  if (ny < 1) throw JobError("/scene/thickness_m", "the strip is thinner than one spacing");
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
  const double length = fitted ? L : nx * dx, thickness = fitted ? H : ny * dx;
  // Roller rows, as many as the kernel reaches.
  const long guard_rows =
      confined ? static_cast<long>(std::ceil(kernel_support(d.kernel) * d.h_over_dx)) : 0;

  sim.motions.push_back(Motion::guided_x("rollers"));
  add_body(sim, "strip", mat);
  const double xa = 0.45 * length, xb = 0.65 * length;
  if (fitted) {
    geometry::SpacingField field(dx, d.grading > 0 ? d.grading : geometry::kDefaultGrading);
    const double x_fine = 0.5 * (xa + xb);
    if (fine < dx) field.add_feature({{x_fine, -0.5 * H}, {x_fine, 0.5 * H}}, fine);
    add_body_fitted(sim,
                    geometry::make_region(
                        {{0.0, -0.5 * H}, {length, -0.5 * H}, {length, 0.5 * H}, {0.0, 0.5 * H}}),
                    field, [](double, double) { return 0; });
  } else {
    const double y0 = -0.5 * thickness - guard_rows * dx;
    lattice::fill_rectangle(0.0, y0, nx, ny + 2 * guard_rows, dx, [&](double x, double y) {
      const bool roller = std::abs(y) > 0.5 * thickness;
      add_particle(sim, x, y, roller ? 1 : 0);
    });
  }
  end_body(sim);

  const double xc = 0.25 * length;
  Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double u = (p.x[i] - xc) / w;
    p.vx[i] = v0 * std::exp(-u * u);
  }
  sim.domain = grown_bounds(p, length);

  // Probe columns: the strip's own particles (not rollers) nearest xa, xb;
  // body-fitted, those within half their spacing of the line x = xa.
  auto column_at = [&](double x_probe) {
    const double x_col = fitted ? x_probe : (std::floor(x_probe / dx) + 0.5) * dx;
    std::vector<std::size_t> col;
    for (std::size_t i = 0; i < p.n; ++i) {
      if (std::abs(p.x[i] - x_col) < (fitted ? 0.5 : 0.25) * p.spacing[i] && p.motion[i] == 0) {
        col.push_back(i);
      }
    }
    if (col.empty()) throw JobError("/discretization", "no particle stands at a probe");
    return std::make_pair(x_col, col);
  };
  const auto [xa_col, col_a] = column_at(xa);
  const auto [xb_col, col_b] = column_at(xb);
  auto mean_vx = [](const std::vector<std::size_t>& col) {
    return [col](const Simulation& s2) {
      double sum = 0;
      for (std::size_t i : col) sum += s2.particles.vx[i];
      return sum / static_cast<double>(col.size());
    };
  };
  scene.columns.push_back({"probe_a_vx_m_s", mean_vx(col_a)});
  scene.columns.push_back({"probe_b_vx_m_s", mean_vx(col_b)});

  const double c_ref = confined ? mat.p_wave_speed() : mat.strip_wave_speed();
  // Until the right-going pulse has passed probe b by 4 widths; the first
  // reflection reaches probe b only after 0.9 L of travel.
  scene.default_end_s = (xb_col - xc + 4.0 * w) / c_ref;
  scene.description = {{"length_m", length},
                       {"thickness_m", thickness},
                       {"lateral", confined ? "confined" : "free"},
                       {"roller_rows_each_side", guard_rows},
                       {"particles", fitted ? "body_fitted" : "lattice"},
                       {"fine_spacing_m", fine},
                       {"bulk_spacing_m", dx},
                       {"pulse_width_m", w},
                       {"probe_a_x_m", xa_col},
                       {"probe_b_x_m", xb_col}};
  scene.analyse = [=](const History& h, const Simulation&) {
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
      const double c = (xb_col - xa_col) / (tb - ta);
      a["wave_speed_m_s"] = c;
      a["speed_error"] = (c - c_ref) / c_ref;
    } else {
      a["wave_speed_m_s"] = nullptr;
      a["speed_error"] = nullptr;
      a["note"] = "the pulse did not reach both probes: run longer";
    }
    return a;
  };
  return scene;
}

}  // namespace gearsph::scenes
