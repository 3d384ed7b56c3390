#include "solver/scene/rack_pinion_roots.hpp"

#include <algorithm>
#include <cmath>

#include "solver/diagnostics/edge_stress.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::scenes {

namespace {

// Recovery points across the critical section, and the points of a curve.
constexpr int kSectionPoints = 41;

geometry::Point at_fraction(const gear::FilletCurve& c) {
  const geometry::Point a = c.points[c.i30], b = c.points[c.i30 + 1];
  return a + c.f30 * (b - a);
}

// The stress tensor at the fillet's own samples (past the reach).
std::vector<gear::PlaneStress> plane(const std::vector<diagnostics::RecoveredStress>& r,
                                     std::size_t first, std::size_t n) {
  std::vector<gear::PlaneStress> out;
  out.reserve(n);
  for (std::size_t k = first; k < first + n; ++k) out.push_back({r[k].xx, r[k].yy, r[k].xy});
  return out;
}

}  // namespace

RootMonitor::RootMonitor(const Simulation& sim, int body, std::vector<int> teeth,
                         std::vector<gear::ToothFillets> fillets, int hub_motion, double window,
                         bool from_stretch)
    : teeth_(std::move(teeth)),
      fillets_(std::move(fillets)),
      hub_motion_(hub_motion),
      window_(window),
      from_stretch_(from_stretch),
      E_(sim.bodies.at(static_cast<std::size_t>(body)).material.E),
      nu_(sim.bodies.at(static_cast<std::size_t>(body)).material.nu) {
  auto edge = [&sim, body](const gear::FilletCurve& c) {
    Edge e;
    e.points = gear::with_reach(c, &e.arc);
    e.first = c.before.size();
    e.recovery = std::make_unique<diagnostics::StressRecovery>(sim, body, e.points);
    return e;
  };
  for (const gear::ToothFillets& f : fillets_) {
    tension_.push_back(edge(f.tension));
    compression_.push_back(edge(f.compression));
    // The chord between the two 30-degree points, sampled evenly; its ends
    // lie on the outline, where the recovery interpolates the outline row.
    Section sec;
    const geometry::Point p = at_fraction(f.tension), q = at_fraction(f.compression);
    sec.centre = 0.5 * (p + q);
    sec.width = geometry::norm(q - p);
    sec.along = (1.0 / sec.width) * (q - p);
    std::vector<geometry::Point> points;
    for (int k = 0; k < kSectionPoints; ++k) {
      const double s = sec.width * (static_cast<double>(k) / (kSectionPoints - 1) - 0.5);
      sec.s.push_back(s);
      points.push_back(sec.centre + s * sec.along);
    }
    section_.push_back(std::make_unique<diagnostics::StressRecovery>(sim, body, points));
    sections_.push_back(sec);
  }
}

const std::vector<ToothRootState>& RootMonitor::at(const Simulation& sim) const {
  if (sim.step == step_ && sim.time == time_ && state_.size() == fillets_.size()) return state_;
  state_.assign(fillets_.size(), {});
  const double angle =
      hub_motion_ < static_cast<int>(sim.motions.size()) ? sim.motions[hub_motion_].angle : 0.0;
  for (std::size_t t = 0; t < fillets_.size(); ++t) {
    const gear::ToothFillets& f = fillets_[t];
    ToothRootState& st = state_[t];
    // Tangential stress from the stretch of each fillet, and the fitted
    // tensor at its samples.
    std::vector<double> tangential[2];
    std::vector<gear::PlaneStress> tensor[2];
    for (int side = 0; side < 2; ++side) {
      const Edge& e = side == 0 ? tension_[t] : compression_[t];
      const std::size_t n = side == 0 ? f.tension.size() : f.compression.size();
      const std::vector<diagnostics::RecoveredStress> r = e.recovery->recover(sim);
      diagnostics::EdgeCurve curve{e.points, {}, e.arc, false};
      for (const diagnostics::RecoveredStress& q : r) curve.displacement.push_back({q.ux, q.uy});
      const std::vector<double> tt = diagnostics::edge_tangential_stress(curve, window_, E_, nu_);
      tangential[side].assign(tt.begin() + static_cast<std::ptrdiff_t>(e.first),
                              tt.begin() + static_cast<std::ptrdiff_t>(e.first + n));
      tensor[side] = plane(r, e.first, n);
    }
    const gear::FilletStress stretch = gear::fillet_stress(f, tangential[0], tangential[1]);
    st.fillet_stress_fit = gear::fillet_stress(f, tensor[0], tensor[1]);
    st.fillet = from_stretch_ ? stretch : st.fillet_stress_fit;
    // sigma_1 of either fillet at its 30-degree point (either flank may
    // carry load: rattle in the backlash).
    const gear::FilletCurve& cc = f.compression;
    const double compression_at30 =
        from_stretch_
            ? std::max(tangential[1][cc.i30] +
                           cc.f30 * (tangential[1][cc.i30 + 1] - tangential[1][cc.i30]),
                       0.0)
            : tensor[1][cc.i30].max_principal() + cc.f30 * (tensor[1][cc.i30 + 1].max_principal() -
                                                            tensor[1][cc.i30].max_principal());
    st.root_stress_Pa = std::max(st.fillet.tension.at_iso30_Pa, compression_at30);
    // Normal stress across the section (along the tooth axis, turned with
    // the hub), integrated by the trapezoidal rule.
    const Section& sec = sections_[t];
    const double c = std::cos(angle), sn = std::sin(angle);
    const double ux = c * sec.along.x - sn * sec.along.y, uy = sn * sec.along.x + c * sec.along.y;
    const double nx = -uy, ny = ux;
    const std::vector<diagnostics::RecoveredStress> r = section_[t]->recover(sim);
    double force = 0.0, moment = 0.0;
    for (std::size_t k = 0; k < r.size(); ++k) {
      const double snn = nx * nx * r[k].xx + 2.0 * nx * ny * r[k].xy + ny * ny * r[k].yy;
      const double w = (k == 0 || k + 1 == r.size() ? 0.5 : 1.0) * sec.width / (r.size() - 1);
      force += w * snn;
      moment += w * snn * sec.s[k];
    }
    st.section_normal_force_N_per_m = force;
    st.section_bending_moment_N = moment;
    st.section_nominal_bending_Pa = 6.0 * std::abs(moment) / (sec.width * sec.width);
  }
  step_ = sim.step;
  time_ = sim.time;
  return state_;
}

}  // namespace gearsph::scenes
