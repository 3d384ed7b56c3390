// gearsph study speed-sweep: one loaded rack_pinion job run at several
// speeds (solver/study/speed_sweep.hpp), each stopped once its steady mesh
// has lasted the periods asked for, beside the lumped model of the same
// pair; writes speed_sweep.json, each speed's run in runs/, and the curves
// (speed_sweep.png) with ISO 6336-1's resonance marked.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/gearsph/cli.hpp"
#include "solver/run/execute.hpp"
#include "solver/study/speed_sweep.hpp"
#ifdef GEARSPH_WITH_RENDER
#include "render/plot_image.hpp"
#endif

namespace gearsph::cli {

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// "0.2,0.4,1" as a JSON array; a word that is not a number stays a string,
// for the request's check to refuse at its pointer.
json parse_ratios(const std::string& text) {
  json out = json::array();
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      const double v = std::stod(item, &used);
      out.push_back(used == item.size() ? json(v) : json(item));
    } catch (const std::exception&) {
      out.push_back(item);
    }
  }
  return out;
}

#ifdef GEARSPH_WITH_RENDER
// One series from two report arrays, NaN for a speed without a value.
render::Series series(const std::string& name, const json& x, const json& y, double y_scale) {
  render::Series s;
  s.name = name;
  for (std::size_t k = 0; k < x.size() && k < y.size(); ++k) {
    s.x.push_back(x[k].get<double>());
    s.y.push_back(y[k].is_number() ? y_scale * y[k].get<double>() : std::nan(""));
  }
  return s;
}

void plot_png(const fs::path& path, const json& r, const char* y_key_sph, const char* y_key_sdof,
              const std::string& y_label, double y_scale) {
  render::Plot plot;
  plot.title = "Speed sweep: SPH and the lumped model (ISO 6336-1 n_E1 marked)";
  plot.x_label = "mesh frequency [Hz]";
  plot.y_label = y_label;
  const json& f = r.at("mesh_frequency_Hz");
  plot.series.push_back(series("SPH", f, r.at(y_key_sph), y_scale));
  plot.series.push_back(series("lumped model (up)", f, r.at(y_key_sdof), y_scale));
  if (std::string(y_key_sdof) == "K_v_sdof") {
    plot.series.push_back(series("lumped model (down)", f, r.at("K_v_sdof_down"), y_scale));
  }
  double lo = 1e300, hi = -1e300;
  for (const render::Series& s : plot.series) {
    for (double v : s.y) {
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
  }
  if (r.at("resonance_Hz_iso").is_number() && hi > lo) {
    const double x = r.at("resonance_Hz_iso").get<double>();
    plot.series.push_back({"ISO 6336-1 resonance (n_E1)", {x, x}, {lo, hi}, render::Rgb8{0, 0, 0}});
  }
  render::write_png(path, render::render_plot_png(plot));
}
#endif

}  // namespace

