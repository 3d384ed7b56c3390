#include "fe/fe_check.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <mutex>
#include <numbers>
#include <sstream>

#include "fe/external_program.hpp"
#include "fe/rack_fe_model.hpp"
#include "solver/gear/gear_rating.hpp"
#include "solver/gear/iso6336_simulated.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"
#ifdef GEARSPH_FE_WITH_RENDER
#include "fe/fe_images.hpp"
#endif

namespace gearsph::fe {

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

std::string mm(double metres) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g mm", 1e3 * metres);
  return text;
}

nlohmann::json xy(Point p) {
  return nlohmann::json::array({p.x, p.y});
}

nlohmann::json mesh_json(const GearFeResult& r, double face_width_m) {
  const gear::FilletStress& s = r.stress;
  double vm_max = 0.0;
  for (const NodalStress& n : r.solution.stress) vm_max = std::max(vm_max, n.von_mises());
  const Point balance = r.reaction_N + r.load.applied_N;
  return {{"fillet_size_m", r.sizes.fillet},
          {"load_size_m", r.sizes.load},
          {"max_size_m", r.sizes.max},
          {"fillet_band_m", r.sizes.fillet_band},
          {"load_band_m", r.sizes.load_band},
          {"grow_to_m", r.sizes.grow_to},
          {"nodes", r.mesh.nodes.size()},
          {"elements", r.mesh.elements.size()},
          {"fillet_tension_peak_Pa", s.tension.stress_Pa},
          {"fillet_tension_peak_radius_m", s.tension.radius_m},
          {"fillet_tension_peak_arc_m", s.tension.arc_m},
          {"fillet_tension_peak_angle_deg", s.tension.angle_rad * kDeg},
          {"fillet_compression_peak_Pa", s.compression.stress_Pa},
          {"fillet_compression_peak_radius_m", s.compression.radius_m},
          {"fillet_compression_at_iso30_Pa", s.compression.at_iso30_Pa},
          {"fillet_stress_at_iso30_Pa", s.tension.at_iso30_Pa},
          {"max_von_mises_Pa", vm_max},
          {"load_displacement_m", r.load_displacement_m},
          // Per unit line load F_n / b [um mm/N]: the pinion's share of the
          // mesh compliance, comparable with the static check's
          // mesh_compliance (docs/gears.md).
          {"pinion_compliance_at_load_um_mm_per_N",
           1e9 * r.load_displacement_m / (geometry::norm(r.load.applied_N) / face_width_m)},
          // The same at the patch centre: the pinion's part of the bodies'
          // approach, which the pair's stiffness takes.
          {"pinion_compliance_at_centre_um_mm_per_N",
           1e9 * r.centre_displacement_m / (geometry::norm(r.load.applied_N) / face_width_m)},
          {"applied_force_N", xy(r.load.applied_N)},
          {"reaction_total_N", xy(r.reaction_N)},
          // |reaction + load| / |load|: the solve's equilibrium, ~1e-6 (the
          // results files carry six digits).
          {"reaction_imbalance", geometry::norm(balance) / geometry::norm(r.load.applied_N)},
          {"face_width_m", face_width_m},
          {"curve_to_mesh_distance_m", r.curve_to_mesh_m},
          {"mesh_s", r.mesh_s},
          {"solve_s", r.solve_s}};
}

std::string curves_csv(const std::vector<GearFeResult>& meshes) {
  std::ostringstream csv;
  csv.precision(10);
  csv << "fillet_size_m,arc_m,tension_radius_m,tension_sigma1_Pa,compression_radius_m,"
         "compression_sigma3_Pa,tangent_angle_deg\n";
  for (const GearFeResult& r : meshes) {
    const gear::FilletCurve& t = r.fillets.tension;
    const gear::FilletCurve& c = r.fillets.compression;
    for (std::size_t i = 0; i < t.size() && i < c.size(); ++i) {
      csv << r.sizes.fillet << ',' << t.arc[i] << ',' << t.radius[i] << ','
          << r.stress.tension_curve[i] << ',' << c.radius[i] << ',' << r.stress.compression_curve[i]
          << ',' << t.tangent_angle[i] * kDeg << '\n';
    }
  }
  return csv.str();
}

