// gearsph study stability: the matrix of failure-prone cases against
// methods (solver/study/stability_matrix.hpp), measured, written as
// stability.csv, stability.json, a colour-coded table (stability_table.png)
// and the particle fields of the failed cells (fields/*.png), each next to
// the same case run with a method that holds.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "apps/gearsph/cli.hpp"
#include "solver/run/execute.hpp"
#include "solver/study/stability_matrix.hpp"
#ifdef GEARSPH_WITH_RENDER
#include "render/colormap.hpp"
#include "render/field_image.hpp"
#include "render/font.hpp"
#include "render/gl_context.hpp"
#include "render/png_io.hpp"
#endif

namespace gearsph::cli {

namespace {

namespace fs = std::filesystem;
using study::Cell;
using study::CellResult;

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

// "3.21 ms", "45 us": a time a reader takes in at a glance.
std::string short_time(double s) {
  if (s >= 1.0) return fmt("%.3g s", s);
  if (s >= 1e-3) return fmt("%.3g ms", s * 1e3);
  return fmt("%.3g us", s * 1e6);
}

// The line of the table and of the console saying what happened.
std::string outcome_line(const CellResult& r) {
  if (r.outcome == "failed") {
    return "FAILS: " + r.failed_by + (r.failed_at_s >= 0 ? " at " + short_time(r.failed_at_s) : "");
  }
  return r.outcome == "warning" ? "warning" : "stable";
}

[[maybe_unused]] std::string measures_line(const CellResult& r) {
  std::string s = "drift " + fmt("%+.2g%%", 100.0 * r.energy_drift);
  s += "  zz " + fmt("%.2f", r.zigzag);
  if (r.max_penetration_over_dx > 0) s += "  pen " + fmt("%.2f dx", r.max_penetration_over_dx);
  if (r.spurious_stress) s += "  vm " + fmt("%.2g", *r.spurious_stress);
  return s;
}

#ifdef GEARSPH_WITH_RENDER

// The von Mises field of a cell's final (or failed) state, framed on the
// body's initial extent so that escaped particles do not shrink the picture.
void field_png(const fs::path& path, const Cell& cell, const CellResult& r,
               const PreparedJob& job) {
  const Simulation& sim = job.scene.sim;
  const Particles& p = sim.particles;
  render::FieldImage img;
  img.width = 1280;
  img.height = 600;
  double x0 = 1e300, y0 = 1e300, x1 = -1e300, y1 = -1e300;
  for (std::size_t i = 0; i < p.n; ++i) {
    img.x.push_back(p.x[i]);
    img.y.push_back(p.y[i]);
    img.value.push_back(p.von_mises(i));
    // Frame the initial and the current shape; a particle on its way out
    // of the domain (or non-finite) does not widen it.
    x0 = std::min(x0, p.x0[i]);
    x1 = std::max(x1, p.x0[i]);
    y0 = std::min(y0, p.y0[i]);
    y1 = std::max(y1, p.y0[i]);
    if (std::isfinite(p.x[i]) && std::isfinite(p.y[i]) && sim.domain.contains(p.x[i], p.y[i])) {
      x0 = std::min(x0, p.x[i]);
      x1 = std::max(x1, p.x[i]);
      y0 = std::min(y0, p.y[i]);
      y1 = std::max(y1, p.y[i]);
    }
  }
  // A margin, then wide enough for the image's shape, so that the title
  // and the time stamp above the view never collide.
  const double m = 0.1 * std::max(x1 - x0, y1 - y0);
  x0 -= m, x1 += m, y0 -= m, y1 += m;
  const double widen = std::max(0.0, 2.2 * (y1 - y0) - (x1 - x0));
  img.zoom = render::Window{x0 - 0.5 * widen, y0, x1 + 0.5 * widen, y1};
  img.particle_size_m = sim.discretization.dx;
  double vmax = 0;
  for (double v : img.value) {
    if (std::isfinite(v)) vmax = std::max(vmax, v);
  }
  const render::EngineeringUnit u = render::engineering_unit(vmax, "Pa");
  img.field_label = "von Mises stress";
  img.unit_label = u.label;
  img.unit_scale = u.scale;
  img.title = cell.case_label + ", " + cell.method_label + ": " +
              (r.outcome == "failed" ? "fails (" + r.failed_by + ")" : r.outcome);
  img.time_s = sim.time;
  render::write_png(path, render::render_field_png(img));
}

render::Rgb8 outcome_colour(const std::string& outcome) {
  if (outcome == "failed") return {228, 120, 110};
  if (outcome == "warning") return {245, 200, 100};
  return {150, 210, 140};
}

// Rows: cases; in each row its cells, left to right, coloured by outcome.
// A thick black frame marks a cell whose outcome differs from what the
// literature leads one to expect (docs/stability.md says why).
void table_png(const fs::path& path, const std::vector<Cell>& cells,
               const std::vector<CellResult>& results) {
  // Layout: each case a block of lines of at most kPerLine cells.
  constexpr int kPerLine = 6;
  const int label_w = 230, cell_w = 290, cell_h = 92, top = 60, legend_h = 70;
  struct Slot {
    std::size_t cell;
    double x, y;
  };
  std::vector<Slot> slots;
  std::vector<std::pair<std::size_t, double>> case_labels;  // first cell, centre y
  double y = top;
  for (std::size_t k = 0; k < cells.size();) {
    std::size_t end = k;
    while (end < cells.size() && cells[end].case_id == cells[k].case_id) ++end;
    const int n = static_cast<int>(end - k);
    const int lines = (n + kPerLine - 1) / kPerLine;
    case_labels.push_back({k, y + 0.5 * lines * cell_h});
    for (int c = 0; c < n; ++c) {
      slots.push_back({k + static_cast<std::size_t>(c), double(label_w + (c % kPerLine) * cell_w),
                       y + (c / kPerLine) * cell_h});
    }
    y += lines * cell_h + 8;
    k = end;
  }
  const int width = label_w + kPerLine * cell_w + 10;
  const int height = static_cast<int>(y) + legend_h;
  const double ly = y + 16;

  render::RgbImage image;
  {
    render::GlCanvas canvas(width, height, 2);
    canvas.clear({255, 255, 255});
    for (const Slot& sl : slots) {
      const CellResult& r = results[sl.cell];
      if (!r.as_expected) {
        canvas.fill_rect({sl.x + 1, sl.y + 1, sl.x + cell_w - 1, sl.y + cell_h - 1}, {});
      }
      const double inset = r.as_expected ? 2 : 5;
      canvas.fill_rect({sl.x + inset, sl.y + inset, sl.x + cell_w - inset, sl.y + cell_h - inset},
                       outcome_colour(r.outcome));
    }
    canvas.fill_rect({10, ly, 34, ly + 20}, outcome_colour("stable"));
    canvas.fill_rect({130, ly, 154, ly + 20}, outcome_colour("warning"));
    canvas.fill_rect({260, ly, 284, ly + 20}, outcome_colour("failed"));
    canvas.fill_rect({370, ly, 394, ly + 20}, {});
    canvas.fill_rect({374, ly + 4, 390, ly + 16}, {255, 255, 255});
    image = canvas.resolve();
  }
  const render::TextStyle title{22, {0, 0, 0}, true};
  const render::TextStyle bold{15, {0, 0, 0}, true};
  const render::TextStyle small{14, {20, 20, 20}, false};
  const render::TextStyle label{17, {0, 0, 0}, true};
  render::draw_text(image, "Stability study: cases x methods (gearsph study stability)", 10, 36,
                    title);
  for (const auto& [first, cy] : case_labels) {
    render::draw_text(image, cells[first].case_label, 10, static_cast<int>(cy), label,
                      render::HAlign::Left, render::VAlign::Middle);
  }
  for (const Slot& sl : slots) {
    const int x = static_cast<int>(sl.x) + 10, yy = static_cast<int>(sl.y);
    const Cell& cell = cells[sl.cell];
    const CellResult& r = results[sl.cell];
    render::draw_text(image, cell.method_label, x, yy + 24, bold);
    render::draw_text(image, outcome_line(r), x, yy + 45, small);
    render::draw_text(image, measures_line(r), x, yy + 64, small);
    render::draw_text(image, "literature: " + cell.expect + (r.as_expected ? "" : " - differs"), x,
                      yy + 83, small);
  }
  const int ty = static_cast<int>(ly) + 15;
  render::draw_text(image, "holds", 42, ty, small);
  render::draw_text(image, "warning", 162, ty, small);
  render::draw_text(image, "fails", 292, ty, small);
  render::draw_text(image, "outcome differs from the literature (see docs/stability.md)", 402, ty,
                    small);
  render::draw_text(image,
                    "drift: final energy balance; zz: zig-zag indicator (max); pen: max overlap; "
                    "vm: max von Mises / rho w^2 R^2; times: when the run was stopped",
                    10, ty + 26, small);
  render::write_png(path, render::encode_png(image));
}

#endif

std::string file_name(const Cell& c) {
  return c.case_id + "__" + c.method_id;
}

}  // namespace

int cmd_speed_sweep(Args& args);  // cmd_speed_sweep.cpp

int cmd_study(Args& args) {
  if (args.positional_first() == "speed-sweep") return cmd_speed_sweep(args);
  const bool full = args.flag("full");
  [[maybe_unused]] const bool no_images = args.flag("no-images");
  const std::string out = args.option("out").value_or("stability");
  const int threads = args.integer("threads", 0);
  const auto only = args.option("only");
  const std::vector<std::string> rest = args.positional();
  if (rest.size() != 1 || rest[0] != "stability") {
    throw std::invalid_argument(
        "usage: gearsph study stability [--out DIR] [--full] [--only TEXT] [--threads N] "
        "[--no-images]");
  }
  fs::create_directories(fs::path(out) / "fields");
  fs::create_directories(fs::path(out) / "jobs");

  std::vector<Cell> cells;
  for (Cell& c : study::stability_cells(full)) {
    if (only && (c.case_id + "/" + c.method_id).find(*only) == std::string::npos) continue;
    cells.push_back(std::move(c));
  }
  std::vector<CellResult> results;
  std::string csv = study::csv_header();
  nlohmann::json report = nlohmann::json::array();
  int unexpected = 0, changed = 0;
  std::printf("%-18s %-30s %-7s %-28s %9s %7s %6s %8s %7s\n", "case", "method", "expect", "outcome",
              "drift", "zigzag", "pen/dx", "particles", "wall_s");
  std::map<std::string, bool> case_has_stable_picture;
  for (const Cell& cell : cells) {
    study::CellRun run = study::run_cell(cell, threads);
    const CellResult& r = run.result;
    unexpected += r.as_expected ? 0 : 1;
    changed += r.as_documented ? 0 : 1;
    std::printf("%-18s %-30s %-7s %-28s %+8.2g%% %7.3f %6.2f %8zu %7.1f%s\n", cell.case_id.c_str(),
                cell.method_id.c_str(), cell.expect.c_str(), outcome_line(r).c_str(),
                100.0 * r.energy_drift, r.zigzag, r.max_penetration_over_dx, r.particles, r.wall_s,
                !r.as_documented ? "  <- NOT AS DOCUMENTED"
                : r.as_expected  ? ""
                                 : "  <- differs from the literature (documented)");
    std::fflush(stdout);
    write_file_atomic(fs::path(out) / "jobs" / (file_name(cell) + ".json"),
                      cell.job.dump(2) + "\n");
    csv += study::csv_row(cell, r);
    nlohmann::json j = study::to_json(cell, r);
    j["summary"] = run.summary;
#ifdef GEARSPH_WITH_RENDER
    // Every failure, and the first stable cell of each case for comparison.
    const bool picture =
        r.outcome == "failed" || (r.outcome != "failed" && !case_has_stable_picture[cell.case_id]);
    if (!no_images && picture) {
      if (r.outcome != "failed") case_has_stable_picture[cell.case_id] = true;
      const std::string name = "fields/" + file_name(cell) + ".png";
      field_png(fs::path(out) / name, cell, r, run.job);
      j["image"] = name;
    }
#endif
    report.push_back(std::move(j));
    results.push_back(r);
  }
  write_file_atomic(fs::path(out) / "stability.csv", csv);
  write_file_atomic(fs::path(out) / "stability.json", report.dump(2) + "\n");
#ifdef GEARSPH_WITH_RENDER
  if (!no_images && !cells.empty()) {
    table_png(fs::path(out) / "stability_table.png", cells, results);
  }
#endif
  std::printf(
      "%zu cells: %d differ from the literature (as documented), %d differ from "
      "docs/stability.md; results in %s/\n",
      cells.size(), unexpected, changed, out.c_str());
  return 0;
}

}  // namespace gearsph::cli
