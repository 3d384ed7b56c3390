#include "solver/diagnostics/stress_intensity.hpp"

#include <cmath>
#include <numbers>
#include <utility>

#include "solver/physics/crack_face_contact.hpp"
#include "solver/physics/simulation.hpp"

namespace gearsph::diagnostics {

namespace {

constexpr double kPi = std::numbers::pi;
// Step of the central difference of the auxiliary displacement, relative to
// r: its error (step^2) and its round-off (1e-16 / step) both stay below
// 1e-9 of the gradient.
constexpr double kStep = 1e-5;

struct Displacement {
  double u1 = 0.0, u2 = 0.0;
};

// Williams' displacement of K_I and K_II at (r, theta), plane strain
// (kappa = 3 - 4 nu; Anderson, Fracture Mechanics, table 2.2).
Displacement williams_displacement(double K_I, double K_II, double r, double theta, double mu,
                                   double kappa) {
  const double c = std::cos(0.5 * theta), s = std::sin(0.5 * theta);
  const double f = std::sqrt(r / (2.0 * kPi)) / (2.0 * mu);
  Displacement u;
  u.u1 = f * (K_I * c * (kappa - 1.0 + 2.0 * s * s) + K_II * s * (kappa + 1.0 + 2.0 * c * c));
  u.u2 = f * (K_I * s * (kappa + 1.0 - 2.0 * c * c) - K_II * c * (kappa - 1.0 - 2.0 * s * s));
  return u;
}

Displacement displacement_at(double K_I, double K_II, double x1, double x2, double mu,
                             double kappa) {
  return williams_displacement(K_I, K_II, std::hypot(x1, x2), std::atan2(x2, x1), mu, kappa);
}

// The weight's gradient: q = (1 + cos(pi s)) / 2 on the ring, s its
// fraction of the ring's width; returns dq/dr.
double weight_slope(double r, const DomainRing& ring) {
  if (r <= ring.r_in || r >= ring.r_out) return 0.0;
  const double width = ring.r_out - ring.r_in;
  return -0.5 * kPi / width * std::sin(kPi * (r - ring.r_in) / width);
}

// The weight itself: 1 inside the ring, the cosine taper on it, 0 beyond.
double weight(double r, const DomainRing& ring) {
  if (r <= ring.r_in) return 1.0;
  if (r >= ring.r_out) return 0.0;
  return 0.5 * (1.0 + std::cos(kPi * (r - ring.r_in) / (ring.r_out - ring.r_in)));
}

// A point's stress and displacement gradient turned into the tip's frame
// (rows of Q: e1 along the advance, e2 across): T' = Q T Q^T.
struct Local {
  double x1, x2, s11, s22, s12, h11, h12, h21, h22;
};

Local to_tip_frame(const DomainPoint& p, const CrackTip& tip) {
  const double c = tip.direction.x, s = tip.direction.y;  // e1 = (c, s), e2 = (-s, c)
  const double dx = p.X.x - tip.tip.x, dy = p.X.y - tip.tip.y;
  Local l{};
  l.x1 = c * dx + s * dy;
  l.x2 = -s * dx + c * dy;
  l.s11 = c * c * p.sxx + 2.0 * c * s * p.sxy + s * s * p.syy;
  l.s22 = s * s * p.sxx - 2.0 * c * s * p.sxy + c * c * p.syy;
  l.s12 = (c * c - s * s) * p.sxy + c * s * (p.syy - p.sxx);
  l.h11 = c * c * p.hxx + c * s * (p.hxy + p.hyx) + s * s * p.hyy;
  l.h12 = c * c * p.hxy - c * s * (p.hxx - p.hyy) - s * s * p.hyx;
  l.h21 = c * c * p.hyx - c * s * (p.hxx - p.hyy) - s * s * p.hxy;
  l.h22 = s * s * p.hxx - c * s * (p.hxy + p.hyx) + c * c * p.hyy;
  return l;
}

// The integrand of I with the auxiliary field `a`, times dq/dr / r (so that
// q,j = that times x_j).
double interaction_density(const Local& l, const WilliamsField& a) {
  const double e11 = a.h11, e22 = a.h22, e12 = 0.5 * (a.h12 + a.h21);
  const double w_int = l.s11 * e11 + l.s22 * e22 + 2.0 * l.s12 * e12;
  // sigma_ij u^aux_i,1 + sigma^aux_ij u_i,1 - W delta_1j, for j = 1 and 2
  const double t1 = l.s11 * a.h11 + l.s12 * a.h21 + a.s11 * l.h11 + a.s12 * l.h21 - w_int;
  const double t2 = l.s12 * a.h11 + l.s22 * a.h21 + a.s12 * l.h11 + a.s22 * l.h21;
  return t1 * l.x1 + t2 * l.x2;
}

}  // namespace

WilliamsField williams_field(double K_I, double K_II, double x1, double x2, double E, double nu) {
  const double mu = E / (2.0 * (1.0 + nu)), kappa = 3.0 - 4.0 * nu;
  const double r = std::hypot(x1, x2), theta = std::atan2(x2, x1);
  const double c = std::cos(0.5 * theta), s = std::sin(0.5 * theta);
  const double c3 = std::cos(1.5 * theta), s3 = std::sin(1.5 * theta);
  const double f = 1.0 / std::sqrt(2.0 * kPi * r);
  WilliamsField w;  // Anderson, table 2.1
  w.s11 = f * (K_I * c * (1.0 - s * s3) - K_II * s * (2.0 + c * c3));
  w.s22 = f * (K_I * c * (1.0 + s * s3) + K_II * s * c * c3);
  w.s12 = f * (K_I * s * c * c3 + K_II * c * (1.0 - s * s3));
  const double d = kStep * r;
  const Displacement px = displacement_at(K_I, K_II, x1 + d, x2, mu, kappa);
  const Displacement mx = displacement_at(K_I, K_II, x1 - d, x2, mu, kappa);
  const Displacement py = displacement_at(K_I, K_II, x1, x2 + d, mu, kappa);
  const Displacement my = displacement_at(K_I, K_II, x1, x2 - d, mu, kappa);
  w.h11 = (px.u1 - mx.u1) / (2.0 * d);
  w.h21 = (px.u2 - mx.u2) / (2.0 * d);
  w.h12 = (py.u1 - my.u1) / (2.0 * d);
  w.h22 = (py.u2 - my.u2) / (2.0 * d);
  return w;
}

StressIntensity interaction_integral(const std::vector<DomainPoint>& points, const CrackTip& tip,
                                     const DomainRing& ring, double E, double nu) {
  double i_one = 0.0, i_two = 0.0;
  StressIntensity out;
  for (const DomainPoint& p : points) {
    const Local l = to_tip_frame(p, tip);
    const double r = std::hypot(l.x1, l.x2);
    const double slope = weight_slope(r, ring);
    if (slope == 0.0) continue;
    const double w = p.volume * slope / r;
    i_one += w * interaction_density(l, williams_field(1.0, 0.0, l.x1, l.x2, E, nu));
    i_two += w * interaction_density(l, williams_field(0.0, 1.0, l.x1, l.x2, E, nu));
    ++out.points;
  }
  const double e_prime = E / (1.0 - nu * nu);
  out.K_I = 0.5 * e_prime * i_one;
  out.K_II = 0.5 * e_prime * i_two;
  return out;
}

namespace {

// H_i = sum_j V0_j (u_j - u_i) (x) G_ij over the reference pairs, whose
// gradients are corrected (F = I + H, physics/total_lagrangian.hpp), per
// particle as xx, xy, yx, yy.
std::vector<double> displacement_gradients(const Simulation& sim) {
  const Particles& p = sim.particles;
  const ReferencePairs& rp = sim.reference;
  std::vector<double> h(4 * p.n, 0.0);
  auto add = [&](std::size_t a, std::size_t b, double v0, const double* g) {
    const double ux = (p.x[b] - p.x0[b]) - (p.x[a] - p.x0[a]);
    const double uy = (p.y[b] - p.y0[b]) - (p.y[a] - p.y0[a]);
    h[4 * a + 0] += v0 * ux * g[0];
    h[4 * a + 1] += v0 * ux * g[1];
    h[4 * a + 2] += v0 * uy * g[0];
    h[4 * a + 3] += v0 * uy * g[1];
  };
  for (std::size_t i = 0; i < p.n; ++i) {
    for (std::uint32_t k = rp.rows[i]; k < rp.rows[i + 1]; ++k) {
      const std::uint32_t j = rp.j[k];
      add(i, j, rp.vol0[j], &rp.g[4 * k]);
      add(j, i, rp.vol0[i], &rp.g[4 * k + 2]);
    }
  }
  return h;
}

}  // namespace

StressIntensity interaction_integral(const Simulation& sim, int body, const CrackTip& tip,
                                     const DomainRing& ring) {
  const Particles& p = sim.particles;
  if (!sim.reference.built()) return {};
  const std::vector<double> h = displacement_gradients(sim);
  std::vector<DomainPoint> points;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (p.body[i] != body) continue;
    const double r = std::hypot(p.x0[i] - tip.tip.x, p.y0[i] - tip.tip.y);
    if (r <= ring.r_in || r >= ring.r_out) continue;
    points.push_back({{p.x0[i], p.y0[i]},
                      sim.reference.vol0[i],
                      p.sigma_xx(i),
                      p.sigma_yy(i),
                      p.sigma_xy(i),
                      h[4 * i],
                      h[4 * i + 1],
                      h[4 * i + 2],
                      h[4 * i + 3]});
  }
  const Material& m = sim.bodies[static_cast<std::size_t>(body)].material;
  StressIntensity out = interaction_integral(points, tip, ring, m.E, m.nu);
  // Closed faces carry the contact's traction t, which the domain form
  // leaves out: their share of the contour that the domain replaces,
  // I = I_A - int_faces t_i u^aux_i,1 q ds (the auxiliary field's faces are
  // free), with t ds the contact force on a face particle.
  const double c = tip.direction.x, s = tip.direction.y;
  const double e_prime = m.E / (1.0 - m.nu * m.nu);
  for (const physics::CrackFacePair& f : sim.reference.faces) {
    const double force = physics::crack_face_force(sim, f);
    if (force == 0.0) continue;
    for (const auto& [k, sign] : {std::pair{f.i, -1.0}, std::pair{f.j, 1.0}}) {
      if (p.body[k] != body) continue;
      const double dx = p.x0[k] - tip.tip.x, dy = p.y0[k] - tip.tip.y;
      const double q = weight(std::hypot(dx, dy), ring);
      if (q == 0.0) continue;
      const double x1 = c * dx + s * dy, x2 = -s * dx + c * dy;
      const double f1 = sign * force * (c * f.nx + s * f.ny);
      const double f2 = sign * force * (-s * f.nx + c * f.ny);
      const WilliamsField one = williams_field(1.0, 0.0, x1, x2, m.E, m.nu);
      const WilliamsField two = williams_field(0.0, 1.0, x1, x2, m.E, m.nu);
      out.K_I -= 0.5 * e_prime * q * (f1 * one.h11 + f2 * one.h21);
      out.K_II -= 0.5 * e_prime * q * (f1 * two.h11 + f2 * two.h21);
    }
  }
  return out;
}

}  // namespace gearsph::diagnostics