nlohmann::json curves_json(const std::vector<GearFeResult>& meshes) {
  nlohmann::json list = nlohmann::json::array();
  for (const GearFeResult& r : meshes) {
    const gear::FilletCurve& t = r.fillets.tension;
    nlohmann::json angle = nlohmann::json::array();
    for (double a : t.tangent_angle) angle.push_back(a * kDeg);
    const double arc30 = t.arc[t.i30] + t.f30 * (t.arc[t.i30 + 1] - t.arc[t.i30]);
    list.push_back({{"fillet_size_m", r.sizes.fillet},
                    {"arc_m", t.arc},
                    {"tension_radius_m", t.radius},
                    {"tension_sigma1_Pa", r.stress.tension_curve},
                    {"compression_radius_m", r.fillets.compression.radius},
                    {"compression_sigma3_Pa", r.stress.compression_curve},
                    {"tangent_angle_deg", angle},
                    {"iso30_arc_m", arc30}});
  }
  return {{"description",
           "stress along tooth 0's fillets from the space centre (arc 0) to the form circle: "
           "largest principal stress on the tension fillet, lowest on the compression fillet"},
          {"meshes", list}};
}

}  // namespace

const std::vector<std::string>& fillet_keys() {
  static const std::vector<std::string> keys = {
      "fillet_tension_peak_Pa", "fillet_tension_peak_radius_m", "fillet_compression_peak_Pa",
      "fillet_stress_at_iso30_Pa"};
  return keys;
}

