// The size of a job from coarse probes (job_size.hpp). The count of
// particles filling a body at spacing k dx is, for a lattice or a graded
// body-fitted fill alike,
//   N(k) = a / k^2 + b / k,
// an area term and a term along the outline (a lattice's rounding there,
// or the graded layer at a feature, whose width grows with k while its
// spacing does: its count goes as 1/k). Two probes at k and 2k (or k and
// k sqrt 2) fix a and b; N(1) = a + b. The steps go as c0 + c1 / k: a fixed
// dt_s gives c1 = 0, the automatic step (proportional to the finest
// spacing) c0 = 0.
#include "solver/job/job_size.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "solver/core/setup_progress.hpp"
#include "solver/job/job.hpp"
#include "solver/scene/builders.hpp"

namespace gearsph {

namespace {

// The schema's largest spacing (discretization.spacing_m): coarser probes
// are refused by the check itself.
constexpr double kLargestSpacing_m = 1.0;
constexpr double kLargestFactor = 1 << 20;
// A coarse probe with fewer particles says little about the outline term:
// then the area term alone is extrapolated from the finer one.
constexpr double kFewestForFit = 30.0;

struct Spacings {
  double dx = 0.0, fine = 0.0, contact = 0.0;  // [m], 0 where the job gives none
};

double spacing_of(const nlohmann::json& d, const std::string& name) {
  if (d.contains(name + "_m")) return d.at(name + "_m").get<double>();
  if (d.contains(name + "_mm")) return 1e-3 * d.at(name + "_mm").get<double>();
  return 0.0;
}

Spacings spacings_of(const nlohmann::json& job) {
  const nlohmann::json& d = job.at("discretization");
  return {spacing_of(d, "spacing"), spacing_of(d, "fine_spacing"),
          spacing_of(d, "contact_spacing")};
}

// The job with every given spacing multiplied by k, in metres.
nlohmann::json coarsened(const nlohmann::json& job, const Spacings& s, double k) {
  nlohmann::json out = job;
  nlohmann::json& d = out["discretization"];
  auto set = [&](const std::string& name, double v) {
    d.erase(name + "_mm");
    d.erase(name + "_m");
    if (v > 0.0) d[name + "_m"] = v * k;
  };
  set("spacing", s.dx);
  set("fine_spacing", s.fine);
  set("contact_spacing", s.contact);
  return out;
}

struct Probe {
  double k = 1.0;
  double particles = 0.0;
  double steps = 0.0;
  double finest = 0.0;  // the finest particle spacing [m]
  double end_s = 0.0;
  bool body_fitted = false;
  std::shared_ptr<const PreparedJob> prepared;
};

Probe build_probe(const nlohmann::json& job, double k) {
  // One thread: a probe is small, and the caller's cores run jobs.
  auto p = std::make_shared<const PreparedJob>(prepare_job(job, 1));
  const auto& spacing = p->scene.sim.particles.spacing;
  Probe out;
  out.k = k;
  out.particles = double(p->scene.sim.particles.n);
  out.steps = double(p->steps);
  out.finest = spacing.empty() ? 0.0 : *std::min_element(spacing.begin(), spacing.end());
  out.end_s = p->end_s;
  for (const Body& b : p->scene.sim.bodies) out.body_fitted = out.body_fitted || b.fitted;
  out.prepared = std::move(p);
  return out;
}

// nullopt: the builders refuse the job this coarse (too few particles
// across a body, a spacing above the schema's largest).
std::optional<Probe> try_probe(const nlohmann::json& job, const Spacings& s, double k) {
  const scenes::CountOnlyScope count_only;
  try {
    return build_probe(coarsened(job, s, k), k);
  } catch (const InvalidJob&) {
    return std::nullopt;
  }
}

struct ProbePair {
  std::optional<Probe> coarse, fine;
};

// From the coarsest factor down, halving, to the first probe with half the
// aimed-at particles or more (a probe has about four times the one before
// it); its predecessor is the coarse probe. Short of it at k = 2, the last
// two probes.
ProbePair search(const nlohmann::json& job, const Spacings& s, double target,
                 double k_start = kLargestFactor) {
  double k = 1.0;
  while (k * 2.0 * s.dx <= kLargestSpacing_m && k < k_start) k *= 2.0;
  ProbePair out;
  for (; k >= 2.0; k /= 2.0) {
    std::optional<Probe> p = try_probe(job, s, k);
    if (!p) continue;
    if (out.fine) out.coarse = out.fine;
    out.fine = p;
    if (p->particles >= 0.5 * target) break;
  }
  return out;
}

double extrapolate(double ka, double na, double kb, double nb) {
  // na = a/ka^2 + b/ka, nb = a/kb^2 + b/kb.
  const double b = (na * ka * ka - nb * kb * kb) / (ka - kb);
  const double a = nb * kb * kb - b * kb;
  return a + b;
}

JobSize exact(const nlohmann::json& job) {
  const Probe p = build_probe(job, 1.0);
  JobSize out;
  out.particles = p.particles;
  out.steps = p.steps;
  out.end_s = p.end_s;
  out.exact = true;
  out.body_fitted = p.body_fitted;
  out.built = p.prepared;
  out.k_fine = 1.0;
  out.probe_particles_fine = p.particles;
  return out;
}

JobSize from_probes(const Probe& fine, const std::optional<Probe>& coarse) {
  JobSize out;
  out.end_s = fine.end_s;
  out.body_fitted = fine.body_fitted;
  out.k_fine = fine.k;
  out.probe_particles_fine = fine.particles;
  if (coarse && coarse->particles >= kFewestForFit) {
    out.k_coarse = coarse->k;
    out.probe_particles_coarse = coarse->particles;
    out.particles = extrapolate(coarse->k, coarse->particles, fine.k, fine.particles);
    // steps = c0 + c1 / k through both probes.
    const double c1 = (coarse->steps - fine.steps) / (1.0 / coarse->k - 1.0 / fine.k);
    const double c0 = fine.steps - c1 / fine.k;
    out.steps = c0 + c1;
  } else {
    out.particles = fine.particles * fine.k * fine.k;
    out.steps = fine.steps * fine.k;
  }
  // The job has at least the finer probe's particles and steps.
  out.particles = std::max(out.particles, fine.particles);
  out.steps = std::ceil(std::max(out.steps, fine.steps));
  out.particles = std::round(out.particles);
  return out;
}

}  // namespace

nlohmann::json JobSize::to_json() const {
  nlohmann::json j = {
      {"particles", particles}, {"steps", steps}, {"exact", exact}, {"body_fitted", body_fitted}};
  if (!exact) {
    j["basis"] = "extrapolated from coarser copies of the job";
    j["probes"] = nlohmann::json::array();
    if (k_coarse > 0) {
      j["probes"].push_back({{"spacing_factor", k_coarse}, {"particles", probe_particles_coarse}});
    }
    j["probes"].push_back({{"spacing_factor", k_fine}, {"particles", probe_particles_fine}});
  }
  return j;
}

JobSize estimate_job_size(const nlohmann::json& job, const JobSizeOptions& options) {
  Spacings s = spacings_of(job);
  // No spacing given: the scene chooses a modest one from its geometry.
  if (!(s.dx > 0.0)) return exact(job);
  // The coarsest copy the builders take, first: a graded scene left to
  // choose its fine spacing takes one from its geometry (at most the bulk
  // one), which a coarser copy does not scale; it is then given, as the job
  // would get it, before the search.
  const ProbePair first = search(job, s, 0.0);
  if (!first.fine) return exact(job);
  if (s.fine <= 0.0 && first.fine->finest < 0.99 * first.fine->k * s.dx) {
    s.fine = std::min(s.dx, first.fine->finest);
  }
  ProbePair pair = search(job, s, options.probe_particles, 2.0 * first.fine->k);
  if (!pair.fine) return exact(job);
  if (!pair.coarse && pair.fine->k > 2.0) {
    pair.coarse = try_probe(job, s, pair.fine->k * std::sqrt(2.0));
  }
  return from_probes(*pair.fine, pair.coarse);
}

// ---- stopping a set-up ------------------------------------------------------

struct SetupStop::Scope {
  SetupProgressScope progress;
};

SetupStop::SetupStop(std::chrono::steady_clock::time_point deadline, std::function<bool()> gone)
    : scope_(new Scope{SetupProgressScope(
          [deadline, gone = std::move(gone)](const SetupStatus& status) {
            if (std::chrono::steady_clock::now() > deadline) {
              throw SetupStopped("the set-up passed its deadline while " + status.stage);
            }
            if (gone && gone()) throw SetupStopped("the request was abandoned");
          },
          0.0)}) {}

SetupStop::~SetupStop() = default;

}  // namespace gearsph
