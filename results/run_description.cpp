#include "results/run_description.hpp"

#include <chrono>
#include <ctime>

#include "results/history_store.hpp"
#include "results/results_layout.hpp"

namespace gearsph::results {

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&now, &tm);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &tm);
  return text;
}

void write_meta(hid_t file, const PreparedJob& job) {
  h5::Id meta = h5::create_group(file, "meta");
  const hid_t m = meta.get();
  h5::write_attribute(m, "format", std::string(kFormatName));
  h5::write_attribute(m, "format_version", std::int64_t{kFormatVersion});
  h5::write_attribute(m, "solver_version", std::string(kSolverVersion));
  h5::write_attribute(m, "job", job.job.dump());
  h5::write_attribute(m, "created", utc_now());
  h5::write_attribute(m, "particles", static_cast<std::int64_t>(job.scene.sim.particles.n));
  h5::write_attribute(m, "frames_planned", job.frames);
  // Sized now so that the end of the run rewrites them in place.
  h5::write_attribute(m, "status", std::string(kStatusRunning), kStatusBytes);
  h5::write_attribute(m, "steps_done", std::int64_t{0});
}

nlohmann::json units_json(const std::vector<std::string>& history_datasets) {
  nlohmann::json u = {
      {"/bodies/E_Pa", "Pa"},          {"/bodies/nu", "1"},
      {"/bodies/rho_kg_m3", "kg/m^3"}, {"/bodies/particle_range", "1"},
      {"/initial/position", "m"},      {"/initial/mass", "kg/m (per metre of thickness)"},
      {"/initial/body_id", "1"},       {"/initial/particle_id", "1"},
      {"/frames/time", "s"},           {"/frames/step", "1"},
  };
  for (const FieldSpec& f : kFrameFields) u[std::string("/frames/") + f.name] = f.unit;
  for (const std::string& h : history_datasets) {
    const std::string unit = HistoryStore::unit_of(h);
    u["/histories/" + h] = unit.empty() ? "1" : unit;
  }
  return u;
}

void write_units(hid_t file, const std::vector<std::string>& history_datasets) {
  h5::Id meta = h5::open_group(file, "meta");
  h5::write_attribute(meta.get(), "units", units_json(history_datasets).dump());
}

void write_status(hid_t file, const std::string& status, std::int64_t steps_done) {
  h5::Id meta = h5::open_group(file, "meta");
  h5::overwrite_attribute(meta.get(), "status", status);
  h5::overwrite_attribute(meta.get(), "steps_done", steps_done);
}

void write_bodies(hid_t file, const Simulation& sim) {
  h5::Id group = h5::create_group(file, "bodies");
  const std::size_t b = sim.bodies.size();
  std::vector<std::string> names;
  std::vector<std::int64_t> range;
  std::vector<double> E, nu, rho;
  for (const Body& body : sim.bodies) {
    names.push_back(body.name);
    range.push_back(static_cast<std::int64_t>(body.begin));
    range.push_back(static_cast<std::int64_t>(body.end));
    E.push_back(body.material.E);
    nu.push_back(body.material.nu);
    rho.push_back(body.material.rho0);
  }
  h5::write_text_dataset(group.get(), "name", names);
  h5::write_dataset(group.get(), "particle_range", range, {b, 2});
  h5::write_dataset(group.get(), "E_Pa", E, {b});
  h5::write_dataset(group.get(), "nu", nu, {b});
  h5::write_dataset(group.get(), "rho_kg_m3", rho, {b});
}

void write_initial(hid_t file, const Particles& p) {
  h5::Id group = h5::create_group(file, "initial");
  const std::size_t n = p.n;
  std::vector<double> xyz(3 * n);
  std::vector<std::int32_t> ids(n);
  for (std::size_t i = 0; i < n; ++i) {
    xyz[3 * i] = p.x0[i];
    xyz[3 * i + 1] = p.y0[i];
    ids[i] = static_cast<std::int32_t>(i);  // particles are never reordered
  }
  const std::vector<std::int32_t> body(p.body.begin(), p.body.end());
  h5::write_dataset(group.get(), "position", xyz, {n, 3}, true);
  h5::write_dataset(group.get(), "body_id", body, {n}, true);
  h5::write_dataset(group.get(), "particle_id", ids, {n}, true);
  h5::write_dataset(group.get(), "mass", p.mass, {n}, true);
}

}  // namespace gearsph::results