namespace {

// The job's model with what the options change: an SPH run's load, another
// support, more teeth; and where its load comes from, in words.
struct CheckCase {
  GearFeJob job;
  std::string load_source, radius_source;
  bool whole = false;
};

CheckCase check_case(GearFeJob job, const FeCheckOptions& o,
                     const geometry::PinionGeometry& pinion) {
  CheckCase k{std::move(job), "the job's rack load per gear, F_n = load_N / cos(alpha)", "", false};
  GearFeCase& c = k.job.model;
  k.radius_source = "the job's contact_point (" + k.job.contact_point + ")";
  if (o.normal_force_N) {
    c.normal_force_N = *o.normal_force_N;
    k.load_source = o.load_source.empty() ? "given" : o.load_source;
  }
  if (o.load_radius_m) {
    c.load_radius_m = std::clamp(*o.load_radius_m, pinion.form_radius(), pinion.tip_radius());
    k.radius_source = o.load_source.empty() ? "given" : o.load_source;
  }
  if (o.rim_depth_m) {
    k.job.rim_depth_m = *o.rim_depth_m;
    c.fixed_radius_m = pinion.root_radius() - k.job.rim_depth_m;
  }
  if (o.teeth) {
    c.first_tooth = o.teeth->first;
    c.last_tooth = o.teeth->second;
  }
  if (o.whole_gear) c.whole_gear = true;
  k.whole = models_whole_gear(c);
  return k;
}

nlohmann::json model_json(const CheckCase& k, const geometry::PinionGeometry& pinion,
                          const FeTools& tools, double step) {
  const GearFeCase& c = k.job.model;
  return {
      {"frame", "gear frame of gear_profile.hpp: pinion centre at the origin, tooth 0 along -y"},
      {"teeth",
       k.whole ? nlohmann::json("all") : nlohmann::json::array({c.first_tooth, c.last_tooth})},
      {"held", k.whole ? "u = 0 on the bore r = fixed_radius_m"
                       : "u = 0 on the inner arc r = fixed_radius_m (where the SPH hub ring "
                         "begins); the radial cut sides are free"},
      {"fixed_radius_m", c.fixed_radius_m},
      {"rim_depth_m", k.job.rim_depth_m},
      {"root_radius_m", pinion.root_radius()},
      {"element", "CPE6: six-node plane-strain triangle (CalculiX), quadratic, unit thickness"},
      {"material", {{"E_Pa", c.E_Pa}, {"nu", c.nu}}},
      {"face_width_m", c.face_width_m},
      {"fillet_stress",
       "CalculiX's nodal stresses (extrapolated from the integration points, averaged between "
       "elements), interpolated along the fillet's boundary edges by their quadratic shape "
       "functions at the samples of gear/fillet.hpp's curves"},
      {"fillet_sample_step_m", step},
      {"mesher", "gmsh " + tools.gmsh.string()},
      {"solver", "CalculiX " + tools.ccx.string()}};
}

nlohmann::json load_json(const CheckCase& k, const GearLoadPatch& load, double ft) {
  const GearFeCase& c = k.job.model;
  return {{"normal_force_N", c.normal_force_N},
          {"tangential_force_N", ft},
          {"source", k.load_source},
          {"radius_source", k.radius_source},
          {"contact_point", k.job.contact_point},
          {"requested_radius_m", load.requested_radius_m},
          {"load_radius_m", load.radius_m},
          {"flank", c.flank_side < 0 ? "tooth 0's -x flank (clockwise pinion)"
                                     : "tooth 0's +x flank (counter-clockwise pinion)"},
          {"direction", xy(load.direction)},
          {"centre_m", xy(load.centre)},
          {"distribution",
           "Hertzian pressure p0 sqrt(1 - (d/a)^2) over the flank, line contact of the "
           "involute on the flat rack flank (Johnson 1985, 4.45), scaled to F_n exactly"},
          {"hertz_half_width_m", load.half_width_m},
          {"hertz_peak_pressure_Pa", load.peak_pressure_Pa},
          {"involute_curvature_radius_m", load.curvature_radius_m}};
}

// Every mesh against the reference (the finest), and the last two as the
// coarse-fine pair.
void add_convergence(const nlohmann::json& meshes, nlohmann::json& s) {
  const nlohmann::json& top = meshes.back();
  std::vector<std::string> keys = fillet_keys();
  for (const char* k :
       {"pinion_compliance_at_load_um_mm_per_N", "rack_compliance_um_mm_per_N",
        "pinion_compliance_at_centre_um_mm_per_N", "rack_compliance_at_centre_um_mm_per_N",
        "pair_mesh_stiffness_N_per_mm_um"}) {
    keys.push_back(k);
  }
  nlohmann::json convergence;
  nlohmann::json sizes = nlohmann::json::array();
  for (const nlohmann::json& m : meshes) sizes.push_back(m.at("fillet_size_m"));
  convergence["fillet_sizes_m"] = sizes;
  for (const std::string& key : keys) {
    nlohmann::json values = nlohmann::json::array(), diffs = nlohmann::json::array();
    const double ref_v = top.at(key).get<double>();
    for (const nlohmann::json& m : meshes) {
      values.push_back(m.at(key));
      diffs.push_back((m.at(key).get<double>() - ref_v) / std::abs(ref_v));
    }
    convergence[key] = {{"values", values}, {"relative_to_reference", diffs}};
  }
  s["convergence"] = convergence;
  if (meshes.size() < 2) return;
  const nlohmann::json& coarse = meshes[meshes.size() - 2];
  nlohmann::json diff;
  for (const std::string& key : keys) {
    const double fine = top.at(key).get<double>();
    diff[key] = {{"coarse", coarse.at(key)},
                 {"fine", fine},
                 {"relative_difference", (coarse.at(key).get<double>() - fine) / std::abs(fine)}};
  }
  s["coarse_fine_difference"] = diff;
}

}  // namespace