int cmd_speed_sweep(Args& args) {
  const std::string out = args.option("out").value_or("speed_sweep");
  const auto ratios_text = args.option("ratios");
  const int threads = args.integer("threads", 0);
  const int steady_periods = args.integer("steady-periods", 20);
  const bool lumped_only = args.flag("lumped-only");
  const auto zeta_text = args.option("damping-ratio");
  const std::string stiffness = args.option("stiffness").value_or("iso");
  const int stiffness_positions =
      args.integer("stiffness-positions", study::kDefaultCyclePositions);
  study::SweepLimits limits;
  if (const auto v = args.option("max-particle-steps")) limits.max_particle_steps = std::stod(*v);
  const std::vector<std::string> rest = args.positional();
  if (rest.size() != 2 || rest[0] != "speed-sweep") {
    throw std::invalid_argument(
        "usage: gearsph study speed-sweep JOB.json --out DIR [--ratios 0.2,0.4,...] "
        "[--steady-periods N] [--threads N] [--max-particle-steps N] [--lumped-only] "
        "[--damping-ratio Z] [--stiffness measured|iso|TABLE.json] [--stiffness-positions N]");
  }
  json request = {
      {"ratios", ratios_text ? parse_ratios(*ratios_text) : json(study::default_sweep_ratios())},
      {"steady_periods", steady_periods},
      // A file: a table given (a measured cycle's stiffness_cycle.json).
      {"stiffness", stiffness == "iso" || stiffness == "measured"
                        ? json(stiffness)
                        : json::parse(read_file(stiffness), nullptr, false)},
      {"stiffness_positions", stiffness_positions}};
  study::SpeedSweepPlan plan;
  try {
    request["job"] = parse_job_text(read_file(rest[1]));
    const study::SpeedSweepRequest req = study::read_speed_sweep(request);
    std::optional<study::MeshStiffnessCycle> cycle;
    if (req.stiffness == "measured") {
      std::printf("mesh stiffness: %d quasi-static checks over one mesh cycle\n",
                  req.stiffness_positions);
      std::fflush(stdout);
      cycle = study::mesh_stiffness_cycle(req.job, req.stiffness_positions, threads);
      // Kept on its own: the checks are worth having if the plan is refused.
      fs::create_directories(out);
      write_file_atomic(fs::path(out) / "stiffness_cycle.json",
                        study::describe_stiffness_cycle(*cycle).dump(2) + "\n");
    }
    plan = study::plan_speed_sweep(req, limits, 30.0, cycle ? &*cycle : nullptr, threads);
  } catch (const InvalidJob& e) {
    std::fprintf(stderr, "gearsph study speed-sweep: refused before any run:\n");
    for (const JobIssue& i : e.issues) {
      std::fprintf(stderr, "  %s: %s\n", i.pointer.empty() ? "(document)" : i.pointer.c_str(),
                   i.message.c_str());
    }
    return 2;
  }
  fs::create_directories(fs::path(out) / "runs");
  std::printf(
      "lumped model (%s stiffness, mean %.4g N/m): natural frequency %.1f Hz; ISO 6336-1 "
      "resonance %.1f Hz\n",
      plan.stiffness_from.c_str(), plan.stiffness.mean(), plan.natural_frequency_Hz,
      plan.iso_resonance_Hz);
  if (plan.stiffness_cycle.is_object()) {
    std::printf("  measured in %.1f s wall:", plan.stiffness_cycle.at("wall_s").get<double>());
    for (std::size_t k = 0; k < plan.stiffness.position.size(); ++k) {
      std::printf(" s=%.4g: %.4g N/m;", plan.stiffness.position[k], plan.stiffness.value[k]);
    }
    std::printf("\n");
  }
  std::vector<json> summaries(plan.jobs.size());
  const auto start = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < plan.jobs.size() && !lumped_only; ++k) {
    const fs::path dir = fs::path(out) / "runs" / ("speed_" + std::to_string(k));
    PreparedJob job = prepare_job(plan.jobs[k], threads);
    ExecuteOptions opt;
    opt.threads = threads;
    const Execution ex = execute_prepared(job, dir, opt);
    summaries[k] = json::parse(read_file((dir / "summary.json").string()));
    const json& d = summaries[k]["analysis"].value("dynamics", json::object());
    std::printf("ratio %.3g: f_mesh %.1f Hz, K_v %.4g, steady %s, %.3g s simulated, %.0f s wall\n",
                plan.request.ratios[k], plan.mesh_frequency_Hz[k], d.value("K_v", 0.0),
                d.value("steady", false) ? "yes" : "no",
                ex.run.history.rows() ? job.scene.sim.time : 0.0, ex.run.wall_s);
    std::fflush(stdout);
  }
  const double fallback = zeta_text ? std::stod(*zeta_text) : 0.05;
  json report = study::sweep_report(plan, summaries, fallback);
  report["wall_s_total"] =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report["jobs"] = plan.jobs.size();
  write_file_atomic(fs::path(out) / "speed_sweep.json", report.dump(2) + "\n");
#ifdef GEARSPH_WITH_RENDER
  plot_png(fs::path(out) / "speed_sweep.png", report, "K_v_sph", "K_v_sdof", "K_v = peak / mean",
           1.0);
  plot_png(fs::path(out) / "speed_sweep_dte.png", report, "dte_pp_m_sph", "dte_pp_m_sdof",
           "DTE peak to peak [um]", 1e6);
#endif
  std::printf("resonance: SPH %s Hz, lumped %s Hz, ISO %s Hz; results in %s/\n",
              report["resonance_Hz_sph"].dump().c_str(), report["resonance_Hz_sdof"].dump().c_str(),
              report["resonance_Hz_iso"].dump().c_str(), out.c_str());
  return 0;
}

}  // namespace gearsph::cli
