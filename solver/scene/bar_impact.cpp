// Two identical bars approaching at +/- v (validation.md section 3): one-
// dimensional impact theory gives a contact stress rho c v, a contact time
// 2 L / c, and separation with reversed velocities (c the bar wave speed,
// here the plane-strain strip speed sqrt(E / (rho (1 - nu^2)))). With the
// contact model "kernel" the bars are coupled through the SPH sums and stick
// instead: the adhesion the seed paper's contact force avoids. Particles on a
// lattice (the default) or body-fitted, optionally graded from a fine
// spacing at the facing ends, where the contact is.
#include <algorithm>
#include <cmath>

#include "solver/scene/builders.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

namespace {

// Mean x-velocity of one body's particles.
double body_velocity_x(const Simulation& sim, int body) {
  const Body& b = sim.bodies[body];
  double sum = 0.0;
  for (std::size_t i = b.begin; i < b.end; ++i) sum += sim.particles.vx[i];
  return sum / static_cast<double>(b.count());
}

// Gap between the bars' facing surfaces (negative: overlap of particle
// cells, `cell` wide; body-fitted particles stand on the faces, cell 0).
double bar_gap(const Simulation& sim, double cell) {
  const Particles& q = sim.particles;
  double right_of_left = -1e300, left_of_right = 1e300;
  for (std::size_t i = 0; i < q.n; ++i) {
    if (q.body[i] == 0)
      right_of_left = std::max(right_of_left, q.x[i]);
    else
      left_of_right = std::min(left_of_right, q.x[i]);
  }
  return left_of_right - right_of_left - cell;
}

// The two bars as modelled: a lattice rounds to whole cells, body-fitted
// particles keep the outline.
struct Bars {
  long nx = 0, ny = 0;  // lattice cells along and across
  double length = 0.0, thickness = 0.0;
  double gap = 0.0;  // between their faces at the start
};

// Refuses fewer than 2 particles across a bar or 4 along it.
Bars bar_size(const nlohmann::json& s, const SceneSpacings& sp, double L, double H) {
  Bars bars;
  bars.nx = lattice::cells(L, sp.dx);
  bars.ny = lattice::cells(H, sp.dx);
  if (bars.ny < 2)
    throw JobError("/discretization", "the spacing leaves fewer than 2 particles across a bar");
  if (bars.nx < 4)
    throw JobError("/discretization", "the spacing leaves fewer than 4 particles along a bar");
  bars.length = sp.fitted ? L : bars.nx * sp.dx;
  bars.thickness = sp.fitted ? H : bars.ny * sp.dx;
  bars.gap = s.at("gap_m").get<double>();
  return bars;
}

// One bar from x0 along +x. Bar A on the left moving right, bar B on the
// right moving left; their faces touch when gap = 0 (a lattice's particles
// are then dx apart across the interface, body-fitted ones stand on the
// faces), where body-fitted particles may be fine.
void fill_bar(Simulation& sim, const std::string& name, double x0, const Bars& bars,
              const SceneSpacings& sp, const Material& mat) {
  const double y0 = -0.5 * bars.thickness, y1 = 0.5 * bars.thickness, length = bars.length;
  add_body(sim, name, mat);
  if (sp.fitted) {
    geometry::SpacingField field(sp.dx, sp.grading);
    const double face = x0 < 0.0 ? 0.0 : bars.gap;
    if (sp.fine < sp.dx) field.add_feature({{face, y0}, {face, y1}}, sp.fine);
    add_body_fitted(
        sim, geometry::make_region({{x0, y0}, {x0 + length, y0}, {x0 + length, y1}, {x0, y1}}),
        field, [](double, double) { return 0; });
  } else {
    lattice::fill_rectangle(x0, y0, bars.nx, bars.ny, sp.dx,
                            [&](double x, double y) { add_particle(sim, x, y, 0); });
  }
  end_body(sim);
}

// Contact time and stress, read where the contact force exceeds 5 % of the
// reference's, and the restitution, against 1D impact theory.
nlohmann::json analyse_bar_impact(const History& h, double sigma_ref, double t_contact,
                                  double thickness) {
  nlohmann::json a;
  a["reference_contact_stress_Pa"] = sigma_ref;
  a["reference_contact_time_s"] = t_contact;
  a["reference"] = "1D impact: sigma = rho c v, t_c = 2 L / c, c = sqrt(E / (rho (1 - nu^2)))";
  const auto t = h.column("time_s");
  const auto vl = h.column("left_vx_m_s"), vr = h.column("right_vx_m_s");
  const auto gap_t = h.column("gap_m");
  const double v_before = vr.front() - vl.front();  // closing speed, negative
  const double v_after = vr.back() - vl.back();
  a["restitution"] = -v_after / v_before;
  a["separated"] = gap_t.back() > 0.0 && v_after > 0.0;
  a["final_gap_m"] = gap_t.back();
  const int fc = h.index("contact_force_bar_left_N_per_m");
  if (fc >= 0) {
    const auto f = h.column("contact_force_bar_left_N_per_m");
    const double threshold = 0.05 * sigma_ref * thickness;
    std::size_t first = f.size(), last = 0;
    for (std::size_t k = 0; k < f.size(); ++k) {
      if (std::abs(f[k]) > threshold) {
        first = std::min(first, k);
        last = k;
      }
    }
    if (first < last) {
      // Times where the force crosses the threshold, interpolated.
      const double t0 = t[first], t1 = t[last];
      a["contact_time_s"] = t1 - t0;
      a["contact_time_error"] = (t1 - t0 - t_contact) / t_contact;
      // Plateau: mean force over the middle 60 % of the contact.
      double sum = 0.0;
      int count = 0;
      for (std::size_t k = first; k <= last; ++k) {
        if (t[k] >= t0 + 0.2 * (t1 - t0) && t[k] <= t1 - 0.2 * (t1 - t0)) {
          sum += std::abs(f[k]);
          ++count;
        }
      }
      const double sigma = count ? sum / count / thickness : 0.0;
      a["contact_stress_Pa"] = sigma;
      a["contact_stress_error"] = (sigma - sigma_ref) / sigma_ref;
    }
  }
  return a;
}

}  // namespace