nlohmann::json run_fe_check(const nlohmann::json& job, const std::filesystem::path& out_dir,
                            const FeCheckOptions& o) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto log = [&o](const std::string& line) {
    if (o.log) o.log(line);
  };
  GearFeJob read = read_gear_fe_job(job);
  const geometry::PinionGeometry pinion(read.model.pinion);
  const CheckCase k = check_case(std::move(read), o, pinion);
  const GearFeCase& c = k.job.model;
  const FeTools tools = find_fe_tools();

  std::vector<double> sizes =
      o.fillet_sizes_m.empty() ? default_fillet_sizes(pinion) : o.fillet_sizes_m;
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  if (sizes.empty() || !(sizes.back() > 0.0)) {
    throw std::invalid_argument("fillet element sizes must be positive");
  }
  // Fillet samples at a quarter of the finest element: the quadratic
  // variation along an edge is resolved, and every mesh is read at the
  // same points.
  const double step = 0.25 * sizes.back();
  std::filesystem::create_directories(out_dir);
  std::optional<WorkDir> temp;
  std::filesystem::path work = out_dir / "fe_model";
  if (o.keep_model_files) {
    std::filesystem::create_directories(work);
  } else {
    temp.emplace("gearsph-fe-");
    work = temp->path();
  }
  std::vector<GearFeResult> results;
  std::vector<RackFeResult> racks;
  // A dismissed job or a stopping server stops the tool that runs, not
  // only the next mesh.
  const ProgramStopScope stop_tools(o.cancelled);
  for (double size : sizes) {
    if (o.cancelled && o.cancelled()) throw FeFailed("the FE check was cancelled");
    char name[48];
    std::snprintf(name, sizeof name, "tooth0_%.4gmm", 1e3 * size);
    log("meshing and solving with " + mm(size) + " elements at the fillets");
    results.push_back(solve_gear_fe(c, gear_mesh_sizes(pinion, size), step, tools, work, name,
                                    o.threads, o.timeout_s));
    const GearFeResult& r = results.back();
    // The rack's tooth under the same pressure, for the pair's stiffness.
    racks.push_back(solve_rack_fe(c, r.load, size, tools, work, std::string(name) + "_rack",
                                  o.threads, o.timeout_s));
    char line[200];
    std::snprintf(line, sizeof line,
                  "  %zu nodes, %zu elements: tension fillet peak %.2f MPa, at ISO's 30-degree "
                  "point %.2f MPa (gmsh %.1f s, ccx %.1f s)",
                  r.mesh.nodes.size(), r.mesh.elements.size(), 1e-6 * r.stress.tension.stress_Pa,
                  1e-6 * r.stress.tension.at_iso30_Pa, r.mesh_s, r.solve_s);
    log(line);
    if (o.progress) o.progress(double(results.size()) / double(sizes.size() + 1));
  }
  const GearFeResult& ref = results.back();

  // ISO 6336-3 method B at the FE load's radius: sigma_F0 = F_t / (b m) Y_F Y_S.
  const gear::IsoToothForm iso = gear::iso_tooth_form(pinion, ref.load.radius_m);
  const double ft = c.normal_force_N * std::cos(k.job.pressure_angle);
  const double sigma_F0 = ft / (c.face_width_m * k.job.module_m) * iso.Y_F * iso.Y_S;

  nlohmann::json s;
  s["job"] = k.job.name;
  s["model"] = model_json(k, pinion, tools, step);
  s["load"] = load_json(k, ref.load, ft);
  nlohmann::json meshes = nlohmann::json::array();
  for (std::size_t i = 0; i < results.size(); ++i) {
    nlohmann::json m = mesh_json(results[i], c.face_width_m);
    // um mm/N. The pair's stiffness in N/(mm um) is 1 / (pinion + rack) at
    // the patch centres: the bodies' approach, which a transmission error
    // measures (the work-conjugate means are less by a^2 / (8 R*) in all).
    const double rack = 1e9 * racks[i].compliance_m2_per_N;
    const double rack_centre = 1e9 * racks[i].centre_compliance_m2_per_N;
    m["rack_compliance_um_mm_per_N"] = rack;
    m["rack_compliance_at_centre_um_mm_per_N"] = rack_centre;
    m["rack_nodes"] = racks[i].mesh.nodes.size();
    m["pair_mesh_stiffness_N_per_mm_um"] =
        1.0 / (m.at("pinion_compliance_at_centre_um_mm_per_N").get<double>() + rack_centre);
    m["pair_mesh_stiffness_work_conjugate_N_per_mm_um"] =
        1.0 / (m.at("pinion_compliance_at_load_um_mm_per_N").get<double>() + rack);
    meshes.push_back(m);
  }
  s["meshes"] = meshes;
  // The reference's numbers at the top, with the SPH static check's names.
  const nlohmann::json& top = meshes.back();
  s["reference_mesh"] = results.size() - 1;
  s["reference_fillet_size_m"] = ref.sizes.fillet;
  for (const std::string& key : fillet_keys()) s[key] = top.at(key);
  for (const char* key :
       {"fillet_tension_peak_angle_deg", "nodes", "elements", "reaction_total_N", "applied_force_N",
        "pinion_compliance_at_load_um_mm_per_N", "rack_compliance_um_mm_per_N",
        "pinion_compliance_at_centre_um_mm_per_N", "rack_compliance_at_centre_um_mm_per_N",
        "pair_mesh_stiffness_N_per_mm_um", "pair_mesh_stiffness_work_conjugate_N_per_mm_um"}) {
    s[key] = top.at(key);
  }
  s["load_radius_m"] = ref.load.radius_m;
  s["tooth0_force_N"] = c.normal_force_N;
  // The colour scale of fe_max_principal_tooth0.png, for an SPH field to be
  // drawn on the same one.
  const std::array<double, 2> range = root_image_range_Pa(ref);
  s["image_range_Pa"] = {range[0], range[1]};
  add_convergence(meshes, s);
  s["iso_6336_3"] = {
      {"method", "ISO 6336-3:2006 method B, sigma_F0 = F_t / (b m_n) Y_F Y_S at the load radius"},
      {"load_radius_m", ref.load.radius_m},
      {"Y_F", iso.Y_F},
      {"Y_S", iso.Y_S},
      {"s_Fn_m", iso.s_Fn},
      {"rho_F_m", iso.rho_F},
      {"h_Fe_m", iso.h_Fe},
      {"sigma_F0_Pa", sigma_F0},
      {"fillet_tension_peak_over_sigma_F0", ref.stress.tension.stress_Pa / sigma_F0},
      {"fillet_stress_at_iso30_over_sigma_F0", ref.stress.tension.at_iso30_Pa / sigma_F0}};

  std::vector<std::string> files = {"fe_summary.json", "fe_fillet_curves.csv",
                                    "fe_fillet_curves.json"};
  write_file_atomic(out_dir / "fe_fillet_curves.csv", curves_csv(results));
  write_file_atomic(out_dir / "fe_fillet_curves.json", curves_json(results).dump(1) + "\n");
