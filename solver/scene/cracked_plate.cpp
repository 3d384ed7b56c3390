// A cracked plate in tension (docs/cracks.md): a plate W x L pulled by a
// uniform traction sigma on its two short ends and relaxed to the static
// state (load ramp and mass-proportional damping of the slowest mode, as
// the Kirsch scene does), with a straight crack of the reference
// configuration (geometry/crack.hpp) whose faces the particles do not
// bridge. Angle 0 puts the crack across the load.
//
// References (Tada, Paris & Irwin, The Stress Analysis of Cracks Handbook,
// 3rd ed., 2000):
//   edge crack of length a, angle 0:  K_I = sigma sqrt(pi a) F(a/W),
//     F(s) = 1.12 - 0.231 s + 10.55 s^2 - 21.72 s^3 + 30.39 s^4 (page 2.10;
//     0.5 % for s <= 0.6; ends free to rotate, as the uniform traction has
//     them), K_II = 0 by symmetry;
//   centre crack of length 2a at angle beta:  K_I = sigma cos^2(beta)
//     sqrt(pi a) F, K_II = sigma sin(beta) cos(beta) sqrt(pi a) F, the
//     normal and shear tractions of the uncracked plate on the crack's line
//     (exact for the infinite plate), with the finite-width factor of the
//     straight crack F(alpha) = (1 - 0.025 alpha^2 + 0.06 alpha^4)
//     sqrt(sec(pi alpha / 2)) (page 2.2, 0.1 % for any alpha) taken at the
//     crack's extent across the plate, alpha = 2 a cos(beta) / W, an
//     approximation for beta != 0 that the docs measure.
// K_I and K_II are read by the interaction integral on a ring around each
// tip (diagnostics/stress_intensity.hpp).
#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <optional>

#include "solver/diagnostics/stress_intensity.hpp"
#include "solver/physics/crack_growth.hpp"
#include "solver/physics/total_lagrangian.hpp"
#include "solver/scene/builders.hpp"
#include "solver/scene/crack_stages.hpp"
#include "solver/scene/lattice.hpp"

