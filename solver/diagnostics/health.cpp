#include "solver/diagnostics/health.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "solver/physics/simulation.hpp"

namespace gearsph::diagnostics {

HealthLimits read_health_limits(const nlohmann::json& h) {
  HealthLimits l;
  if (!h.is_object()) return l;
  if (h.contains("on_failure")) l.stop = h.at("on_failure").get<std::string>() == "stop";
  if (h.contains("energy_growth_max")) l.energy_growth = h.at("energy_growth_max").get<double>();
  if (h.contains("min_spacing_over_dx")) {
    l.min_spacing_over_dx = h.at("min_spacing_over_dx").get<double>();
  }
  if (h.contains("penetration_max_over_dx")) {
    l.penetration_over_dx = h.at("penetration_max_over_dx").get<double>();
  }
  if (h.contains("zigzag_warning")) l.zigzag = h.at("zigzag_warning").get<double>();
  return l;
}

namespace {

// Calls f(i, j) for each same-body pair of the run's interaction list
// (reference pairs for total Lagrangian, the Verlet list otherwise).
template <class F>
void for_each_body_pair(const Simulation& sim, F&& f) {
  const Particles& p = sim.particles;
  const bool tl = sim.reference.built();
  const auto& rows = tl ? sim.reference.rows : sim.neighbours.rows;
  const auto& js = tl ? sim.reference.j : sim.neighbours.j;
  if (rows.size() < p.n + 1) return;
  for (std::size_t i = 0; i < p.n; ++i) {
    for (std::uint32_t k = rows[i]; k < rows[i + 1]; ++k) {
      const std::size_t j = js[k];
      if (j <= i || p.body[j] != p.body[i]) continue;
      f(i, j);
    }
  }
}

}  // namespace

namespace {

// The same-body pairs with their spacing (the pair's own: graded particles;
// dx on a lattice), and those whose reference distance is about one spacing.
void find_health_pairs(const Simulation& sim, HealthPairs& h) {
  const Particles& p = sim.particles;
  h.i.clear();
  h.j.clear();
  h.dx2.clear();
  h.near.clear();
  const double *x0 = p.x0.data(), *y0 = p.y0.data(), *spacing = p.spacing.data();
  for_each_body_pair(sim, [&](std::size_t i, std::size_t j) {
    const double ddx = x0[i] - x0[j], ddy = y0[i] - y0[j];
    const double dx = 0.5 * (spacing[i] + spacing[j]);
    if (ddx * ddx + ddy * ddy <= 1.5 * 1.5 * dx * dx) {
      h.near.push_back(static_cast<std::uint32_t>(h.i.size()));
    }
    h.i.push_back(static_cast<std::uint32_t>(i));
    h.j.push_back(static_cast<std::uint32_t>(j));
    h.dx2.push_back(dx * dx);
  });
  h.count.assign(p.n, 0.0);
  for (const std::uint32_t k : h.near) {
    h.count[h.i[k]] += 1.0;
    h.count[h.j[k]] += 1.0;
  }
  h.particles = p.n;
  h.fixed = sim.reference.built();
}

void refresh(const Simulation& sim, HealthPairs& h) {
  if (!h.fixed || h.particles != sim.particles.n) find_health_pairs(sim, h);
}

}  // namespace

Spacing min_spacing(const Simulation& sim, HealthPairs& h) {
  refresh(sim, h);
  const Particles& p = sim.particles;
  const double *x = p.x.data(), *y = p.y.data(), *dx2 = h.dx2.data();
  const std::uint32_t *pi = h.i.data(), *pj = h.j.data();
  const std::size_t pairs = h.i.size();
  // The closest pair over its own spacing as one vector loop, then the
  // first pair at that distance for its particle.
  h.q2.resize(pairs);
  double* const q2 = h.q2.data();
  double q2_min = 1e300;
#pragma omp simd reduction(min : q2_min)
  for (std::size_t k = 0; k < pairs; ++k) {
    const double ddx = x[pi[k]] - x[pj[k]], ddy = y[pi[k]] - y[pj[k]];
    q2[k] = (ddx * ddx + ddy * ddy) / dx2[k];
    q2_min = std::min(q2_min, q2[k]);
  }
  Spacing s;
  for (std::size_t k = 0; k < pairs; ++k) {
    if (q2[k] == q2_min) {
      s.particle = static_cast<long>(pi[k]);
      s.over_dx = std::sqrt(q2_min);
      break;
    }
  }
  return s;
}

double penetration_over_dx(const Simulation& sim) {
  if (sim.bodies.size() < 2) return 0.0;
  // Graded particles: against the finest spacing (where the bodies touch).
  double dx = sim.discretization.dx;
  for (double s : sim.particles.spacing) dx = std::min(dx, s);
  if (sim.contact.model != ContactModel::Kernel) return sim.contact_state.max_penetration / dx;
  // Kernel coupling has no contact law: overlap is measured against the
  // lattice spacing, the distance of two touching particles.
  const Particles& p = sim.particles;
  const NeighbourList& nl = sim.neighbours;
  if (nl.rows.size() < p.n + 1) return 0.0;
  double worst = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    for (std::uint32_t k = nl.rows[i]; k < nl.rows[i + 1]; ++k) {
      const std::size_t j = nl.j[k];
      if (p.body[j] == p.body[i]) continue;
      const double r = std::hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]);
      worst = std::max(worst, (dx - r) / dx);
    }
  }
  return worst;
}

