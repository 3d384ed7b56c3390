// Two identical bars approaching at +/- v (validation.md section 3): one-
// dimensional impact theory gives a contact stress rho c v, a contact time
// 2 L / c, and separation with reversed velocities (c the bar wave speed,
// here the plane-strain strip speed sqrt(E / (rho (1 - nu^2)))). With the
// contact model "kernel" the bars are coupled through the SPH sums and stick
// instead: the adhesion the paper's contact force avoids. Particles on a
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

}  // namespace

Scene build_bar_impact(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double L = s.at("length_m").get<double>();
  const double H = s.at("thickness_m").get<double>();
  const double v = s.at("velocity_m_s").get<double>();
  const Material mat = read_material(s.at("material"));

  Scene scene;
  scene.type = "bar_impact";
  Simulation& sim = scene.sim;
  sim.discretization = in.discretization;
  Discretization& d = sim.discretization;
  const auto [fitted, dx, fine] = lattice_scene_spacings(d, H / 10.0);
  const long nx = lattice::cells(L, dx), ny = lattice::cells(H, dx);
  if (ny < 2)
    throw JobError("/discretization", "the spacing leaves fewer than 2 particles across a bar");
  if (nx < 4)
    throw JobError("/discretization", "the spacing leaves fewer than 4 particles along a bar");
  const double length = fitted ? L : nx * dx, thickness = fitted ? H : ny * dx;
  const double gap = s.at("gap_m").get<double>();
  const double y0 = -0.5 * thickness, y1 = 0.5 * thickness;

  // Bar A on the left moving right, bar B on the right moving left; their
  // faces touch when gap = 0 (a lattice's particles are then dx apart
  // across the interface, body-fitted ones stand on the faces).
  auto bar = [&](const std::string& name, double x0) {
    add_body(sim, name, mat);
    if (fitted) {
      geometry::SpacingField field(dx, d.grading > 0 ? d.grading : geometry::kDefaultGrading);
      const double face = x0 < 0.0 ? 0.0 : gap;
      if (fine < dx) field.add_feature({{face, y0}, {face, y1}}, fine);
      add_body_fitted(
          sim, geometry::make_region({{x0, y0}, {x0 + length, y0}, {x0 + length, y1}, {x0, y1}}),
          field, [](double, double) { return 0; });
    } else {
      lattice::fill_rectangle(x0, y0, nx, ny, dx,
                              [&](double x, double y) { add_particle(sim, x, y, 0); });
    }
    end_body(sim);
  };
  bar("bar_left", -length);
  bar("bar_right", gap);
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
  // Gap between the bars' facing surfaces (negative: overlap of particle
  // cells; body-fitted particles stand on the faces).
  const double cell = fitted ? 0.0 : dx;
  scene.columns.push_back({"gap_m", [cell](const Simulation& s2) {
                             const Particles& q = s2.particles;
                             double right_of_left = -1e300, left_of_right = 1e300;
                             for (std::size_t i = 0; i < q.n; ++i) {
                               if (q.body[i] == 0)
                                 right_of_left = std::max(right_of_left, q.x[i]);
                               else
                                 left_of_right = std::min(left_of_right, q.x[i]);
                             }
                             return left_of_right - right_of_left - cell;
                           }});
  scene.description = {{"length_m", length},
                       {"thickness_m", thickness},
                       {"particles", fitted ? "body_fitted" : "lattice"},
                       {"fine_spacing_m", fine},
                       {"bulk_spacing_m", dx},
                       {"bar_wave_speed_m_s", c},
                       {"reference_contact_time_s", t_contact},
                       {"reference_contact_stress_Pa", sigma_ref}};

  scene.analyse = [=](const History& h, const Simulation&) {
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
  };
  return scene;
}

}  // namespace gearsph::scenes
