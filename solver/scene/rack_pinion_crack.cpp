// A root crack in the rack_pinion static check (rack_pinion_crack.hpp,
// docs/cracks.md "The gear").
#include "solver/scene/rack_pinion_crack.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "solver/physics/crack_growth.hpp"
#include "solver/physics/total_lagrangian.hpp"
#include "solver/scene/crack_stages.hpp"
#include "solver/scene/rack_pinion_roots.hpp"
#include "solver/scene/scene.hpp"

namespace gearsph::scenes {

namespace {

using geometry::Point;
constexpr double kPi = std::numbers::pi;
// Increments: at least two spacings (a shorter segment cuts too few pairs to
// be a step of the crack), four by default, as the cracked plate's.
constexpr double kLeastIncrementSpacings = 2.0;
constexpr double kDefaultIncrementSpacings = 4.0;
constexpr int kDefaultMaxIncrements = 40;
// The lines of the fan to the other fillet.
constexpr int kFanToFillet = 4;

std::string mm(double m) {
  return std::to_string(1e3 * m) + " mm";
}

// The point and outward normal of the fillet at arc s (linear between
// samples).
void fillet_at(const gear::FilletCurve& c, double s, Point& q, Point& n, Point& t) {
  std::size_t k = 0;
  while (k + 2 < c.size() && c.arc[k + 1] < s) ++k;
  const double f = std::clamp((s - c.arc[k]) / (c.arc[k + 1] - c.arc[k]), 0.0, 1.0);
  q = c.points[k] + f * (c.points[k + 1] - c.points[k]);
  n = c.normal[k] + f * (c.normal[k + 1] - c.normal[k]);
  n = (1.0 / geometry::norm(n)) * n;
  t = c.tangent[k] + f * (c.tangent[k + 1] - c.tangent[k]);
  t = (1.0 / geometry::norm(t)) * t;
}

// The first t > 0 where the ray p + t d meets the segment a-b, or infinity.
double ray_segment(Point p, Point d, Point a, Point b) {
  const Point e = b - a;
  const double den = geometry::cross(d, e);
  if (std::abs(den) < 1e-300) return std::numeric_limits<double>::infinity();
  const Point w = a - p;
  const double t = geometry::cross(w, e) / den, u = geometry::cross(w, d) / den;
  if (t <= 0.0 || u < 0.0 || u > 1.0) return std::numeric_limits<double>::infinity();
  return t;
}

// The first t > 0 where the ray meets the circle |x - c| = r from outside it.
double ray_circle(Point p, Point d, Point c, double r) {
  const Point w = p - c;
  const double b = geometry::dot(w, d), cc = geometry::dot(w, w) - r * r;
  const double disc = b * b - cc;
  if (disc < 0.0 || cc < 0.0) return std::numeric_limits<double>::infinity();
  const double t = -b - std::sqrt(disc);
  return t > 0.0 ? t : std::numeric_limits<double>::infinity();
}

double angle_from_axis(Point q, const GearCrackSite& s) {
  double a = std::atan2(q.y - s.centre.y, q.x - s.centre.x) - s.tooth_axis;
  while (a > kPi) a -= 2.0 * kPi;
  while (a < -kPi) a += 2.0 * kPi;
  return a;
}

double clearance(Point tip, const GearCrackSite& s) {
  const double outline = geometry::distance_to_polyline(s.outline, tip, true);
  const double bore = geometry::norm(tip - s.centre) - s.r_drive;
  return std::min(outline, bore);
}

}  // namespace

double fillet_arc_of_position(const gear::FilletCurve& c, double position) {
  // 0: the fillet's top, where the involute begins (its last sample); 1: its
  // bottom on the root circle, the space's centre (its first).
  return c.arc.back() + position * (c.arc.front() - c.arc.back());
}

GearCrackPlan plan_gear_crack(const nlohmann::json& c, const GearCrackSite& site, bool quasi_static,
                              bool fitted) {
  if (!quasi_static) {
    throw JobError("/scene/crack",
                   "a crack grows in quasi-static stages: it needs \"quasi_static\": true (a "
                   "dynamic run has no static state to read K from)");
  }
  if (!fitted) {
    throw JobError("/discretization/particles",
                   "a gear crack needs body-fitted particles (the default): the paper's lattice "
                   "leaves a staircase at the fillet where the crack starts");
  }
  GearCrackPlan plan;
  const nlohmann::json& pos = c.at("fillet_position");
  if (pos.is_number()) {
    const double p = pos.get<double>();
    if (!(p >= 0.0 && p <= 1.0)) {
      throw JobError("/scene/crack/fillet_position",
                     "a crack starts on the tension fillet: 0 (its top, where the involute "
                     "begins) to 1 (its bottom on the root circle), or \"peak\"");
    }
    plan.position = p;
  }
  plan.length = 1e-3 * c.at("length_mm").get<double>();
  plan.angle = c.value("angle_deg", 0.0) * kPi / 180.0;
  const double least = kCrackLeastClearSpacings * site.spacing;
  if (plan.length < least || plan.length >= site.thickness) {
    throw JobError("/scene/crack/length_mm",
                   "the crack must be at least 8 spacings long (" + mm(least) +
                       " here: the ring that reads K needs them; a finer "
                       "discretization.fine_spacing_m allows a shorter one) and shorter than "
                       "the tooth is thick at its root (s_Fn " +
                       mm(site.thickness) + ")");
  }
  plan.increment = 1e-3 * c.value("increment_mm", 0.0);
  if (plan.increment <= 0.0) plan.increment = kDefaultIncrementSpacings * site.spacing;
  if (plan.increment < kLeastIncrementSpacings * site.spacing || plan.increment > plan.length) {
    throw JobError("/scene/crack/increment_mm",
                   "an increment is at least 2 spacings (" +
                       mm(kLeastIncrementSpacings * site.spacing) +
                       " here) and at most the crack's initial length (" + mm(plan.length) + ")");
  }
  plan.max_increments = c.value("max_increments", kDefaultMaxIncrements);
  if (c.contains("paris")) {
    plan.paris_C = c.at("paris").at("C").get<double>();
    plan.paris_m = c.at("paris").at("m").get<double>();
  }
  // The crack's way, a fan from its start (the peak's: ISO's 30-degree
  // point, near which it lies): to points of the other fillet and the
  // other flank's foot (through the tooth), and to the bore under the
  // start and under the space centres either side (through the rim).
  const gear::FilletCurve& f = site.fillets.tension;
  const gear::FilletCurve& o = site.fillets.compression;
  const double arc = plan.position ? fillet_arc_of_position(f, *plan.position)
                                   : f.arc[f.i30] + f.f30 * (f.arc[f.i30 + 1] - f.arc[f.i30]);
  const std::vector<Point> path = gear_crack_path(plan, site, arc);
  const Point start = path.front();
  for (int k = 0; k <= kFanToFillet; ++k) {
    plan.refine.push_back({start, o.points[(o.size() - 1) * k / kFanToFillet]});
  }
  const double r0 = geometry::norm(start - site.centre);
  const double a0 = std::atan2(start.y - site.centre.y, start.x - site.centre.x);
  for (const double turn : {-1.0, -0.5, 0.0, 0.5, 1.0}) {
    const double a = a0 + turn * site.half_pitch;
    const Point bore = site.centre + site.r_drive * Point{std::cos(a), std::sin(a)};
    if (r0 > site.r_drive) plan.refine.push_back({start, bore});
  }
  return plan;
}

std::vector<Point> gear_crack_path(const GearCrackPlan& plan, const GearCrackSite& site, double arc,
                                   Point* direction) {
  Point q, n, t;
  fillet_at(site.fillets.tension, arc, q, n, t);
  // Angle 0 along the inward normal; positive turned up the fillet, towards
  // the tooth's tip.
  const Point d = std::cos(plan.angle) * (-1.0 * n) + std::sin(plan.angle) * t;
  if (direction) *direction = d;
  // The mouth one spacing outside the surface, so that every pair across the
  // faces is cut up to it (as the cracked plate's).
  return {q - site.spacing * d, q + plan.length * d};
}

std::string gear_crack_heading(const std::vector<Point>& path, const GearCrackSite& site) {
  const Point tip = path.back();
  Point d = tip - path[path.size() - 2];
  d = (1.0 / geometry::norm(d)) * d;
  double best = ray_circle(tip, d, site.centre, site.r_drive);
  bool bore = std::isfinite(best);
  Point hit{};
  const std::size_t m = site.outline.size();
  for (std::size_t k = 0; k < m; ++k) {
    const double tk = ray_segment(tip, d, site.outline[k], site.outline[(k + 1) % m]);
    if (tk < best) {
      best = tk;
      bore = false;
      hit = tip + tk * d;
    }
  }
  if (bore || !std::isfinite(best)) return "rim";
  // Through the tooth: out at the toothed surface (no deeper than a spacing
  // below the root circle) within a pitch of the tooth's axis, i.e. at its
  // other flank or fillet or the floor of the space beside it, so that the
  // tooth comes away. Anything else (the bore, the modelled sector's cut
  // sides) splits the rim.
  const bool near_tooth = std::abs(angle_from_axis(hit, site)) <= 2.0 * site.half_pitch;
  const bool on_surface = geometry::norm(hit - site.centre) >= site.root_radius - site.spacing;
  return near_tooth && on_surface ? "tooth" : "rim";
}

void attach_gear_crack(Scene& scene, const GearCrackPlan& plan, std::shared_ptr<GearCrackSite> site,
                       std::shared_ptr<const RootMonitor> roots, double settle_s) {
  auto g = std::make_shared<CrackStages>();
  g->in.increment = plan.increment;
  g->in.max_increments = plan.max_increments;
  g->dx = site->spacing;
  g->settle_s = settle_s;
  g->clearance = [site](Point tip, const geometry::Crack&) { return clearance(tip, *site); };
  g->boundary_outcome = [site](const geometry::Crack& grown, Point) {
    return gear_crack_heading(grown.path, *site);
  };
  struct Start {
    double arc = 0.0;
    bool placed = false;
  };
  auto start = std::make_shared<Start>();
  if (plan.position) {
    start->arc = fillet_arc_of_position(site->fillets.tension, *plan.position);
    scene.sim.cracks.push_back({0, gear_crack_path(plan, *site, start->arc), false});
    start->placed = true;
  } else {
    // The peak is not known before the first stage: until then the crack is
    // a point at the ISO 30-degree point, which cuts no pair (a pair is cut
    // only across a segment of length), so that the job is checked as a
    // cracked one from the start (the total-Lagrangian form).
    const gear::FilletCurve& f = site->fillets.tension;
    const Point q = f.points[f.i30] + f.f30 * (f.points[f.i30 + 1] - f.points[f.i30]);
    scene.sim.cracks.push_back({0, {q, q}, false});
  }
  // The peak: read on the uncracked tooth at the end of the first stage, the
  // crack cut there, and the tooth settled again before K is read.
  scene.next_stage = [g, start, plan, site, roots, settle_s](Simulation& sim) {
    if (!start->placed) {
      start->arc = roots->at(sim)[site->monitor_tooth].fillet.tension.arc_m;
      sim.cracks.back() = {0, gear_crack_path(plan, *site, start->arc), false};
      start->placed = true;
      sim.reference = ReferencePairs();
      physics::total_lagrangian_setup(sim);
      g->stage_start = std::chrono::steady_clock::now();
      return settle_s;
    }
    return grow_crack_stage(*g, sim);
  };
  const auto before = scene.analyse;
  scene.analyse = [before, g, start, plan, site](const History& h, const Simulation& s2) {
    nlohmann::json out = before(h, s2);
    nlohmann::json c = crack_growth_json(*g);
    const gear::FilletCurve& f = site->fillets.tension;
    c["start_arc_m"] = start->arc;
    c["start_fillet_position"] = (f.arc.back() - start->arc) / (f.arc.back() - f.arc.front());
    c["initial_length_m"] = plan.length;
    c["spacing_m"] = site->spacing;
    // A stop at a boundary classifies the path with the tip that would have
    // come too near it; a run that used its increments before reaching one
    // takes where its last segment heads (reached_boundary false).
    c["reached_boundary"] = g->outcome == "tooth" || g->outcome == "rim";
    if (g->outcome == "max_increments" && start->placed && !s2.cracks.empty()) {
      c["outcome"] = gear_crack_heading(s2.cracks.back().path, *site);
    }
    std::vector<double> K_eq, da;
    for (std::size_t k = 0; k < g->K_I.size(); ++k) {
      K_eq.push_back(physics::equivalent_K(g->K_I[k], g->K_II[k]));
    }
    c["K_eq_Pa_sqrt_m"] = K_eq;
    if (plan.paris_C && !g->paths.empty()) {
      const std::vector<Point>& p = g->paths[0];
      for (std::size_t k = 0; k + 1 < p.size(); ++k) da.push_back(geometry::norm(p[k + 1] - p[k]));
      const double n = physics::paris_cycles(da, K_eq, *plan.paris_C, *plan.paris_m);
      c["paris"] = {{"C", *plan.paris_C},
                    {"m", *plan.paris_m},
                    {"R", 0.0},
                    {"cycles", std::isfinite(n) ? nlohmann::json(n) : nlohmann::json()},
                    {"rule",
                     "trapezoidal in the crack length over each increment of 1 / (C dK_eq^m), "
                     "dK_eq in MPa m^0.5"}};
    }
    out["crack"] = c;
    return out;
  };
}

}  // namespace gearsph::scenes