Scene build_bar_impact(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double L = s.at("length_m").get<double>();
  const double H = s.at("thickness_m").get<double>();
  const double v = s.at("velocity_m_s").get<double>();
  const Material mat = read_material(s.at("material"));

  Scene scene = start_scene("bar_impact", in);
  scene.history_every_step = true;  // the contact time and the peak contact stress
  Simulation& sim = scene.sim;
  const SceneSpacings sp = lattice_scene_spacings(sim.discretization, H / 10.0);
  const Bars bars = bar_size(s, sp, L, H);
  const double length = bars.length, thickness = bars.thickness, gap = bars.gap;
  const double y0 = -0.5 * thickness, y1 = 0.5 * thickness;

  fill_bar(sim, "bar_left", -length, bars, sp, mat);
  fill_bar(sim, "bar_right", gap, bars, sp, mat);
  Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) p.vx[i] = p.body[i] == 0 ? v : -v;
  scene.outlines.push_back(
      {"bar_left", 0, {{-length, y0}, {0.0, y0}, {0.0, y1}, {-length, y1}}, true});
  scene.outlines.push_back(
      {"bar_right", 1, {{gap, y0}, {gap + length, y0}, {gap + length, y1}, {gap, y1}}, true});
  sim.domain = grown_bounds(p, 2 * length);

  const double c = mat.strip_wave_speed();
  const double t_contact = 2.0 * length / c;
  const double sigma_ref = mat.rho0 * c * v;
  scene.default_end_s = gap / (2 * v) + 1.6 * t_contact;
  scene.columns.push_back(
      {"left_vx_m_s", [](const Simulation& s2) { return body_velocity_x(s2, 0); }});
  scene.columns.push_back(
      {"right_vx_m_s", [](const Simulation& s2) { return body_velocity_x(s2, 1); }});
  const double cell = sp.fitted ? 0.0 : sp.dx;
  scene.columns.push_back({"gap_m", [cell](const Simulation& s2) { return bar_gap(s2, cell); }});
  scene.description = {{"length_m", length},
                       {"thickness_m", thickness},
                       {"bar_wave_speed_m_s", c},
                       {"reference_contact_time_s", t_contact},
                       {"reference_contact_stress_Pa", sigma_ref}};
  describe_spacings(scene.description, sp);
  scene.analyse = [=](const History& h, const Simulation&) {
    return analyse_bar_impact(h, sigma_ref, t_contact, thickness);
  };
  return scene;
}

}  // namespace gearsph::scenes