#ifdef GEARSPH_FE_WITH_RENDER
  if (o.images) {
    char title[160];
    std::snprintf(title, sizeof title, "F_n %.0f N at r = %.2f mm", c.normal_force_N,
                  1e3 * ref.load.radius_m);
    for (const std::string& f : write_fe_images(results, out_dir, title)) files.push_back(f);
  }
#endif
  s["files"] = files;
  s["wall_s"] = std::chrono::duration<double>(Clock::now() - start).count();
  write_file_atomic(out_dir / "fe_summary.json", s.dump(2) + "\n");
  return s;
}

namespace {

bool positive(const nlohmann::json& j, const char* key) {
  return j.contains(key) && j[key].is_number() && j[key].get<double>() > 0.0;
}

// What a finished SPH static check modelled (its summary's model block):
// the pinion's teeth, the radius its hub ring holds, the rack's teeth.
// Null where the summary does not say.
nlohmann::json sph_structure(const nlohmann::json& sph) {
  if (!sph.contains("model") || !sph["model"].contains("pinion")) return nullptr;
  const nlohmann::json& pm = sph["model"]["pinion"];
  nlohmann::json out = nlohmann::json::object();
  if (pm.contains("modelled_teeth") && pm["modelled_teeth"].is_array() &&
      !pm["modelled_teeth"].empty()) {
    out["pinion_teeth"] = pm["modelled_teeth"];
    if (pm.contains("teeth")) out["gear_teeth"] = pm["teeth"];
  }
  if (positive(pm, "deformable_from_radius_m")) {
    out["held_radius_m"] = pm["deformable_from_radius_m"];
  }
  if (positive(pm, "root_radius_m")) out["root_radius_m"] = pm["root_radius_m"];
  if (sph["model"].contains("rack")) {
    out["rack_teeth"] = sph["model"]["rack"].value("modelled_teeth", 0);
  }
  return out;
}

}  // namespace

