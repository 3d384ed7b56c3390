#include "solver/scene/crack_stages.hpp"

#include <cmath>
#include <numbers>

#include "solver/physics/crack_growth.hpp"
#include "solver/physics/total_lagrangian.hpp"

namespace gearsph::scenes {

namespace {

CrackTipReadout tip_readout(geometry::Point tip, geometry::Point behind,
                            const geometry::Crack& crack, const CrackClearance& clearance) {
  const geometry::Point d = tip - behind;
  const double n = std::hypot(d.x, d.y);
  const double rho = clearance(tip, crack);
  return {{tip, {d.x / n, d.y / n}}, {kCrackRingInner * rho, kCrackRingOuter * rho}, rho};
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

std::vector<CrackTipReadout> crack_tips(const geometry::Crack& crack,
                                        const CrackClearance& clearance) {
  const std::vector<geometry::Point>& p = crack.path;
  std::vector<CrackTipReadout> tips{tip_readout(p.back(), p[p.size() - 2], crack, clearance)};
  if (crack.front_is_tip) tips.push_back(tip_readout(p.front(), p[1], crack, clearance));
  return tips;
}

double grow_crack_stage(CrackStages& g, Simulation& sim) {
  g.stage_s.push_back(seconds_since(g.stage_start));
  geometry::Crack& crack = sim.cracks.back();
  const std::vector<CrackTipReadout> tips = crack_tips(crack, g.clearance);
  if (!g.first_done && g.on_first_stage) g.on_first_stage(tips, sim);
  g.first_done = true;
  double ki = 0.0, kii = 0.0;
  std::vector<geometry::Point> next;
  for (std::size_t t = 0; t < tips.size(); ++t) {
    const diagnostics::StressIntensity k =
        diagnostics::interaction_integral(sim, crack.body, tips[t].tip, tips[t].ring);
    if (g.paths.size() <= t) g.paths.push_back({tips[t].tip.tip});
    ki += k.K_I / static_cast<double>(tips.size());
    kii += k.K_II / static_cast<double>(tips.size());
    const double kink = physics::max_tangential_stress_kink(k.K_I, k.K_II);
    next.push_back(
        physics::grown_tip(tips[t].tip.tip, tips[t].tip.direction, kink, g.in.increment));
    if (t == 0) g.kink_deg.push_back(kink * 180.0 / std::numbers::pi);
  }
  g.K_I.push_back(ki);
  g.K_II.push_back(kii);
  const int done = static_cast<int>(g.paths[0].size()) - 1;
  if (ki < g.in.K_I_threshold) {
    g.outcome = "arrested";
    g.stop = "K_I " + std::to_string(ki) + " Pa m^0.5 fell below the threshold";
    return 0.0;
  }
  if (done >= g.in.max_increments) {
    g.outcome = "max_increments";
    g.stop = std::to_string(done) + " increments, as asked";
    return 0.0;
  }
  // Every tip grown at once (a centre crack's two), then each new tip's room
  // checked on the grown crack.
  geometry::Crack grown = crack;
  grown.path.push_back(next[0]);
  if (next.size() > 1) grown.path.insert(grown.path.begin(), next[1]);
  for (const geometry::Point q : next) {
    const double rho = g.clearance(q, grown);
    if (rho < kCrackLeastClearSpacings * g.dx) {
      g.outcome = g.boundary_outcome ? g.boundary_outcome(grown, q) : "free_surface";
      g.stop = "the next tip would lie " + std::to_string(rho / g.dx) +
               " spacings from a boundary: " +
               (rho < g.dx ? std::string("within a spacing of it")
                           : "too near for the ring that reads K (at least 8 spacings)");
      return 0.0;
    }
  }
  crack = grown;
  for (std::size_t t = 0; t < next.size(); ++t) g.paths[t].push_back(next[t]);
  // The pairs and their corrections built again for the new cut, on the same
  // reference positions: every particle's (docs/cracks.md measures the cost
  // against the stage's settling).
  const auto rebuild = std::chrono::steady_clock::now();
  sim.reference = ReferencePairs();
  physics::total_lagrangian_setup(sim);
  g.rebuild_s.push_back(seconds_since(rebuild));
  g.stage_start = std::chrono::steady_clock::now();
  return g.settle_s;
}

nlohmann::json crack_growth_json(const CrackStages& g) {
  nlohmann::json paths = nlohmann::json::array();
  for (const auto& path : g.paths) {
    nlohmann::json pts = nlohmann::json::array();
    for (const geometry::Point q : path) pts.push_back({q.x, q.y});
    paths.push_back(pts);
  }
  return {{"increment_m", g.in.increment},
          {"increments", g.paths.empty() ? std::size_t{0} : g.paths[0].size() - 1},
          {"path_m", paths.empty() ? nlohmann::json::array() : paths[0]},
          {"tip_paths_m", paths},
          {"K_I_Pa_sqrt_m", g.K_I},
          {"K_II_Pa_sqrt_m", g.K_II},
          {"kink_deg", g.kink_deg},
          {"outcome", g.outcome.empty() ? nlohmann::json() : nlohmann::json(g.outcome)},
          {"stop", g.stop},
          {"pair_rebuild_s", g.rebuild_s},
          {"stage_wall_s", g.stage_s}};
}

}  // namespace gearsph::scenes
