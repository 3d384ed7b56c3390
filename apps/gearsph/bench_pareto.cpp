// The sweeps of `gearsph bench pareto` (its options: cmd_bench.cpp).
#include "apps/gearsph/bench_pareto.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "apps/gearsph/bench_measure.hpp"
#include "solver/job/job.hpp"
#include "solver/run/runner.hpp"
#ifdef GEARSPH_WITH_RENDER
#include "render/plot_image.hpp"
#include "render/png_io.hpp"
#endif

namespace gearsph::cli::bench {

namespace {

constexpr const char* kKernels[] = {"seed_quartic", "cubic_spline", "quintic_spline",
                                    "wendland_c2"};

struct Setting {
  std::string kernel;
  double h_over_dx = 0;  // 0: the kernel's default
  int across = 10;       // particles across the plate thickness (H/dx), or the Hertz a/dx
  double cfl = 0;        // 0: the default step (80 % of the measured limit)
  std::string formulation = "total_lagrangian";
  std::string label = {};  // as printed and charted
  double spacing_mm = 0;   // the gear sweep's spacing
};

// A sweep's settings and, for each, its cost (CPU time [s]), |error| (NaN
// when the run gave none) and CSV row.
struct Sweep {
  std::vector<Setting> set;
  std::vector<double> cost, err;
  std::vector<std::string> rows;
  explicit Sweep(std::vector<Setting> settings)
      : set(std::move(settings)), cost(set.size(), 0.0), err(set.size(), std::nan("")) {}
};

// Indices of the points no other point beats in both cost and error.
std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& err) {
  std::vector<bool> front(cost.size(), false);
  for (std::size_t i = 0; i < cost.size(); ++i) {
    if (!std::isfinite(err[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < cost.size() && !dominated; ++j) {
      if (j == i || !std::isfinite(err[j])) continue;
      dominated = cost[j] <= cost[i] && err[j] <= err[i] && (cost[j] < cost[i] || err[j] < err[i]);
    }
    front[i] = !dominated;
  }
  return front;
}

#ifdef GEARSPH_WITH_RENDER
// One marker series: the settings of a kernel and formulation, a cross for
// TL and a plus for UL, each marker `half` wide (log10 units) either side.
render::Series markers(const Sweep& s, const std::string& kernel, const std::string& form,
                       const std::array<double, 2>& half) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double dxm = half[0], dym = half[1];
  const bool tl = form == "total_lagrangian";
  render::Series m;
  m.name = kernel + (tl ? " TL (x)" : " UL (+)");
  for (std::size_t i = 0; i < s.set.size(); ++i) {
    if (s.set[i].kernel != kernel || s.set[i].formulation != form) continue;
    if (!std::isfinite(s.err[i]) || s.err[i] <= 0) continue;
    const double x = std::log10(s.cost[i]), y = std::log10(s.err[i]);
    if (tl) {
      m.x.insert(m.x.end(), {x - dxm, x + dxm, nan, x - dxm, x + dxm, nan});
      m.y.insert(m.y.end(), {y - dym, y + dym, nan, y + dym, y - dym, nan});
    } else {
      m.x.insert(m.x.end(), {x - dxm, x + dxm, nan, x, x, nan});
      m.y.insert(m.y.end(), {y, y, nan, y - dym, y + dym, nan});
    }
  }
  return m;
}

// The Pareto front as a staircase: each front point holds its error until
// the next, cheaper to more expensive.
render::Series front_staircase(const Sweep& s, const std::vector<bool>& front) {
  render::Series f;
  f.name = "Pareto front";
  f.colour = render::Rgb8{0, 0, 0};
  std::vector<std::pair<double, double>> pts;
  for (std::size_t i = 0; i < s.set.size(); ++i)
    if (front[i] && s.err[i] > 0) pts.emplace_back(std::log10(s.cost[i]), std::log10(s.err[i]));
  std::sort(pts.begin(), pts.end());
  for (std::size_t k = 0; k < pts.size(); ++k) {
    f.x.push_back(pts[k].first);
    f.y.push_back(pts[k].second);
    if (k + 1 < pts.size()) {
      f.x.push_back(pts[k + 1].first);
      f.y.push_back(pts[k].second);
    }
  }
  return f;
}

// Error against cost on log-log axes: one marker series per kernel and
// formulation, the Pareto front as a line. Nothing without a finite error.
void pareto_chart(const std::filesystem::path& path, const std::string& title,
                  const std::string& error_name, const Sweep& s, const std::vector<bool>& front) {
  render::Plot plot;
  plot.title = title;
  plot.x_label = "log10 CPU time [s]";
  plot.y_label = "log10 |" + error_name + "|";
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (std::size_t i = 0; i < s.set.size(); ++i) {
    if (!std::isfinite(s.err[i]) || s.err[i] <= 0) continue;
    x0 = std::min(x0, std::log10(s.cost[i]));
    x1 = std::max(x1, std::log10(s.cost[i]));
    y0 = std::min(y0, std::log10(s.err[i]));
    y1 = std::max(y1, std::log10(s.err[i]));
  }
  if (x0 > x1) return;
  const double mx = 0.08 * std::max(x1 - x0, 0.1), my = 0.08 * std::max(y1 - y0, 0.1);
  plot.x_range = render::Range{x0 - mx, x1 + mx};
  plot.y_range = render::Range{y0 - my, y1 + my};
  const std::array<double, 2> half = {0.25 * mx, 0.25 * my};  // marker half size
  for (const char* k : kKernels) {
    for (const char* form : {"total_lagrangian", "updated_lagrangian"}) {
      render::Series m = markers(s, k, form, half);
      if (!m.x.empty()) plot.series.push_back(std::move(m));
    }
  }
  plot.series.push_back(front_staircase(s, front));
  render::write_png(path, render::render_plot_png(plot));
}
#endif

// The rows of a sweep (into `csv`, whose header is written), its Pareto
// front (pareto_NAME_front.csv), the chart (pareto_NAME.png) and the front
// printed.
void report_sweep(const std::filesystem::path& out, const std::string& name,
                  [[maybe_unused]] const std::string& title, const std::string& error_name,
                  const Sweep& s, std::ofstream& csv) {
  const std::vector<bool> front = pareto_front(s.cost, s.err);
  std::ofstream fcsv(out / ("pareto_" + name + "_front.csv"));
  fcsv << "setting,cpu_s,abs_error\n";
  for (std::size_t i = 0; i < s.set.size(); ++i) {
    csv << s.rows[i] << '\n';
    if (front[i]) fcsv << s.set[i].label << ',' << s.cost[i] << ',' << s.err[i] << '\n';
  }
  csv.flush();
  const std::filesystem::path png = out / ("pareto_" + name + ".png");
#ifdef GEARSPH_WITH_RENDER
  pareto_chart(png, title, error_name, s, front);
  std::printf("chart: %s\n", png.c_str());
#else
  std::printf("(built without the renderer: no PNG chart)\n");
#endif
  std::printf("Pareto front, %s (cheapest first):\n", error_name.c_str());
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < s.set.size(); ++i)
    if (front[i]) idx.push_back(i);
  std::sort(idx.begin(), idx.end(), [&](auto a, auto b) { return s.cost[a] < s.cost[b]; });
  for (std::size_t i : idx)
    std::printf("  %-52s cpu %8.2f s  |error| %.3g%%\n", s.set[i].label.c_str(), s.cost[i],
                100 * s.err[i]);
}

// One run of a sweep: CPU time and the summary (empty when refused).
struct SweepRun {
  double cpu = 0, wall = 0, dt = 0;
  std::size_t particles = 0;
  std::int64_t steps = 0;
  std::string status;
  bool refused = false;
  json summary;
};

// "refused: WHY" as a CSV field: no commas or line breaks.
std::string refusal(const std::exception& e) {
  std::string status = std::string("refused: ") + e.what();
  for (char& c : status)
    if (c == ',' || c == '\n') c = ';';
  return status;
}

SweepRun run_for_sweep(const json& job, int threads) {
  SweepRun r;
  try {
    PreparedJob pj = prepare_job(job, threads);
    r.particles = pj.scene.sim.particles.n;
    r.dt = pj.scene.sim.dt;
    const double c0 = cpu_seconds();
    const RunResult rr = run_job(pj);
    r.cpu = cpu_seconds() - c0;
    r.wall = rr.wall_s;
    r.steps = rr.steps_done;
    r.status = rr.status;
    r.summary = rr.summary;
  } catch (const std::exception& e) {
    r.status = refusal(e);
    r.refused = true;
  }
  return r;
}

// A sweep's table line: the run and its error, or its status when it gave
// none.
void print_sweep_row(const std::string& label, const SweepRun& r, const std::string& error) {
  std::printf("%-52s %9zu %8lld %9.2f %9.2f %11s\n", label.c_str(), r.particles,
              static_cast<long long>(r.steps), r.wall, r.cpu, error.c_str());
  std::fflush(stdout);
}

// ------------------------------------------------------------ Hertz

// Hertz line contact (validation.md 6) at the half-width a over `a_over_dx`
// spacings.
json hertz_job(const std::string& kernel, double a_m, int a_over_dx) {
  return {{"name", "pareto-hertz"},
          {"scene",
           {{"type", "hertz"},
            {"cap_height_over_a", 6.0},
            {"block_half_width_over_a", 6.0},
            {"block_depth_over_a", 6.0}}},
          {"discretization", {{"spacing_m", a_m / a_over_dx}, {"kernel", kernel}}},
          {"output", {{"frames", 0}}}};
}

// Hertz line contact: peak-pressure error against cost, over kernel and a/dx
// (the contact half-width in spacings), TL.
void hertz_sweep(const std::filesystem::path& out, bool quick, int threads) {
  const double a = 4.8138e-4;  // the scene's half-width at its default load [m]
  const std::vector<int> across = quick ? std::vector<int>{3, 4} : std::vector<int>{3, 4, 6};
  std::vector<Setting> set;
  for (const char* k : kKernels)
    for (int n : across) {
      Setting s{k, 0, n, 0, "total_lagrangian"};
      s.label = std::string(k) + " a/dx=" + std::to_string(n);
      set.push_back(s);
    }
  Sweep sweep(std::move(set));
  std::ofstream csv(out / "pareto_hertz.csv");
  csv << "kernel,a_over_dx,particles,steps,wall_s,cpu_s,peak_pressure_Pa,reference_Pa,"
         "p0_error,half_width_error,status\n";
  std::printf("\n%-52s %9s %8s %9s %9s %11s\n", "Hertz setting", "particles", "steps", "wall_s",
              "cpu_s", "p0_err");
  for (std::size_t i = 0; i < sweep.set.size(); ++i) {
    const Setting& s = sweep.set[i];
    const SweepRun r = run_for_sweep(hertz_job(s.kernel, a, s.across), threads);
    double p0 = std::nan(""), ref = std::nan(""), aerr = std::nan("");
    if (r.summary.contains("analysis") && r.summary["analysis"].contains("peak_pressure_Pa")) {
      const json& an = r.summary.at("analysis");
      p0 = an.at("peak_pressure_Pa").get<double>();
      ref = an.at("reference_peak_pressure_Pa").get<double>();
      aerr =
          an.at("half_width_m").get<double>() / an.at("reference_half_width_m").get<double>() - 1;
      sweep.err[i] = std::abs(p0 / ref - 1.0);
    }
    sweep.cost[i] = r.cpu;
    print_sweep_row(s.label, r,
                    std::isfinite(sweep.err[i]) ? fmt("%+.2f%%", 100 * (p0 / ref - 1)) : r.status);
    std::ostringstream line;
    line << s.kernel << ',' << s.across << ',' << r.particles << ',' << r.steps << ',' << r.wall
         << ',' << r.cpu << ',' << p0 << ',' << ref << ',' << (p0 / ref - 1) << ',' << aerr << ','
         << r.status;
    sweep.rows.push_back(line.str());
  }
  report_sweep(out, "hertz", "Hertz line contact: peak-pressure error against CPU time", "p0 error",
               sweep, csv);
}

// ------------------------------------------------------------ gear

// The quasi-static gear (validation.md 7) under 1 kN at spacing dx_mm.
json static_gear_job(const std::string& kernel, double dx_mm) {
  return {{"name", "pareto-gear"},
          {"scene",
           {{"type", "rack_pinion"},
            {"quasi_static", true},
            {"pinion", {{"omega_rad_s", 0.0}}},
            {"rack", {{"velocity_m_s", 0.0}, {"load_N", 1000.0}}}}},
          {"discretization", {{"spacing_mm", dx_mm}, {"kernel", kernel}}},
          {"output", {{"frames", 0}}}};
}

// Tooth 0's nominal root bending stress [Pa]; NaN if the run gave none.
double root_bending_Pa(const SweepRun& r) {
  const json::json_pointer check("/analysis/static_check");
  return r.summary.contains(check)
             ? r.summary.at(check).at("nominal_bending_stress_Pa").get<double>()
             : std::nan("");
}

std::vector<Setting> gear_settings(bool quick) {
  const std::vector<double> spacings_mm =
      quick ? std::vector<double>{1.0} : std::vector<double>{1.0, 0.5};
  std::vector<Setting> set;
  for (const char* k : kKernels)
    for (double mm : spacings_mm) {
      Setting s{k, 0, 0, 0, "total_lagrangian"};
      s.label = std::string(k) + " dx=" + fmt("%.2g", mm) + " mm";
      s.spacing_mm = mm;
      set.push_back(s);
    }
  return set;
}

// The static gear: tooth 0's root bending stress against the finest run's,
// over kernel and spacing.
void gear_sweep(const std::filesystem::path& out, bool quick, int threads) {
  const double finest_mm = quick ? 0.5 : 0.25;
  std::printf("\nGear reference: seed_quartic at %.2g mm ...\n", finest_mm);
  std::fflush(stdout);
  const SweepRun finest = run_for_sweep(static_gear_job("seed_quartic", finest_mm), threads);
  const double reference = root_bending_Pa(finest);
  std::printf("  %.4g MPa (%zu particles, cpu %.1f s)\n", 1e-6 * reference, finest.particles,
              finest.cpu);
  Sweep sweep(gear_settings(quick));
  std::ofstream csv(out / "pareto_gear.csv");
  csv << "kernel,spacing_mm,particles,steps,wall_s,cpu_s,root_bending_Pa,reference_Pa,"
         "reference_spacing_mm,error,status\n";
  std::printf("%-52s %9s %8s %9s %9s %11s\n", "gear setting", "particles", "steps", "wall_s",
              "cpu_s", "root_err");
  for (std::size_t i = 0; i < sweep.set.size(); ++i) {
    const Setting& s = sweep.set[i];
    const SweepRun r = run_for_sweep(static_gear_job(s.kernel, s.spacing_mm), threads);
    const double sigma = root_bending_Pa(r);
    const double e = sigma / reference - 1.0;
    sweep.err[i] = std::abs(e);
    sweep.cost[i] = r.cpu;
    print_sweep_row(s.label, r, std::isfinite(e) ? fmt("%+.2f%%", 100 * e) : r.status);
    std::ostringstream line;
    line << s.kernel << ',' << s.spacing_mm << ',' << r.particles << ',' << r.steps << ',' << r.wall
         << ',' << r.cpu << ',' << sigma << ',' << reference << ',' << finest_mm << ',' << e << ','
         << r.status;
    sweep.rows.push_back(line.str());
  }
  report_sweep(out, "gear", "Static gear: root bending error (vs the finest run) against CPU time",
               "root bending error", sweep, csv);
}

// ------------------------------------------------------------ plate

std::string plate_label(const Setting& s) {
  std::string l = s.kernel + " H/dx=" + std::to_string(s.across);
  if (s.h_over_dx > 0) l += " h/dx=" + fmt("%.2g", s.h_over_dx);
  if (s.cfl > 0) l += " cfl=" + fmt("%.2g", s.cfl);
  l += s.formulation == "total_lagrangian" ? " TL" : " UL";
  return l;
}

std::vector<Setting> plate_settings(bool quick) {
  std::vector<Setting> set;
  // The kernel x spacing x formulation grid at default h/dx and step ...
  const std::vector<int> across = quick ? std::vector<int>{5, 10} : std::vector<int>{5, 10, 20};
  // UL costs ~10x TL per step (kernel sums on the moving configuration,
  // neighbour rebuilds): --quick runs it at the coarsest spacing only.
  for (const char* k : kKernels)
    for (int a : across)
      for (const char* f : {"total_lagrangian", "updated_lagrangian"})
        if (!(quick && a > across.front() && std::string(f) == "updated_lagrangian"))
          set.push_back({k, 0, a, 0, f});
  // ... and one factor at a time around H/dx = 10, TL: a wider and a
  // narrower kernel, a small and a large Courant number.
  for (const char* k : kKernels) {
    const bool support3 = std::string(k) == "seed_quartic" || std::string(k) == "quintic_spline";
    set.push_back({k, support3 ? 1.3 : 1.2, 10, 0, "total_lagrangian"});
    if (!quick) set.push_back({k, support3 ? 0.8 : 2.0, 10, 0, "total_lagrangian"});
  }
  for (const char* k : {"seed_quartic", "wendland_c2"}) {
    set.push_back({k, 0, 10, 0.1, "total_lagrangian"});
    set.push_back({k, 0, 10, 0.4, "total_lagrangian"});
  }
  for (Setting& s : set) s.label = plate_label(s);
  return set;
}

json plate_sweep_job(const Setting& s) {
  json job = plate_job(0.02 / s.across);
  job["discretization"]["kernel"] = s.kernel;
  if (s.h_over_dx > 0) job["discretization"]["h_over_dx"] = s.h_over_dx;
  job["method"] = {{"formulation", s.formulation}};
  // 1.7 reference periods: three zero crossings even with a 10 % long period.
  job["time"] = {{"end_s", 1.7 * 0.2540606}};
  if (s.cfl > 0) job["time"]["cfl"] = s.cfl;
  job["output"]["history_points"] = 2000;
  return job;
}

// A plate run and what its analysis measured (NaN: not measured; the decay
// stays 0 when the run was refused).
struct PlateRun {
  SweepRun run;
  double period = std::nan(""), period_error = std::nan(""), decay = 0;
};

PlateRun run_plate_setting(const Setting& s, int threads) {
  PlateRun p;
  p.run = run_for_sweep(plate_sweep_job(s), threads);
  if (p.run.refused) return p;
  try {
    const json& a = p.run.summary.at("analysis");
    if (a.value("period_s", json()).is_number()) {
      p.period = a.at("period_s").get<double>();
      p.period_error = a.at("period_error").get<double>();
    }
    const json d = a.value("amplitude_decay_2_periods", json());
    p.decay = d.is_number() ? d.get<double>() : std::nan("");
  } catch (const std::exception& e) {
    p.run.status = refusal(e);
  }
  return p;
}

std::string plate_csv_row(const Setting& s, const PlateRun& p) {
  const SweepRun& r = p.run;
  std::ostringstream line;
  line << s.kernel << ',' << (s.h_over_dx > 0 ? fmt("%.3g", s.h_over_dx) : "default") << ','
       << s.across << ',' << s.formulation << ',' << (s.cfl > 0 ? fmt("%.3g", s.cfl) : "default")
       << ',' << r.dt << ',' << r.particles << ',' << r.steps << ',' << r.wall << ',' << r.cpu
       << ',' << p.period << ',' << p.period_error << ',' << p.decay << ',' << r.status;
  return line.str();
}

// The oscillating plate: period error against cost over kernel, spacing,
// h/dx, Courant number and formulation.
void plate_sweep(const std::filesystem::path& out, bool quick, int threads) {
  Sweep sweep(plate_settings(quick));
  std::ofstream csv(out / "pareto_plate.csv");
  csv << "kernel,h_over_dx,H_over_dx,formulation,cfl,dt_s,particles,steps,wall_s,cpu_s,"
         "period_s,period_error,amplitude_decay_2_periods,status\n";
  std::printf("%-52s %9s %8s %9s %9s %11s\n", "setting", "particles", "steps", "wall_s", "cpu_s",
              "period_err");
  for (std::size_t i = 0; i < sweep.set.size(); ++i) {
    const Setting& s = sweep.set[i];
    const PlateRun p = run_plate_setting(s, threads);
    sweep.cost[i] = p.run.cpu;
    sweep.err[i] = std::abs(p.period_error);
    print_sweep_row(
        s.label, p.run,
        std::isfinite(p.period_error) ? fmt("%+.2f%%", 100 * p.period_error) : p.run.status);
    sweep.rows.push_back(plate_csv_row(s, p));
  }
  report_sweep(out, "plate", "Oscillating plate: period error against CPU time", "period error",
               sweep, csv);
}

}  // namespace

void pareto_sweeps(const std::filesystem::path& out, const std::string& cases, bool quick,
                   int threads) {
  auto wanted = [&cases](const char* c) { return cases.find(c) != std::string::npos; };
  if (wanted("hertz")) hertz_sweep(out, quick, threads);
  if (wanted("gear")) gear_sweep(out, quick, threads);
  if (wanted("plate")) plate_sweep(out, quick, threads);
}

}  // namespace gearsph::cli::bench
