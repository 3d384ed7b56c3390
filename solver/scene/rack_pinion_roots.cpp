#include "solver/scene/rack_pinion_roots.hpp"

#include <algorithm>
#include <cmath>

#include "solver/core/simulation.hpp"

namespace gearsph::scenes {

namespace {

// Recovery points across the critical section, and the points of a curve.
constexpr int kSectionPoints = 41;

geometry::Point at_fraction(const gear::FilletCurve& c) {
  const geometry::Point a = c.points[c.i30], b = c.points[c.i30 + 1];
  return a + c.f30 * (b - a);
}

std::vector<gear::PlaneStress> plane(const std::vector<diagnostics::RecoveredStress>& r) {
  std::vector<gear::PlaneStress> out;
  out.reserve(r.size());
  for (const diagnostics::RecoveredStress& s : r) out.push_back({s.xx, s.yy, s.xy});
  return out;
}

}  // namespace

RootMonitor::RootMonitor(const Simulation& sim, int body, std::vector<int> teeth,
                         std::vector<gear::ToothFillets> fillets, int hub_motion)
    : teeth_(std::move(teeth)), fillets_(std::move(fillets)), hub_motion_(hub_motion) {
  for (const gear::ToothFillets& f : fillets_) {
    tension_.push_back(std::make_unique<diagnostics::StressRecovery>(sim, body, f.tension.points));
    compression_.push_back(
        std::make_unique<diagnostics::StressRecovery>(sim, body, f.compression.points));
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
    const std::vector<gear::PlaneStress> compression = plane(compression_[t]->recover(sim));
    st.fillet = gear::fillet_stress(f, plane(tension_[t]->recover(sim)), compression);
    // sigma_1 of either fillet at its 30-degree point.
    const auto at30 = [](const std::vector<double>& v, const gear::FilletCurve& c) {
      return v[c.i30] + c.f30 * (v[c.i30 + 1] - v[c.i30]);
    };
    std::vector<double> compression_sigma1;
    for (const gear::PlaneStress& s : compression) {
      compression_sigma1.push_back(s.max_principal());
    }
    st.root_stress_Pa =
        std::max(st.fillet.tension.at_iso30_Pa, at30(compression_sigma1, f.compression));
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
