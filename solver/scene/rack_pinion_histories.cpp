// The rack-and-pinion scene's history columns (docs/gears.md, What a run
// reports): what a gear engineer follows through a run, read from the
// particles at every history row.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "solver/physics/contact_near_field.hpp"
#include "solver/physics/simulation.hpp"
#include "solver/scene/rack_pinion.hpp"
#include "solver/scene/scene.hpp"

namespace gearsph::scenes {

namespace {

constexpr double kPi = std::numbers::pi;

// The rack's motion and transmission error, the hub's rate and torque, and
// the contact force.
void add_drive_histories(Scene& scene, const GearLayout& L) {
  const Particles& p = scene.sim.particles;
  const double b = L.face_width_m, r = L.pitch_radius;
  const std::size_t rb0 = scene.sim.bodies[1].begin, rb1 = scene.sim.bodies[1].end;
  auto rack_mean = [rb0, rb1](const Column<double>& v) {
    double sum = 0;
    for (std::size_t i = rb0; i < rb1; ++i) sum += v[i];
    return sum / static_cast<double>(rb1 - rb0);
  };
  double x_rack0 = 0;
  for (std::size_t i = rb0; i < rb1; ++i) x_rack0 += p.x[i];
  x_rack0 /= static_cast<double>(rb1 - rb0);
  scene.columns.push_back(
      {"rack_vx_m_s", [rack_mean](const Simulation& s2) { return rack_mean(s2.particles.vx); }});
  // Transmission error: the rack's displacement minus ideal rolling r theta
  // (theta = omega t when the hub is held at omega).
  scene.columns.push_back({"transmission_error_m", [rack_mean, x_rack0, r](const Simulation& s2) {
                             return rack_mean(s2.particles.x) - x_rack0 - r * s2.motions[1].angle;
                           }});
  scene.columns.push_back(
      {"pinion_omega_rad_s", [](const Simulation& s2) { return s2.motions[1].omega; }});
  // Torque the teeth put on the hub, reversed, per gear (face width b): what
  // a drive holding the speed supplies (the hub's own inertia aside).
  scene.columns.push_back({"pinion_torque_Nm", [b, cx = L.cx, cy = L.cy](const Simulation& s2) {
                             const Particles& q = s2.particles;
                             double t = 0;
                             for (std::size_t i = 0; i < q.n; ++i) {
                               if (q.motion[i] != 1) continue;
                               const double fx = q.mass[i] * (q.ax[i] + q.ext_ax[i]);
                               const double fy = q.mass[i] * (q.ay[i] + q.ext_ay[i]);
                               t -= (q.x[i] - cx) * fy - (q.y[i] - cy) * fx;
                             }
                             return t * b;
                           }});
  scene.columns.push_back({"contact_force_N", [b](const Simulation& s2) {
                             const ContactState& cs = s2.contact_state;
                             return cs.force_x.size() > 1
                                        ? b * std::hypot(cs.force_x[1], cs.force_y[1])
                                        : 0.0;
                           }});
}

// Per modelled tooth, the stress recovered on its true fillets and across
// its critical section (RootMonitor: once per row, whatever the columns).
void add_root_histories(Scene& scene, const GearLayout& L, std::size_t t) {
  constexpr double kDeg = 180.0 / kPi;
  const std::string sk = "_t" + std::to_string(L.pinion_teeth[t]);
  auto col = [&](const std::string& name, auto read) {
    scene.columns.push_back({name, [roots = L.roots, t, read](const Simulation& s2) {
                               return read(roots->at(s2)[t]);
                             }});
  };
  // The larger sigma_1 at the two 30-degree points (ISO 6336-3's section).
  col("root_stress" + sk + "_Pa", [](const ToothRootState& st) { return st.root_stress_Pa; });
  // Nominal bending stress 6 M / s^2 on the critical section: what ISO's
  // Y_F describes, before the fillet's stress concentration Y_S.
  col("root_bending" + sk + "_Pa",
      [](const ToothRootState& st) { return st.section_nominal_bending_Pa; });
  col("fillet_tension_peak" + sk + "_Pa",
      [](const ToothRootState& st) { return st.fillet.tension.stress_Pa; });
  col("fillet_tension_peak_radius" + sk + "_m",
      [](const ToothRootState& st) { return st.fillet.tension.radius_m; });
  col("fillet_tension_peak_angle" + sk + "_deg",
      [kDeg](const ToothRootState& st) { return kDeg * st.fillet.tension.angle_rad; });
  col("fillet_iso30" + sk + "_Pa",
      [](const ToothRootState& st) { return st.fillet.tension.at_iso30_Pa; });
  col("fillet_compression_peak" + sk + "_Pa",
      [](const ToothRootState& st) { return st.fillet.compression.stress_Pa; });
  col("fillet_compression_peak_radius" + sk + "_m",
      [](const ToothRootState& st) { return st.fillet.compression.radius_m; });
  col("fillet_compression_peak_angle" + sk + "_deg",
      [kDeg](const ToothRootState& st) { return kDeg * st.fillet.compression.angle_rad; });
}

// Per modelled tooth k, its contact force and the Hertz pressure it implies.
// Particles of no tooth have tooth_of = kNoTooth.
void add_tooth_load_histories(Scene& scene, const GearLayout& L, int k,
                              const std::vector<int>& tooth_of, double e_star) {
  const double b = L.face_width_m;
  const std::string sk = "_t" + std::to_string(k);
  scene.columns.push_back(
      {"tooth_force_t" + std::to_string(k) + "_N", [tooth_of, k, b](const Simulation& s2) {
         const Particles& q = s2.particles;
         double fx = 0, fy = 0;
         for (std::size_t i = 0; i < q.n; ++i) {
           if (tooth_of[i] != k) continue;
           fx += q.mass[i] * q.contact_ax[i];
           fy += q.mass[i] * q.contact_ay[i];
         }
         return b * std::hypot(fx, fy);
       }});
  // A Hertz sub-model on the resolved load: the line-contact peak pressure
  // for the tooth's contact force per unit face width and the curvature of
  // its involute flank, 1 / sqrt(r^2 - r_b^2), at the radius where the force
  // acts (force-weighted; held between the form and tip circles), the rack
  // flank being straight. The basis of ISO 6336-2's sigma_H; not read from
  // particles. At the tip the contact meets the involute's end, not the
  // corner's turn, which has no Hertz radius (docs/gears.md).
  const double cx = L.cx, cy = L.cy, rb = L.base_radius;
  const double r_lo = std::max(L.form_radius, rb), r_hi = L.tip_radius;
  scene.columns.push_back(
      {"contact_pressure" + sk + "_Pa",
       [tooth_of, k, e_star, cx, cy, rb, r_lo, r_hi](const Simulation& s2) {
         const Particles& q = s2.particles;
         double fx = 0, fy = 0, wsum = 0, rsum = 0;
         for (std::size_t i = 0; i < q.n; ++i) {
           if (tooth_of[i] != k) continue;
           const double ax = q.contact_ax[i], ay = q.contact_ay[i];
           fx += q.mass[i] * ax;
           fy += q.mass[i] * ay;
           const double w = q.mass[i] * std::hypot(ax, ay);
           wsum += w;
           rsum += w * std::hypot(q.x[i] - cx, q.y[i] - cy);
         }
         if (!(wsum > 0)) return 0.0;
         const double r = std::clamp(rsum / wsum, r_lo, r_hi);
         const double rho = std::sqrt(std::max(r * r - rb * rb, 0.0));
         return rho > 0 ? physics::hertz_peak_pressure(std::hypot(fx, fy), e_star, 1.0 / rho) : 0.0;
       }});
}

// The probe particles' velocities.
void add_probe_histories(Scene& scene, const GearProbes& probes) {
  const std::pair<const char*, std::size_t> named[] = {{"pinion_tooth", probes.pinion_tooth},
                                                       {"rack_tooth", probes.rack_tooth},
                                                       {"rack_back", probes.rack_back}};
  for (const auto& [name, i] : named) {
    scene.columns.push_back({std::string("probe_") + name + "_vx_m_s",
                             [i = i](const Simulation& s2) { return s2.particles.vx[i]; }});
    scene.columns.push_back({std::string("probe_") + name + "_vy_m_s",
                             [i = i](const Simulation& s2) { return s2.particles.vy[i]; }});
  }
}

}  // namespace

void add_gear_histories(Scene& scene, const GearLayout& L, const std::vector<int>& tooth_of,
                        const GearProbes& probes) {
  add_drive_histories(scene, L);
  for (std::size_t t = 0; t < L.pinion_teeth.size(); ++t) {
    add_root_histories(scene, L, t);
    add_tooth_load_histories(scene, L, L.pinion_teeth[t], tooth_of, L.contact_modulus);
  }
  add_probe_histories(scene, probes);
}

}  // namespace gearsph::scenes
