// gearsph validate --study accuracy: the static check against its FE check
// over pinions drawn from the space users work in (solver/validation/
// accuracy_map.hpp), and the distribution of the errors.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include "apps/gearsph/cli.hpp"
#include "fe/fe_check.hpp"
#include "solver/job/job.hpp"
#include "solver/run/execute.hpp"
#include "solver/validation/accuracy_map.hpp"
#ifdef GEARSPH_WITH_RENDER
#include "render/plot_image.hpp"
#endif

namespace gearsph::cli {

namespace {

// The quantities the map reports, as fe_comparison names them.
const char* const kQuantities[] = {"fillet_tension_peak_Pa", "fillet_compression_peak_Pa",
                                   "mesh_stiffness_N_per_mm_um"};

// Median, 95th percentile and worst of |error| (nearest rank), with the worst
// case's draw and its signed error.
nlohmann::json distribution(const nlohmann::json& rows, const std::string& quantity) {
  std::vector<std::pair<double, std::size_t>> e;
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const nlohmann::json& r = rows[k];
    if (r.contains("errors") && r["errors"].contains(quantity) &&
        r["errors"][quantity].is_number()) {
      e.emplace_back(std::abs(r["errors"][quantity].get<double>()), k);
    }
  }
  if (e.empty()) return nullptr;
  std::sort(e.begin(), e.end());
  auto rank = [&](double q) {  // nearest rank: the ceil(q n)-th smallest
    const auto r = static_cast<std::size_t>(std::ceil(q * static_cast<double>(e.size())));
    return e[std::clamp<std::size_t>(r, 1, e.size()) - 1].first;
  };
  const nlohmann::json& worst = rows[e.back().second];
  return {{"cases", e.size()},
          {"median_abs", rank(0.5)},
          {"p95_abs", rank(0.95)},
          {"worst_abs", e.back().first},
          {"worst_signed", worst["errors"][quantity]},
          {"worst_draw", worst["draw"]},
          {"worst_job", worst["job"]}};
}

#ifdef GEARSPH_WITH_RENDER
// The errors' cumulative distributions, one step line per quantity, with
// the 5 % target drawn either side: how many cases read within a given
// error is read off at a glance.
void write_distribution_plot(const nlohmann::json& rows, const std::filesystem::path& png) {
  render::Plot plot;
  plot.title = "accuracy map: static check against its FE check";
  plot.x_label = "error (SPH - FE) / FE [%]";
  plot.y_label = "fraction of cases with a smaller error";
  const char* const names[] = {"fillet tension peak", "fillet compression peak", "mesh stiffness"};
  double lo = -5.0, hi = 5.0;
  for (int q = 0; q < 3; ++q) {
    std::vector<double> e;
    for (const nlohmann::json& r : rows) {
      if (r.contains("errors") && r["errors"][kQuantities[q]].is_number()) {
        e.push_back(100.0 * r["errors"][kQuantities[q]].get<double>());
      }
    }
    if (e.empty()) continue;
    std::sort(e.begin(), e.end());
    render::Series s;
    s.name = names[q];
    const double n = static_cast<double>(e.size());
    for (std::size_t k = 0; k < e.size(); ++k) {
      s.x.insert(s.x.end(), {e[k], e[k]});
      s.y.insert(s.y.end(), {static_cast<double>(k) / n, static_cast<double>(k + 1) / n});
    }
    lo = std::min(lo, e.front());
    hi = std::max(hi, e.back());
    plot.series.push_back(std::move(s));
  }
  render::Series target;  // both lines, broken by a NaN
  target.name = "the 5 % target";
  const double gap = std::nan("");
  target.x = {-5.0, -5.0, gap, 5.0, 5.0};
  target.y = {0.0, 1.0, gap, 0.0, 1.0};
  target.colour = render::Rgb8{120, 120, 120};
  plot.series.push_back(std::move(target));
  plot.x_range = render::Range{std::floor(lo - 1.0), std::ceil(hi + 1.0)};
  plot.y_range = render::Range{0.0, 1.0};
  const std::vector<unsigned char> bytes = render::render_plot_png(plot);
  std::ofstream(png, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}
#endif

}  // namespace

int cmd_accuracy_map(Args& args) {
  const bool quick = args.flag("quick");
  const int count = std::max(1, args.integer("cases", quick ? 5 : 40));
  const std::string out = args.option("out").value_or("accuracy");
  const int threads = args.integer("threads", 0);
  // --fillet-tolerance T: also fail when a fillet tension peak is further
  // than T from FE (the suite's claim).
  std::optional<double> tolerance;
  if (const auto t = args.option("fillet-tolerance")) tolerance = std::stod(*t);
  // --replot: draw an earlier map's accuracy.json again, without running it.
  const auto replot = args.option("replot");
  args.positional();
  std::filesystem::create_directories(out);
  if (replot) {
    const nlohmann::json earlier = nlohmann::json::parse(read_file(*replot));
#ifdef GEARSPH_WITH_RENDER
    write_distribution_plot(earlier.at("cases"), std::filesystem::path(out) / "accuracy_map.png");
    std::printf("drew %s/accuracy_map.png from %s\n", out.c_str(), replot->c_str());
    return 0;
#else
    throw std::invalid_argument("--replot: this build has no render layer (GEARSPH_RENDER)");
#endif
  }

  std::vector<validation::SkippedDraw> skipped;
  const std::vector<validation::AccuracyCase> cases = validation::accuracy_cases(count, &skipped);
  fe::FeCheckOptions fe_options;
  fe_options.images = false;
  std::printf("%5s %4s %6s %5s %6s %5s %5s %6s | %8s %8s %8s | %7s %7s\n", "draw", "z", "m_mm",
              "alpha", "x", "rim_m", "N/mm", "point", "tension", "compr.", "c_mesh", "sph_s",
              "fe_s");
  nlohmann::json rows = nlohmann::json::array();
  int failed = 0;
  for (const validation::AccuracyCase& c : cases) {
    const std::filesystem::path dir =
        std::filesystem::path(out) / ("draw-" + std::to_string(c.draw));
    nlohmann::json row = {{"draw", c.draw},
                          {"teeth", c.teeth},
                          {"module_mm", c.module_mm},
                          {"pressure_angle_deg", c.pressure_angle_deg},
                          {"profile_shift", c.profile_shift},
                          {"rim_modules", c.rim_modules},
                          {"line_load_N_per_mm", c.line_load_N_per_mm},
                          {"contact_point", c.contact_point},
                          {"job", c.job}};
    try {
      ExecuteOptions eo;
      eo.threads = threads;
      const Execution sph = execute_job(c.job, dir / "sph", eo);
      row["sph_wall_s"] = sph.run.wall_s;
      row["particles"] = sph.run.summary.value("particles", 0);
      if (sph.run.status != "completed") throw std::runtime_error("SPH run " + sph.run.status);
      // Above one, the rack tooth is wedged (rack_pinion_analysis.cpp): not
      // the FE's single loaded flank.
      row["load_carried_by_tooth0"] =
          sph.run.summary["analysis"]["static_check"].value("load_carried_by_tooth0", 0.0);
      fe::FeCheckOptions o = fe_options;
      fe::model_the_sph_run(sph.run.summary, (dir / "sph" / "summary.json").string(), o);
      const auto t0 = std::chrono::steady_clock::now();
      const nlohmann::json fe_summary = fe::run_fe_check(validate_job(c.job), dir / "fe", o);
      row["fe_wall_s"] =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const nlohmann::json cmp = fe::fe_comparison(sph.run.summary, fe_summary);
      row["errors"] = nlohmann::json::object();
      for (const char* q : kQuantities) {
        row["errors"][q] =
            cmp.contains(q) && cmp[q].contains("error") ? cmp[q]["error"] : nlohmann::json();
      }
      if (cmp.contains("structure")) row["structure"] = cmp["structure"];
    } catch (const std::exception& e) {
      row["failed"] = e.what();
      ++failed;
    }
    auto pct = [&](const char* q) {
      return row.contains("errors") && row["errors"][q].is_number()
                 ? 100.0 * row["errors"][q].get<double>()
                 : std::nan("");
    };
    std::printf(
        "%5d %4d %6.2f %5.1f %+6.2f %5.1f %5.0f %6s | %+7.2f%% %+7.2f%% %+7.2f%% | %7.1f %7.1f%s\n",
        c.draw, c.teeth, c.module_mm, c.pressure_angle_deg, c.profile_shift, c.rim_modules,
        c.line_load_N_per_mm, c.contact_point.c_str(), pct("fillet_tension_peak_Pa"),
        pct("fillet_compression_peak_Pa"), pct("mesh_stiffness_N_per_mm_um"),
        row.value("sph_wall_s", 0.0), row.value("fe_wall_s", 0.0),
        row.contains("failed") ? ("  failed: " + row["failed"].get<std::string>()).c_str() : "");
    std::fflush(stdout);
    rows.push_back(row);
  }
  nlohmann::json report = {
      {"space",
       {{"teeth", {8, 60}},
        {"module_mm", {1, 10}},
        {"pressure_angle_deg", {14.5, 25}},
        {"profile_shift", {-0.5, 0.8}},
        {"rim_modules_below_root", {0.5, 3}},
        {"line_load_N_per_mm", {50, 500}},
        {"contact_points", {"pitch", "hpstc", "tip"}},
        {"min_tip_thickness_modules", validation::kMinTipThickness},
        {"draws", "Halton sequence, bases 2, 3, 5, 7, 11, 13; backlash 0 (the FE's geometry)"}}},
      {"errors_are", "(SPH - FE) / |FE|, FE the finest mesh of gearsph fe --compare"},
      {"cases", rows},
      {"skipped_draws", nlohmann::json::array()},
      {"failed_cases", failed}};
  for (const validation::SkippedDraw& s : skipped) {
    report["skipped_draws"].push_back({{"draw", s.draw}, {"reason", s.reason}});
  }
  for (const char* q : kQuantities) report["distribution"][q] = distribution(rows, q);
  write_file_atomic(std::filesystem::path(out) / "accuracy.json", report.dump(2) + "\n");
#ifdef GEARSPH_WITH_RENDER
  write_distribution_plot(rows, std::filesystem::path(out) / "accuracy_map.png");
#endif
  for (const char* q : kQuantities) {
    const nlohmann::json& d = report["distribution"][q];
    if (d.is_null()) continue;
    std::printf("%-28s median %.2f %%, 95th percentile %.2f %%, worst %+.2f %% (draw %d) of %zu\n",
                q, 100.0 * d["median_abs"].get<double>(), 100.0 * d["p95_abs"].get<double>(),
                100.0 * d["worst_signed"].get<double>(), d["worst_draw"].get<int>(),
                d["cases"].get<std::size_t>());
  }
  int beyond = 0;
  if (tolerance) {
    for (const nlohmann::json& r : rows) {
      if (r.contains("errors") && r["errors"]["fillet_tension_peak_Pa"].is_number() &&
          std::abs(r["errors"]["fillet_tension_peak_Pa"].get<double>()) > *tolerance) {
        std::printf("draw %d: the fillet tension peak is %+.2f %% from FE, beyond %.1f %%\n",
                    r["draw"].get<int>(),
                    100.0 * r["errors"]["fillet_tension_peak_Pa"].get<double>(),
                    100.0 * *tolerance);
        ++beyond;
      }
    }
  }
  std::printf("%zu case(s), %d failed to run, %zu draw(s) skipped; report in %s/accuracy.json\n",
              rows.size(), failed, skipped.size(), out.c_str());
  return failed == 0 && beyond == 0 ? 0 : 1;
}

}  // namespace gearsph::cli