void model_the_sph_run(const nlohmann::json& sph, const std::string& source, FeCheckOptions& o) {
  if (sph.contains("analysis") && sph["analysis"].contains("static_check")) {
    const nlohmann::json& sc = sph["analysis"]["static_check"];
    if (positive(sc, "tooth0_force_N")) o.normal_force_N = sc["tooth0_force_N"].get<double>();
    if (positive(sc, "load_radius_m")) o.load_radius_m = sc["load_radius_m"].get<double>();
    o.load_source =
        "the SPH run's tooth-0 normal force and load radius (" + source + " analysis.static_check)";
  }
  const nlohmann::json st = sph_structure(sph);
  if (st.is_null()) return;
  if (st.contains("pinion_teeth")) {
    const std::vector<int> teeth = st["pinion_teeth"].get<std::vector<int>>();
    if (st.contains("gear_teeth") &&
        static_cast<int>(teeth.size()) >= st["gear_teeth"].get<int>()) {
      o.whole_gear = true;
    } else {
      o.teeth = std::pair{teeth.front(), teeth.back()};
    }
  }
  if (st.contains("held_radius_m") && st.contains("root_radius_m")) {
    o.rim_depth_m = st["root_radius_m"].get<double>() - st["held_radius_m"].get<double>();
  }
}

namespace {

// What the FE model and the SPH run modelled, side by side, and whether
// they are the same structure: a comparison means something only then.
nlohmann::json structure_comparison(const nlohmann::json& fe, const nlohmann::json& sph) {
  if (!fe.contains("model")) {
    return {{"same", nullptr}, {"note", "the FE summary does not say what it modelled"}};
  }
  const nlohmann::json& m = fe.at("model");
  nlohmann::json fe_side = {{"pinion_teeth", m.at("teeth")},
                            {"held_radius_m", m.at("fixed_radius_m")},
                            {"rack_teeth", 1}};
  nlohmann::json block = {{"fe", fe_side}, {"sph", sph}};
  if (sph.is_null() || !sph.contains("pinion_teeth")) {
    block["same"] = nullptr;
    block["note"] = "the SPH run's summary does not say what it modelled";
    return block;
  }
  std::vector<std::string> differ;
  const std::vector<int> teeth = sph.at("pinion_teeth").get<std::vector<int>>();
  const bool sph_whole =
      sph.contains("gear_teeth") && static_cast<int>(teeth.size()) >= sph["gear_teeth"].get<int>();
  const nlohmann::json& ft = m.at("teeth");
  const bool same_teeth = ft.is_string() ? sph_whole
                                         : !sph_whole && ft[0].get<int>() == teeth.front() &&
                                               ft[1].get<int>() == teeth.back();
  if (!same_teeth) differ.push_back("pinion teeth");
  if (sph.contains("held_radius_m") &&
      std::abs(sph["held_radius_m"].get<double>() - m.at("fixed_radius_m").get<double>()) > 1e-9) {
    differ.push_back("held radius");
  }
  if (sph.value("rack_teeth", 1) != 1) differ.push_back("rack teeth");
  block["same"] = differ.empty();
  std::string list;
  for (const std::string& d : differ) list += (list.empty() ? "" : ", ") + d;
  block["note"] = differ.empty()
                      ? "both model the same pinion teeth on the same held rim, and one rack tooth"
                      : "the two models differ in: " + list +
                            " (the FE rack is always one tooth cut at the space centres)";
  return block;
}

}  // namespace