namespace gearsph::scenes {

namespace {

constexpr double kPi = std::numbers::pi;
// The ring of the domain integral, as fractions of the distance rho from
// the tip to the nearest other boundary (an edge, the mouth, the other
// tip): wide enough to hold many particles, clear of the tip's support
// inside and of the other boundaries outside (docs/cracks.md measures
// the result's independence of them).
constexpr double kRingOuter = kCrackRingOuter;
constexpr double kRingInner = kCrackRingInner;
// A second, smaller ring that reaches into the tip's support, reported for
// the domain independence (a path-independent integral gives the same K on
// any ring where the discrete field is sound).
constexpr double kSmallRingOuter = 0.5;
constexpr double kSmallRingInner = 0.15;
// Spacings along the crack (edge: its length; centre: its half-length) the
// ring needs to leave the tip's support out; the default puts twenty there
// (K_I within 3-6 % of Tada for a/W 0.1-0.6, converging at first order in
// the spacing: docs/cracks.md).
constexpr double kLeastSpacingsAlong = 8.0;
constexpr double kDefaultSpacingsAlong = 20.0;
// Tada's edge-crack factor holds to a/W = 0.6; a centre crack's extent
// leaves at least a tenth of the width on either side.
constexpr double kEdgeMostAcross = 0.6;
constexpr double kCentreMostAcross = 0.8;

// Growth (physics/crack_growth.hpp): the increment's least length and its
// default, in spacings. A segment of two spacings cuts the pairs of at
// least two rows of particles on either side of it; four is the default.
constexpr double kLeastIncrementSpacings = 2.0;
constexpr double kDefaultIncrementSpacings = 4.0;

struct CrackInput {
  bool edge = true;
  double length = 0.0;  // edge: a; centre: 2a [m]
  double angle = 0.0;   // from the normal to the load [rad]
  CrackGrowthInput growth;
  double a() const { return edge ? length : 0.5 * length; }
};

CrackInput read_crack(const nlohmann::json& c) {
  CrackInput in;
  in.edge = c.at("kind").get<std::string>() == "edge";
  in.length = c.at("length_m").get<double>();
  in.angle = c.at("angle_deg").get<double>() * kPi / 180.0;
  in.growth.increment = c.value("increment_m", 0.0);
  in.growth.max_increments = c.value("max_increments", 0);
  in.growth.K_I_threshold = c.value("K_I_threshold_Pa_sqrt_m", 0.0);
  return in;
}

// The increment as asked, or the default; refused below two spacings or
// beyond the crack's own length (edge) or half-length (centre).
double growth_increment(const CrackInput& c, double dx) {
  if (c.growth.increment <= 0.0) return kDefaultIncrementSpacings * dx;
  if (c.growth.increment < kLeastIncrementSpacings * dx || c.growth.increment > c.a()) {
    throw JobError(
        "/scene/crack/increment_m",
        "an increment is at least 2 spacings (" + std::to_string(kLeastIncrementSpacings * dx) +
            " m here: a shorter segment cuts too few pairs to be a step of the crack) "
            "and at most the crack's " +
            std::string(c.edge ? "length" : "half-length") + " (" + std::to_string(c.a()) + " m)");
  }
  return c.growth.increment;
}

void check_proportions(double W, double L, const CrackInput& c) {
  if (L < 2.0 * W) {
    throw JobError("/scene/length_m",
                   "the plate must be at least twice as long as it is wide, or its loaded ends "
                   "change the field at the crack");
  }
  const double across = c.length * std::cos(c.angle), along = c.length * std::sin(c.angle);
  if (c.edge && across > kEdgeMostAcross * W) {
    throw JobError("/scene/crack/length_m",
                   "an edge crack may reach at most 0.6 of the width across the plate (length "
                   "times cos(angle) <= 0.6 width_m: Tada's factor holds to a/W = 0.6, and a "
                   "ligament is left); this one reaches " +
                       std::to_string(across / W) + " of it");
  }
  if (!c.edge && across > kCentreMostAcross * W) {
    throw JobError("/scene/crack/length_m",
                   "a centre crack may span at most 0.8 of the width across the plate (length "
                   "times cos(angle) <= 0.8 width_m); this one spans " +
                       std::to_string(across / W) + " of it");
  }
  if (std::abs(along) > 0.5 * L) {
    throw JobError("/scene/crack/angle_deg",
                   "the crack runs along the load over more than half the plate's length "
                   "(length times sin(angle) <= length_m / 2)");
  }
}

double crack_spacing(Discretization& d, const CrackInput& c) {
  if (d.layout == ParticleLayout::BodyFitted) {
    throw JobError("/discretization/particles",
                   "the cracked plate places its particles on a lattice only (the crack runs "
                   "between lattice columns, so that no particle sits on a face)");
  }
  particle_layout(d, ParticleLayout::Lattice);
  if (d.dx <= 0.0) d.dx = c.a() / kDefaultSpacingsAlong;
  if (c.a() < kLeastSpacingsAlong * d.dx) {
    throw JobError("/discretization", "the crack needs at least 8 spacings along its " +
                                          std::string(c.edge ? "length" : "half-length") +
                                          " (a spacing of at most " +
                                          std::to_string(c.a() / kLeastSpacingsAlong) +
                                          " m) for its tip's field to be read");
  }
  return d.dx;
}

// The crack's path, from the mouth (beyond the free edge, so that every
// pair across the faces is cut up to the surface) or the first tip, to the
// tip. Edge cracks start on the edge y = -W/2 at x = 0; centre cracks are
// centred on the origin; both at x = 0 between two lattice columns for
// angle 0.
geometry::Crack crack_path(const CrackInput& c, double half_width, double dx) {
  const geometry::Point d{std::sin(c.angle), std::cos(c.angle)};
  geometry::Crack crack;
  if (c.edge) {
    const geometry::Point mouth{0.0, -half_width};
    crack.path = {mouth - dx * d, mouth + c.length * d};
  } else {
    crack.path = {-c.a() * d, c.a() * d};
    crack.front_is_tip = true;
  }
  return crack;
}

// The lattice plate, its end columns pulled by sigma (each particle a
// spacing's share of the edge); returns the half-length and half-width as
// modelled. Even numbers of columns and rows put x = 0 and y = 0 between
// two of them: a crack across the load lies between columns, and a tip a
// whole number of spacings from the edge or the centre lies between rows.
geometry::Point fill_plate(Simulation& sim, double W, double L, double dx, double sigma,
                           const Material& mat) {
  long nx = lattice::cells(L, dx);
  nx += nx % 2;
  long ny = lattice::cells(W, dx);
  ny += ny % 2;
  const geometry::Point half{0.5 * nx * dx, 0.5 * ny * dx};
  add_body(sim, "plate", mat);
  lattice::fill_rectangle(-half.x, -half.y, nx, ny, dx,
                          [&](double x, double y) { add_particle(sim, x, y, 0); });
  end_body(sim);
  Particles& p = sim.particles;
  for (std::size_t i = 0; i < p.n; ++i) {
    const double share = sigma * dx / p.mass[i];  // force per unit thickness / mass
    if (p.x[i] > half.x - dx) p.load_ax[i] = share;
    if (p.x[i] < -half.x + dx) p.load_ax[i] = -share;
  }
  return half;
}

// Tada's finite-width factors (see the file's comment).
double edge_factor(double s) {
  return 1.12 - 0.231 * s + 10.55 * s * s - 21.72 * std::pow(s, 3) + 30.39 * std::pow(s, 4);
}
double centre_factor(double alpha) {
  const double sec = 1.0 / std::cos(0.5 * kPi * alpha);
  return (1.0 - 0.025 * alpha * alpha + 0.06 * std::pow(alpha, 4)) * std::sqrt(sec);
}

struct Reference {
  std::optional<double> K_I, K_II;
  double scale = 0.0;  // |sigma| sqrt(pi a)
  std::string text;
};

// The references at the tip path.back() (whose advance is +d).
Reference reference_factors(const CrackInput& c, double sigma, double width) {
  Reference r;
  const double root = std::sqrt(kPi * c.a());
  r.scale = std::abs(sigma) * root;
  // In compression the faces close (physics/crack_face_contact.hpp): they
  // carry the normal traction, none of mode I is left, and frictionless
  // faces slide under the shear traction alone.
  const bool closed = sigma < 0.0;
  if (c.edge) {
    r.text = "Tada, Paris & Irwin: single edge crack in a strip, K_I = sigma sqrt(pi a) F(a/W)";
    if (closed) r.text = "compression closes the crack: K_I = 0";
    if (c.angle != 0.0) {
      r.text += "; none for an inclined edge crack";
      return r;
    }
    r.K_I = closed ? 0.0 : sigma * root * edge_factor(c.length / width);
    r.K_II = 0.0;
    return r;
  }
  r.text =
      "Tada, Paris & Irwin: centre crack, sigma_n sqrt(pi a) F and tau sqrt(pi a) F with "
      "F(2 a cos(beta) / W)";
  const double f = centre_factor(c.length * std::cos(c.angle) / width);
  // Tractions of the uncracked plate (sigma along x) on the crack's line,
  // in the tip's frame e1 = d = (sin b, cos b), e2 = (-cos b, sin b).
  const double cb = std::cos(c.angle), sb = std::sin(c.angle);
  if (closed) r.text += "; compression closes the crack: K_I = 0, K_II from the shear traction";
  r.K_I = closed ? 0.0 : sigma * cb * cb * root * f;
  r.K_II = -sigma * sb * cb * root * f;
  return r;
}

// The distance from a tip to the nearest other boundary: the plate's edges
// and, for a centre crack, the other tip.
double clear_radius(geometry::Point tip, const geometry::Crack& crack, geometry::Point half) {
  double rho = std::min({half.x - std::abs(tip.x), half.y - std::abs(tip.y)});
  if (crack.front_is_tip) {
    const geometry::Point d = crack.path.back() - crack.path.front();
    rho = std::min(rho, std::hypot(d.x, d.y));
  }
  return rho;
}

nlohmann::json tip_json(const diagnostics::StressIntensity& k, const CrackTipReadout& t,
                        const Simulation& s2) {
  const double rho = t.ring.r_out / kRingOuter;
  const diagnostics::DomainRing small{kSmallRingInner * rho, kSmallRingOuter * rho};
  const diagnostics::StressIntensity ks = diagnostics::interaction_integral(s2, 0, t.tip, small);
  return {{"tip_m", {t.tip.tip.x, t.tip.tip.y}},
          {"K_I_Pa_sqrt_m", k.K_I},
          {"K_II_Pa_sqrt_m", k.K_II},
          {"ring_m", {t.ring.r_in, t.ring.r_out}},
          {"ring_particles", k.points},
          {"small_ring_m", {small.r_in, small.r_out}},
          {"small_ring_K_I_Pa_sqrt_m", ks.K_I},
          {"small_ring_K_II_Pa_sqrt_m", ks.K_II}};
}

// K at every tip, their mean (a centre crack's two tips are alike by
// symmetry; K_II's sign is each tip's own frame's, alike too), against the
// references.
nlohmann::json analyse_cracked_plate(const std::vector<CrackTipReadout>& tips, const Reference& ref,
                                     const Simulation& s2) {
  nlohmann::json out;
  out["reference"] = ref.text;
  double ki = 0.0, kii = 0.0;
  for (const CrackTipReadout& t : tips) {
    const diagnostics::StressIntensity k = diagnostics::interaction_integral(s2, 0, t.tip, t.ring);
    out["tips"].push_back(tip_json(k, t, s2));
    ki += k.K_I / static_cast<double>(tips.size());
    kii += k.K_II / static_cast<double>(tips.size());
  }
  out["K_I_Pa_sqrt_m"] = ki;
  out["K_II_Pa_sqrt_m"] = kii;
  out["reference_K_I_Pa_sqrt_m"] = ref.K_I ? nlohmann::json(*ref.K_I) : nlohmann::json();
  out["reference_K_II_Pa_sqrt_m"] = ref.K_II ? nlohmann::json(*ref.K_II) : nlohmann::json();
  if (ref.K_I && *ref.K_I != 0.0) out["K_I_error"] = (ki - *ref.K_I) / *ref.K_I;
  // K_II against the scale of the loading (K_II's own reference may be 0).
  if (ref.K_II && ref.K_I && *ref.K_I != 0.0) {
    out["K_II_error_over_K_I"] = (kii - *ref.K_II) / *ref.K_I;
  }
  // Against |sigma| sqrt(pi a), which a closed crack's K_I = 0 needs.
  out["load_scale_Pa_sqrt_m"] = ref.scale;
  if (ref.K_I) out["K_I_error_over_scale"] = (ki - *ref.K_I) / ref.scale;
  if (ref.K_II && *ref.K_II != 0.0) out["K_II_error"] = (kii - *ref.K_II) / *ref.K_II;
  return out;
}

}  // namespace

Scene build_cracked_plate(const SceneInput& in) {
  const nlohmann::json& s = in.scene;
  const double W = s.at("width_m").get<double>(), L = s.at("length_m").get<double>();
  const double sigma = s.at("tension_Pa").get<double>();
  const Material mat = read_material(s.at("material"));
  const CrackInput crack = read_crack(s.at("crack"));
  check_proportions(W, L, crack);

  Scene scene = start_scene("cracked_plate", in);
  Simulation& sim = scene.sim;
  const double dx = crack_spacing(sim.discretization, crack);
  const double increment = growth_increment(crack, dx);
  const geometry::Point half = fill_plate(sim, W, L, dx, sigma, mat);
  sim.cracks.push_back(crack_path(crack, half.y, dx));
  const std::vector<geometry::Point> path = sim.cracks.back().path;
  const CrackClearance clearance = [half](geometry::Point tip, const geometry::Crack& c) {
    return clear_radius(tip, c, half);
  };
  const std::vector<CrackTipReadout> tips = crack_tips(sim.cracks.back(), clearance);
  sim.domain = grown_bounds(sim.particles, L);
  const geometry::Polygon rect = {
      {-half.x, -half.y}, {half.x, -half.y}, {half.x, half.y}, {-half.x, half.y}};
  scene.outlines.push_back(polygon_outline("plate", 0, rect));
  scene.outlines.push_back({"crack", 0, {{path[0].x, path[0].y}, {path[1].x, path[1].y}}, false});

  // Dynamic relaxation at the slower of the plate's stretch along its
  // length (omega = pi c / L) and its first free-free bending mode, which
  // an edge crack's eccentric section excites (omega = 22.37 sqrt(E I /
  // (rho A L^4)), Blevins, Formulas for Natural Frequency, table 8-1).
  const double c_bar = mat.strip_wave_speed();
  const double length = 2.0 * half.x, width = 2.0 * half.y;
  const double bending = 22.37 * width / (length * length) * c_bar / std::sqrt(12.0);
  const double omega = std::min(kPi * c_bar / length, bending);
  relax_to_static(scene, omega);

  const Reference ref = reference_factors(crack, sigma, width);
  // K_I at the crack's end as it is now (it moves as the crack grows).
  scene.columns.push_back({"K_I_Pa_sqrt_m", [clearance](const Simulation& s2) {
                             const CrackTipReadout t = crack_tips(s2.cracks.back(), clearance)[0];
                             return diagnostics::interaction_integral(s2, 0, t.tip, t.ring).K_I;
                           }});
  scene.description = {{"plate_m", {length, width}},
                       {"crack_kind", crack.edge ? "edge" : "centre"},
                       {"a_over_W", (crack.edge ? crack.length : 2.0 * crack.a()) / width},
                       {"spacings_along_a", crack.a() / dx}};
  if (crack.growth.max_increments == 0) {
    scene.analyse = [=](const History&, const Simulation& s2) {
      return analyse_cracked_plate(tips, ref, s2);
    };
    return scene;
  }
  auto growth = std::make_shared<CrackStages>();
  auto initial = std::make_shared<nlohmann::json>();
  growth->in = crack.growth;
  growth->in.increment = increment;
  growth->dx = dx;
  growth->settle_s = kCrackSettlePeriods * 2.0 * kPi / omega;
  growth->clearance = clearance;
  growth->on_first_stage = [initial, ref](const std::vector<CrackTipReadout>& t,
                                          const Simulation& s2) {
    *initial = analyse_cracked_plate(t, ref, s2);
  };
  scene.next_stage = [growth](Simulation& s2) { return grow_crack_stage(*growth, s2); };
  // The drawn crack's K against its references (read at the first stage),
  // then the growth.
  scene.analyse = [=](const History&, const Simulation& s2) {
    nlohmann::json out = initial->is_null() ? analyse_cracked_plate(tips, ref, s2) : *initial;
    out["crack"] = crack_growth_json(*growth);
    return out;
  };
  return scene;
}

}  // namespace gearsph::scenes