double zigzag_indicator(const Simulation& sim) {
  HealthPairs pairs;
  return zigzag_indicator(sim, pairs);
}

double zigzag_indicator(const Simulation& sim, HealthPairs& h) {
  refresh(sim, h);
  const Particles& p = sim.particles;
  // The in-plane stress tensor, component by component: signed fields stay
  // smooth through a neutral axis, where von Mises has a kink.
  constexpr int kComponents = 3;
  h.s.resize(kComponents * p.n);
  h.sum.assign(kComponents * p.n, 0.0);
  double* const s = h.s.data();
  double* const sum = h.sum.data();
  for (std::size_t i = 0; i < p.n; ++i) {
    s[kComponents * i + 0] = p.sigma_xx(i);
    s[kComponents * i + 1] = p.sigma_yy(i);
    s[kComponents * i + 2] = p.sigma_xy(i);
  }
  // Nearest neighbours only (HealthPairs::near).
  for (const std::uint32_t k : h.near) {
    const std::size_t i = h.i[k], j = h.j[k];
    for (int c = 0; c < kComponents; ++c) {
      sum[kComponents * i + c] += s[kComponents * j + c];
      sum[kComponents * j + c] += s[kComponents * i + c];
    }
  }
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < p.n; ++i) {
    if (h.count[i] < 1.0) continue;
    for (int c = 0; c < kComponents; ++c) {
      const double v = s[kComponents * i + c];
      const double d = v - sum[kComponents * i + c] / h.count[i];
      num += d * d;
      den += v * v;
    }
  }
  return den > 0.0 ? std::sqrt(num / den) : 0.0;
}

void HealthMonitor::raise(const Simulation& sim, const std::string& detector, double value,
                          double limit, bool stop, long particle, const std::string& what) {
  if (!stop && std::find(warned_.begin(), warned_.end(), detector) != warned_.end()) return;
  HealthEvent e;
  e.detector = detector;
  e.level = stop ? "stop" : "warning";
  e.step = sim.step;
  e.time_s = sim.time;
  e.value = value;
  e.limit = limit;
  e.particle = particle;
  std::ostringstream msg;
  msg.precision(3);
  // A stop reads like the divergence guard's message (step, time, particle,
  // quantity = value), so whoever parses one understands the other.
  if (stop) {
    msg << "diverged at step " << sim.step << " (t = " << sim.time
        << " s): health check stopped the run (" << detector << " = " << value << ", limit "
        << limit << "): " << what;
  } else {
    msg << "health warning at step " << sim.step << " (t = " << sim.time << " s): " << what;
  }
  e.message = msg.str();
  events_.push_back(e);
  if (!stop) {
    warned_.push_back(detector);
    return;
  }
  stopped_ = true;
  throw HealthError(e);
}

void HealthMonitor::check(const Simulation& sim, bool full) {
  check(sim, energy(sim), full);
}