nlohmann::json fe_comparison(const nlohmann::json& sph_summary, const nlohmann::json& fe) {
  const nlohmann::json* check = nullptr;
  if (sph_summary.contains("analysis") && sph_summary["analysis"].contains("static_check")) {
    check = &sph_summary["analysis"]["static_check"];
  }
  nlohmann::json block;
  std::vector<std::string> missing;
  for (const std::string& key : fillet_keys()) {
    const double fe_v = fe.at(key).get<double>();
    nlohmann::json entry = {{"sph", nullptr}, {"fe", fe_v}, {"error", nullptr}};
    if (check && check->contains(key) && (*check)[key].is_number()) {
      const double sph = (*check)[key].get<double>();
      entry["sph"] = sph;
      entry["error"] = (sph - fe_v) / std::abs(fe_v);
    } else {
      missing.push_back(key);
    }
    block[key] = entry;
  }
  if (missing.empty()) {
    block["status"] = "compared";
    block["message"] =
        "error = (sph - fe) / |fe|, the FE solution at the finest fillet mesh as the reference";
  } else {
    std::string list;
    for (const std::string& k : missing) list += (list.empty() ? "" : ", ") + k;
    block["status"] = "sph_values_missing";
    block["message"] = "the SPH static check (summary analysis.static_check) does not give " +
                       list + "; only the FE values are shown";
  }
  block["structure"] = structure_comparison(fe, sph_structure(sph_summary));
  block["fe_summary"] = "fe_summary.json";
  block["fe_fillet_size_m"] = fe.at("reference_fillet_size_m");
  block["load"] = {{"normal_force_N", fe.at("load").at("normal_force_N")},
                   {"load_radius_m", fe.at("load").at("load_radius_m")},
                   {"source", fe.at("load").at("source")}};
  block["iso_sigma_F0_Pa"] = fe.at("iso_6336_3").at("sigma_F0_Pa");
  if (fe.contains("image_range_Pa")) block["image_range_Pa"] = fe.at("image_range_Pa");
  block["coarse_fine_difference"] = fe.value("coarse_fine_difference", nlohmann::json());
  // Each body's compliance beside the static check's split of the mesh
  // compliance: FE's include each body's side of the Hertz indentation,
  // which the SPH split counts in its contact part (docs/gears.md).
  if (fe.contains("pinion_compliance_at_load_um_mm_per_N")) {
    nlohmann::json entry = {
        {"fe_pinion_at_load", fe.at("pinion_compliance_at_load_um_mm_per_N")},
        {"note",
         "FE: each body's load displacement, its side of the Hertz indentation included "
         "(the pinion from its held radius, the rack from its mean); SPH: each body's smoothed "
         "contact point, and the contact part (the near field and spring of both bodies)"}};
    if (fe.contains("rack_compliance_um_mm_per_N")) {
      entry["fe_rack_at_load"] = fe.at("rack_compliance_um_mm_per_N");
    }
    // At the patch centres: the approach the pair's stiffness takes.
    for (const auto& [key, name] :
         {std::pair{"pinion_compliance_at_centre_um_mm_per_N", "fe_pinion_at_centre"},
          std::pair{"rack_compliance_at_centre_um_mm_per_N", "fe_rack_at_centre"}}) {
      if (fe.contains(key)) entry[name] = fe.at(key);
    }
    if (check && check->contains("mesh_compliance") && (*check)["mesh_compliance"].is_object()) {
      const nlohmann::json& mc = (*check)["mesh_compliance"];
      entry["sph_pinion"] = mc.value("pinion_um_mm_per_N", 0.0);
      entry["sph_contact"] = mc.value("contact_um_mm_per_N", 0.0);
      entry["sph_rack"] = mc.value("rack_um_mm_per_N", 0.0);
    }
    block["mesh_compliance_um_mm_per_N"] = entry;
  }
  // The pair's mesh stiffness: FE's pinion and rack in series at their
  // contact centres, each with its side of the Hertz indentation, against
  // the static check's.
  if (fe.contains("pair_mesh_stiffness_N_per_mm_um")) {
    const double fe_k = fe.at("pair_mesh_stiffness_N_per_mm_um").get<double>();
    nlohmann::json entry = {{"fe", fe_k}, {"sph", nullptr}, {"error", nullptr}};
    if (check && check->contains("mesh_stiffness_N_per_mm_um") &&
        (*check)["mesh_stiffness_N_per_mm_um"].is_number()) {
      const double sph = (*check)["mesh_stiffness_N_per_mm_um"].get<double>();
      entry["sph"] = sph;
      entry["error"] = (sph - fe_k) / fe_k;
    }
    block["mesh_stiffness_N_per_mm_um"] = entry;
  }
  // A rated static check (analysis.rating): the FE stresses rated under the
  // same factors, beside the simulation's safeties.
  if (sph_summary.contains("analysis") && sph_summary["analysis"].contains("rating") &&
      sph_summary["analysis"]["rating"].is_object() &&
      sph_summary["analysis"]["rating"].contains("iso6336")) {
    try {
      block["rating"] = gear::iso6336::rating_from_fe_check(sph_summary["analysis"]["rating"], fe);
    } catch (const std::exception& e) {
      block["rating"] = {{"status", "failed"}, {"message", e.what()}};
    }
  }
  return block;
}

