#pragma once
// The FE check of a quasi-static rack_pinion job (`gearsph fe`, and a run's
// `"fe_check": true`): the loaded tooth solved at two (or more) fillet
// element sizes, the finest as the reference, the fillet numbers with the
// SPH static check's names, ISO 6336-3's sigma_F0 beside them, and the
// files a reviewer opens:
//   fe_summary.json          the numbers, per mesh and for the reference
//   fe_fillet_curves.csv     stress along both fillets against arc length,
//   fe_fillet_curves.json    per mesh
//   fe_fillet_curves.png     the same as a plot
//   fe_von_mises.png, fe_max_principal.png      the reference mesh's field
//   fe_*_tooth0.png, fe_mesh_tooth0.png         tooth 0 and its root, closer
// (images only in a build with the renderer).
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "fe/gear_fe_job.hpp"

namespace gearsph::fe {

struct FeCheckOptions {
  std::vector<double> fillet_sizes_m;  // empty: default_fillet_sizes (coarse to fine)
  int threads = 1;                     // for CalculiX
  double timeout_s = 300.0;            // each run of gmsh or ccx
  bool images = true;
  // Keep the model files (.geo, .msh, .inp, .frd, logs) in out_dir/fe_model/
  // instead of a temporary directory.
  bool keep_model_files = false;
  // The load of a finished SPH run (its measured tooth-0 force and load
  // radius) instead of the job's nominal load, and what to call it.
  std::optional<double> normal_force_N, load_radius_m;
  std::string load_source;
  // Where the model is held and which teeth it has (default: what the SPH
  // static check of the job models).
  std::optional<double> rim_depth_m;
  std::optional<std::pair<int, int>> teeth;  // first and last, tooth 0 loaded
  bool whole_gear = false;
  std::function<bool()> cancelled;              // checked between meshes
  std::function<void(const std::string&)> log;  // progress lines
  // The part of the check done (0-1): after each mesh, the files and images
  // at the end counted as one more mesh.
  std::function<void(double)> progress;
};

// The options that make the FE check solve what a finished SPH static check
// solved (its summary.json): its measured tooth-0 force and load radius,
// its modelled teeth and the radius its hub ring holds. `source` names the
// summary in words.
void model_the_sph_run(const nlohmann::json& sph_summary, const std::string& source,
                       FeCheckOptions& options);

// Solves, writes the files above into `out_dir` and returns fe_summary.json's
// content. Throws InvalidJob (a job it cannot model), FeUnavailable (no
// gmsh or ccx), FeFailed (a tool failed).
nlohmann::json run_fe_check(const nlohmann::json& job, const std::filesystem::path& out_dir,
                            const FeCheckOptions& options);

// The keys both the SPH static check and fe_summary.json give.
const std::vector<std::string>& fillet_keys();

// summary.json's fe_comparison block: for each fillet number, the SPH
// value (summary.analysis.static_check), the FE value and the relative
// error (sph - fe) / |fe|; SPH values that are missing are null and the
// block says so (status "sph_values_missing") rather than guess.
nlohmann::json fe_comparison(const nlohmann::json& sph_summary, const nlohmann::json& fe_summary);

// Makes every run of a job with "fe_check": true (gearsph run, the job
// service, its workers) run the FE check after the SPH run, write its files
// beside the run's and add fe_comparison to the summary. Once per process.
void register_fe_check();

}  // namespace gearsph::fe
