#include "solver/validation/cases.hpp"

#include <cmath>

namespace gearsph::validation {

namespace {

using nlohmann::json;

const char* const kKernels[] = {"seed_quartic", "cubic_spline", "quintic_spline", "wendland_c2"};

// |measured - reference| / reference from two analysis fields.
std::function<Measurement(const json&, double)> relative(const std::string& measured,
                                                         const std::string& reference) {
  return [=](const json& summary, double tol) {
    Measurement m;
    const json& a = summary.at("analysis");
    if (!a.contains(measured) || a.at(measured).is_null()) {
      m.note = "no measurement (" + summary.value("message", std::string("see summary")) + ")";
      return m;
    }
    m.measured = a.at(measured).get<double>();
    m.reference = a.at(reference).get<double>();
    m.error = (m.measured - m.reference) / m.reference;
    m.pass = std::abs(m.error) <= tol && summary.at("status") == "completed";
    return m;
  };
}

// measured / scale (scale 1 when not given) must stay below the tolerance.
std::function<Measurement(const json&, double)> bounded(const std::string& measured,
                                                        const std::string& scale) {
  return [=](const json& summary, double tol) {
    Measurement m;
    const json& a = summary.at("analysis");
    m.measured = a.at(measured).get<double>();
    m.reference = scale.empty() ? 1.0 : a.at(scale).get<double>();
    m.error = m.measured / m.reference;
    m.pass = m.error <= tol && summary.at("status") == "completed";
    return m;
  };
}

json plate_job(const std::string& kernel) {
  return {{"name", "plate-" + kernel},
          {"scene", {{"type", "plate"}, {"length_m", 0.2}, {"thickness_m", 0.02}, {"Vf", 0.01}}},
          {"discretization", {{"spacing_m", 0.002}, {"kernel", kernel}}}};
}

json strip_job(const std::string& kernel, const std::string& lateral, bool quick) {
  // Steel strip; the pulse is 4 % of the length, long against the thickness.
  const double length = quick ? 0.3 : 0.6;
  return {{"name", "strip-" + lateral + "-" + kernel},
          {"scene",
           {{"type", "strip_wave"},
            {"length_m", length},
            {"thickness_m", lateral == "free" ? 0.006 : 0.004},
            {"lateral", lateral}}},
          {"discretization", {{"spacing_m", quick ? 0.001 : 0.0005}, {"kernel", kernel}}}};
}

json disk_job(const std::string& kernel, bool driven, bool quick) {
  json scene = {
      {"type", "spinning_disk"}, {"radius_m", 0.02}, {"omega_rad_s", 2000.0}, {"driven", driven}};
  json job = {{"name", std::string("disk-") + (driven ? "driven-" : "free-") + kernel},
              {"scene", scene},
              {"discretization", {{"spacing_m", quick ? 0.002 : 0.001}, {"kernel", kernel}}}};
  if (driven) {
    // The rotated-stress check is about the Jaumann rate, i.e. the
    // updated-Lagrangian stress update (total Lagrangian has no stress rate).
    scene["initial_stress_Pa"] = {{"xx", 50e6}, {"yy", -20e6}, {"xy", 10e6}};
    job["scene"] = scene;
    job["method"] = {{"formulation", "updated_lagrangian"}};
  }
  return job;
}

}  // namespace

std::vector<Case> cases(bool quick) {
  std::vector<Case> out;
  for (const char* k : kKernels) {
    out.push_back({std::string("plate_period/") + k, "5", "period [s]",
                   "thin plate, omega^2 = E H^2 k^4 / (12 rho (1 - nu^2))", 0.05, plate_job(k),
                   relative("period_s", "reference_period_s")});
  }
  for (const char* lateral : {"confined", "free"}) {
    for (const char* k : kKernels) {
      const std::string lat = lateral;
      out.push_back(
          {"wave_speed_" + lat + "/" + k, "2", "wave speed [m/s]",
           lat == "confined" ? "c_p = sqrt((K + 4G/3)/rho)" : "c = sqrt(E / (rho (1 - nu^2)))",
           0.02, strip_job(k, lat, quick), relative("wave_speed_m_s", "reference_speed_m_s")});
    }
  }
  for (const char* k : kKernels) {
    // A free spinning disk: the von Mises stress stays at the centrifugal
    // level (steady 0.17, dynamic peak <= ~0.35 rho omega^2 R^2), far below
    // what any spurious strain rate would build (G omega t).
    out.push_back({std::string("disk_free/") + k, "4", "max von Mises / (rho omega^2 R^2)",
                   "centrifugal stress scale; steady centre value 0.171", 0.5,
                   disk_job(k, false, quick), bounded("max_von_mises_Pa", "centrifugal_scale_Pa"),
                   Case::Kind::Bound});
    out.push_back({std::string("disk_rotated_stress/") + k, "4",
                   "max |S - R S0 R^T| / |S0| over one revolution", "S(t) = R(wt) S0 R(wt)^T", 0.01,
                   disk_job(k, true, quick), bounded("max_stress_rotation_error", ""),
                   Case::Kind::Bound});
  }
  return out;
}

}  // namespace gearsph::validation