namespace {

void add_fe_comparison(const PreparedJob& job, const RunResult& run,
                       const std::filesystem::path& dir, const ExecuteOptions& eo,
                       nlohmann::json& summary) {
  const nlohmann::json& scene = job.job.at("scene");
  if (scene.value("type", "") != "rack_pinion" || !scene.value("fe_check", false)) return;
  if (run.status != "completed") {
    summary["fe_comparison"] = {{"status", "not_run"},
                                {"message", "the SPH run did not complete (" + run.status + ")"}};
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [start] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  FeCheckOptions o;
  o.threads = std::max(1, job.scene.sim.threads);
  if (eo.observer) {
    o.cancelled = [obs = eo.observer] { return obs->cancelled(); };
    // The job service counts this stage in the job's progress, ETA and wall time.
    o.progress = [obs = eo.observer, &elapsed](double fraction) {
      obs->on_stage({"fe_check", fraction, elapsed()});
    };
    o.progress(0.0);
  }
  // The SPH run's own load on tooth 0 and its structure, so that both solve
  // the same problem.
  model_the_sph_run(summary, "summary", o);
  try {
    summary["fe_comparison"] = fe_comparison(summary, run_fe_check(job.job, dir, o));
    // The FE-based safeties also stand in the rating itself.
    if (summary["fe_comparison"].contains("rating") && summary.contains("analysis") &&
        summary["analysis"].contains("rating")) {
      summary["analysis"]["rating"]["fe_check"] = summary["fe_comparison"]["rating"];
    }
  } catch (const FeUnavailable& e) {
    summary["fe_comparison"] = {{"status", "unavailable"}, {"message", e.what()}};
  } catch (const InvalidJob& e) {
    summary["fe_comparison"] = {{"status", "failed"}, {"message", e.what()}};
  } catch (const std::exception& e) {
    summary["fe_comparison"] = {{"status", "failed"},
                                {"message", std::string("the FE check failed: ") + e.what()}};
  }
  summary["fe_comparison"]["wall_s"] = elapsed();
  if (o.progress) o.progress(1.0);
}

}  // namespace

void register_fe_check() {
  static std::once_flag once;
  std::call_once(once, [] { register_summary_addition(add_fe_comparison); });
}

}  // namespace gearsph::fe
