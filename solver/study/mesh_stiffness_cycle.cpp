#include "solver/study/mesh_stiffness_cycle.hpp"

#include <chrono>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"

namespace gearsph::study {

namespace {

using json = nlohmann::json;
namespace dyn = gear::dynamics;

// Five pinion teeth: tooth 0, its two neighbours (the tooth ahead shares the
// load in double contact) and one more each side, so that both loaded teeth
// keep the rim beside their fillets (a static check of tooth 0 alone models
// its two neighbours for the same reason: docs/gears.md).
constexpr int kCyclePinionTeeth = 5;
// Four rack teeth, offsets -2 .. 1 from the pitch point: tooth 0's driving
// flank meets offset -1 (clockwise) or 0 (counter-clockwise), the tooth
// ahead of it -2 or 1.
constexpr int kCycleRackTeeth = 4;
constexpr int kMaxCyclePositions = 64;

json static_check_of(const json& dynamic_job, double radius_m) {
  json job = dynamic_job;
  json& s = job["scene"];
  s["quasi_static"] = true;
  s["contact_point"] = 1e3 * radius_m;
  // At rest; a static check's sense of drive is the sign of omega, which a
  // counter-clockwise pinion keeps at a rate too small to turn it.
  const double omega = s["pinion"].value("omega_rad_s", 0.0);
  s["pinion"]["omega_rad_s"] = omega > 0.0 ? 1e-12 : 0.0;
  s["pinion"]["modelled_teeth"] = kCyclePinionTeeth;
  // The load acts against the rack's motion (its sign gives the side).
  s["rack"]["velocity_m_s"] = s["rack"].value("velocity_m_s", 0.0) > 0.0 ? 1e-12 : 0.0;
  s["rack"]["modelled_teeth"] = kCycleRackTeeth;
  // What moves with the bodies beyond the model changes no static deflection.
  s["rack"].erase("attached_mass_kg");
  s["pinion"].erase("attached_inertia_kg_m2");
  s["pinion"].erase("torque_N_m");
  // A static check's length is its relaxation's (scene default).
  if (job.contains("time")) job["time"].erase("end_s");
  job["output"]["frames"] = 0;
  if (job["output"].contains("history_points")) job["output"].erase("history_points");
  job["name"] = dynamic_job.value("name", std::string("job")) + "-stiffness-r" +
                std::to_string(1e3 * radius_m);
  return job;
}

}  // namespace

MeshCyclePlan plan_mesh_stiffness_cycle(const json& dynamic_job, int positions) {
  if (positions < 2 || positions > kMaxCyclePositions) {
    throw InvalidJob(std::vector<JobIssue>{
        {"/stiffness_positions", "the mesh cycle's stiffness needs from 2 to " +
                                     std::to_string(kMaxCyclePositions) + " positions; got " +
                                     std::to_string(positions)}});
  }
  const json& s = dynamic_job.at("scene");
  if (s.at("type") != "rack_pinion" || s.value("quasi_static", false) ||
      !(s.at("rack").value("load_N", 0.0) > 0.0)) {
    throw InvalidJob(
        std::vector<JobIssue>{{"/job/scene",
                               "the mesh cycle's stiffness is measured for a loaded dynamic "
                               "rack_pinion job (rack.load_N > 0, not quasi_static)"}});
  }
  MeshCyclePlan plan;
  plan.face_width_m = 1e-3 * s.at("pinion").at("face_width_mm").get<double>();
  // The pinion's circles and contact ratio from a static check's scene.
  json probe_job = static_check_of(dynamic_job, 0.0);
  probe_job["scene"]["contact_point"] = "pitch";
  const PreparedJob probe = prepare_job(probe_job, 1);
  const json& d = probe.scene.description;
  const double rb = d.at("pinion").at("base_radius_m").get<double>();
  const double ra = d.at("pinion").at("tip_radius_m").get<double>();
  const int z = s.at("pinion").at("teeth").get<int>();
  plan.contact_ratio = d.at("contact_ratio").get<double>();
  if (!(plan.contact_ratio > 1.0 && plan.contact_ratio < 2.0)) {
    throw InvalidJob(std::vector<JobIssue>{
        {"/job/scene/pinion",
         "the mesh cycle's stiffness is measured for a contact ratio between 1 and 2; this "
         "pair's is " +
             std::to_string(plan.contact_ratio)}});
  }
  plan.base_pitch_m = 2.0 * std::numbers::pi * rb / z;
  // The path of contact ends at the tip circle; it starts eps p_b before.
  const double g_end = std::sqrt(ra * ra - rb * rb);
  const double g_start = g_end - plan.contact_ratio * plan.base_pitch_m;
  for (int k = 0; k < positions; ++k) {
    const double sk = (k + 0.5) / positions;
    const double g = g_start + sk * plan.base_pitch_m;
    plan.position.push_back(sk);
    plan.radius_m.push_back(std::hypot(rb, g));
    plan.jobs.push_back(static_check_of(dynamic_job, plan.radius_m.back()));
  }
  return plan;
}

double static_check_stiffness_N_m(const json& summary, double face_width_m) {
  const json& a = summary.at("analysis");
  if (!a.contains("mesh_stiffness_N_per_mm_um")) {
    throw std::runtime_error("the static check read no mesh stiffness (no rack lag under load)");
  }
  // N/(mm um) per mm of face: times b [mm] gives N/um, times 1e6 N/m.
  return a.at("mesh_stiffness_N_per_mm_um").get<double>() * (1e3 * face_width_m) * 1e6;
}

dyn::MeshCycleTable mesh_cycle_table(const std::vector<double>& position,
                                     const std::vector<double>& stiffness) {
  if (position.size() != stiffness.size() || position.size() < 2) {
    throw std::invalid_argument(
        "a mesh cycle table needs at least two positions, one reading each");
  }
  for (std::size_t k = 0; k < position.size(); ++k) {
    if (!(position[k] >= 0.0 && position[k] < 1.0) || (k > 0 && !(position[k] > position[k - 1]))) {
      throw std::invalid_argument("mesh cycle positions must ascend within [0, 1)");
    }
    if (!(std::isfinite(stiffness[k]) && stiffness[k] > 0.0)) {
      throw std::invalid_argument("a mesh stiffness reading must be a finite positive number");
    }
  }
  dyn::MeshCycleTable t;
  t.position = position;
  t.value = stiffness;
  return t;
}

MeshCycleLevels mesh_cycle_levels(const dyn::MeshCycleTable& t, double contact_ratio) {
  MeshCycleLevels out;
  double sum_s = 0.0, sum_d = 0.0;
  int n_s = 0, n_d = 0;
  for (std::size_t k = 0; k < t.position.size(); ++k) {
    if (t.position[k] < contact_ratio - 1.0) {
      sum_d += t.value[k];
      ++n_d;
    } else {
      sum_s += t.value[k];
      ++n_s;
    }
  }
  out.single_pair_N_m = n_s ? sum_s / n_s : 0.0;
  out.double_pair_N_m = n_d ? sum_d / n_d : 0.0;
  out.mean_N_m = t.mean();
  return out;
}

MeshStiffnessCycle mesh_stiffness_cycle(const json& dynamic_job, int positions, int threads) {
  MeshStiffnessCycle out;
  const auto start = std::chrono::steady_clock::now();
  out.plan = plan_mesh_stiffness_cycle(dynamic_job, positions);
  std::vector<double> k;
  for (const json& job : out.plan.jobs) {
    PreparedJob prepared = prepare_job(job, threads);
    const RunResult r = run_job(prepared);
    if (r.status != "completed") {
      throw std::runtime_error("the static check " + job.value("name", std::string()) +
                               " did not complete: " + r.message);
    }
    out.particle_steps +=
        static_cast<double>(prepared.scene.sim.particles.n) * static_cast<double>(r.steps_done);
    k.push_back(static_check_stiffness_N_m(r.summary, out.plan.face_width_m));
    const json& sc = r.summary.at("analysis").value("static_check", json::object());
    out.tooth0_share.push_back(sc.value("load_carried_by_tooth0", std::nan("")));
  }
  out.table = mesh_cycle_table(out.plan.position, k);
  out.levels = mesh_cycle_levels(out.table, out.plan.contact_ratio);
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

json describe_stiffness_cycle(const MeshStiffnessCycle& c) {
  json share = json::array();
  for (double v : c.tooth0_share) share.push_back(std::isfinite(v) ? json(v) : json());
  return {{"position", c.table.position},
          {"stiffness_N_m", c.table.value},
          {"contact_radius_m", c.plan.radius_m},
          {"tooth0_load_share", share},
          {"position_definition",
           "fraction of a base pitch tooth 0's contact has moved along the path of contact from "
           "its start; two pairs in contact below contact_ratio - 1"},
          {"contact_ratio", c.plan.contact_ratio},
          {"double_contact_ends_at", c.plan.contact_ratio - 1.0},
          {"single_pair_mean_N_m", c.levels.single_pair_N_m},
          {"double_pair_mean_N_m", c.levels.double_pair_N_m},
          {"mean_N_m", c.levels.mean_N_m},
          {"wall_s", c.wall_s},
          {"particle_steps", c.particle_steps}};
}

}  // namespace gearsph::study