void HealthMonitor::check(const Simulation& sim, const EnergyState& e, bool full) {
  const double mech = e.kinetic + e.elastic + e.contact;
  if (!started_) {
    e0_ = e.total();
    started_ = true;
  }
  measures_.energy_scale = std::max(measures_.energy_scale, mech);
  const double growth =
      measures_.energy_scale > 0.0 ? (e.total() - e0_) / measures_.energy_scale : 0.0;
  measures_.energy_growth = std::max(measures_.energy_growth, growth);

  // The pair loops (spacing, zig-zag) only on a full check.
  const Spacing sp = full ? min_spacing(sim, pairs_) : Spacing{};
  if (full) measures_.min_spacing_over_dx = std::min(measures_.min_spacing_over_dx, sp.over_dx);
  const double pen = penetration_over_dx(sim);
  measures_.max_penetration_over_dx = std::max(measures_.max_penetration_over_dx, pen);
  const double zz = full ? zigzag_indicator(sim, pairs_) : 0.0;
  if (full) {
    measures_.zigzag = std::max(measures_.zigzag, zz);
    measures_.zigzag_final = zz;
  }

  const HealthLimits& L = limits_;
  const double wf = L.warn_fraction;
  std::ostringstream m;
  m.precision(3);
  // Energy: the balance should stay flat; growth means the scheme feeds the
  // motion (time step above the limit, artificial stress, stiff contact).
  if (growth > wf * L.energy_growth) {
    const bool stop = L.stop && growth > L.energy_growth;
    m.str("");
    m << "the energy balance grew by " << 100.0 * growth
      << " % of the largest mechanical energy (limit " << 100.0 * L.energy_growth
      << " %): the scheme is adding energy. Lower the time step (time.cfl), or switch off "
         "artificial stress / use the total-Lagrangian formulation"
      << (sim.method.artificial_stress.enabled() && growth < L.energy_growth
              ? " (artificial stress stores energy the balance does not count: a rise of "
                "~15 % is expected with it)"
              : "");
    // Where it shows: the fastest particle.
    const Particles& p = sim.particles;
    std::size_t fastest = 0;
    for (std::size_t i = 1; i < p.n; ++i) {
      if (p.vx[i] * p.vx[i] + p.vy[i] * p.vy[i] >
          p.vx[fastest] * p.vx[fastest] + p.vy[fastest] * p.vy[fastest]) {
        fastest = i;
      }
    }
    if (p.n > 0) {
      m << "; fastest particle " << fastest << " of body '" << sim.bodies[p.body[fastest]].name
        << "' at (" << p.x[fastest] << ", " << p.y[fastest] << ") m";
    }
    raise(sim, "energy_growth", growth, L.energy_growth, stop, p.n > 0 ? long(fastest) : -1,
          m.str());
  }
  // Disorder: lattice neighbours closer than a fraction of the spacing.
  // Warn 60 % of the way from 1 dx down to the limit (0.7 dx for 0.5): the
  // Poisson contraction of a 10 % stretch stays above it.
  const double spacing_warn = 1.0 - 0.6 * (1.0 - L.min_spacing_over_dx);
  if (sp.particle >= 0 && sp.over_dx < spacing_warn) {
    const bool stop = L.stop && sp.over_dx < L.min_spacing_over_dx;
    m.str("");
    m << "particles of body '" << sim.bodies[sim.particles.body[sp.particle]].name
      << "' came within " << sp.over_dx << " dx of each other (particle " << sp.particle
      << ", limit " << L.min_spacing_over_dx << " dx): particle disorder"
      << (sim.method.formulation == Formulation::TotalLagrangian
              ? " (hourglass modes). Use hourglass control (method.hourglass)"
              : " (tensile instability or hourglass modes). Use the total-Lagrangian "
                "formulation, or artificial stress (method.artificial_stress) and hourglass "
                "control");
    raise(sim, "particle_disorder", sp.over_dx, L.min_spacing_over_dx, stop, sp.particle, m.str());
  }
  if (pen > wf * L.penetration_over_dx) {
    const bool stop = L.stop && pen > L.penetration_over_dx;
    m.str("");
    m << "bodies overlap by " << pen << " dx (limit " << L.penetration_over_dx
      << " dx): the contact is too soft for this impact, or the bodies pass through each "
         "other. Use a stiffer contact (method.contact.D) or a smaller spacing";
    raise(sim, "penetration", pen, L.penetration_over_dx, stop, -1, m.str());
  }
  if (zz > L.zigzag) {
    m.str("");
    m << "the stress field zig-zags from particle to particle (indicator " << zz
      << ", warning above " << L.zigzag
      << "): hourglass (zero-energy) modes. Use hourglass control (method.hourglass) or "
         "the gradient correction";
    raise(sim, "zigzag", zz, L.zigzag, false, -1, m.str());
  }
}

std::string HealthMonitor::status() const {
  if (stopped_) return "stopped";
  return events_.empty() ? "ok" : "warning";
}

nlohmann::json HealthMonitor::report() const {
  nlohmann::json r;
  r["status"] = status();
  r["limits"] = {{"on_failure", limits_.stop ? "stop" : "warn"},
                 {"energy_growth_max", limits_.energy_growth},
                 {"min_spacing_over_dx", limits_.min_spacing_over_dx},
                 {"penetration_max_over_dx", limits_.penetration_over_dx},
                 {"zigzag_warning", limits_.zigzag},
                 {"warn_fraction", limits_.warn_fraction}};
  const HealthMeasures& m = measures_;
  r["measures"] = {
      {"energy_growth", m.energy_growth},
      {"energy_scale_J_per_m", m.energy_scale},
      {"min_spacing_over_dx", m.min_spacing_over_dx < 1e299 ? m.min_spacing_over_dx : 0.0},
      {"max_penetration_over_dx", m.max_penetration_over_dx},
      {"zigzag_max", m.zigzag},
      {"zigzag_final", m.zigzag_final}};
  nlohmann::json ev = nlohmann::json::array();
  for (const HealthEvent& e : events_) {
    ev.push_back({{"detector", e.detector},
                  {"level", e.level},
                  {"step", e.step},
                  {"time_s", e.time_s},
                  {"value", e.value},
                  {"limit", e.limit},
                  {"particle", e.particle},
                  {"message", e.message}});
  }
  r["events"] = ev;
  return r;
}

std::vector<std::string> HealthMonitor::warnings() const {
  std::vector<std::string> w;
  for (const HealthEvent& e : events_) w.push_back(e.message);
  return w;
}

}  // namespace gearsph::diagnostics
