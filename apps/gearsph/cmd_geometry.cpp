// gearsph geometry JOB.json --out DIR: the scene a job would simulate, as
// pictures and tables a person can check before running it: outlines and
// particles (SVG, coloured by body and by kinematic role) and CSV files.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "apps/gearsph/cli.hpp"
#include "solver/geometry/svg.hpp"
#include "solver/job/job.hpp"

namespace gearsph::cli {

namespace {

// Colours by body (free particles) and a grey for driven/guided ones.
const char* const kBodyColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd"};
const char* const kDrivenColour = "#8c8c8c";

geometry::SvgDrawing drawing_of(const PreparedJob& job) {
  const Simulation& sim = job.scene.sim;
  const Particles& p = sim.particles;
  geometry::SvgDrawing d;
  // Graded particles: the range of their spacings, not the bulk's alone.
  auto spacing_of = [&](std::size_t i) {
    return i < p.spacing.size() && p.spacing[i] > 0.0 ? p.spacing[i] : sim.discretization.dx;
  };
  double finest = p.n ? spacing_of(0) : sim.discretization.dx, coarsest = finest;
  for (std::size_t i = 1; i < p.n; ++i) {
    finest = std::min(finest, spacing_of(i));
    coarsest = std::max(coarsest, spacing_of(i));
  }
  auto mm = [](double m) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3f", m * 1e3);
    return std::string(text);
  };
  d.title = job.job.at("name").get<std::string>() + " (" + job.scene.type +
            "): " + std::to_string(p.n) + " particles, " +
            (coarsest > 1.001 * finest ? "spacing " + mm(finest) + " to " + mm(coarsest)
                                       : "dx = " + mm(coarsest)) +
            " mm";
  // Scale so that the drawing is about 1200 px wide.
  double x0 = 1e300, x1 = -1e300;
  for (std::size_t i = 0; i < p.n; ++i) {
    x0 = std::min(x0, p.x[i]);
    x1 = std::max(x1, p.x[i]);
  }
  d.px_per_mm = std::clamp(1200.0 / std::max(1e-3, (x1 - x0) * 1e3), 0.5, 200.0);
  // Each dot 0.4 of its particle's own spacing, so that graded particles
  // look as dense as they are: one set of dots per body, role and spacing
  // (to 2 %).
  for (std::size_t b = 0; b < sim.bodies.size(); ++b) {
    std::map<std::pair<bool, long>, geometry::SvgDots> sets;
    for (std::size_t i = sim.bodies[b].begin; i < sim.bodies[b].end; ++i) {
      const long bin = std::lround(std::log(spacing_of(i) / finest) / std::log(1.02));
      geometry::SvgDots& dots = sets[{p.motion[i] != 0, bin}];
      if (dots.points.empty()) {
        dots.colour = p.motion[i] == 0 ? kBodyColours[b % 4] : kDrivenColour;
        dots.radius_m = 0.4 * finest * std::pow(1.02, static_cast<double>(bin));
      }
      dots.points.push_back({p.x[i], p.y[i]});
    }
    for (auto& [key, dots] : sets) d.dots.push_back(std::move(dots));
  }
  for (const Outline& o : job.scene.outlines) {
    geometry::SvgPolyline line;
    for (const auto& q : o.points) line.points.push_back({q[0], q[1]});
    line.closed = o.closed;
    line.width_px = 1.2;
    d.lines.push_back(line);
  }
  return d;
}

}  // namespace

int cmd_geometry(Args& args) {
  const auto out = args.option("out");
  const auto pos = args.positional();
  if (pos.size() != 1 || !out)
    throw std::invalid_argument("usage: gearsph geometry JOB.json --out DIR");
  PreparedJob job;
  try {
    job = prepare_job(parse_job_text(read_file(pos[0])), 1);
  } catch (const InvalidJob& e) {
    std::fprintf(stderr, "gearsph geometry: %s is not a valid job:\n", pos[0].c_str());
    for (const JobIssue& i : e.issues) {
      std::fprintf(stderr, "  %s: %s\n", i.pointer.empty() ? "(document)" : i.pointer.c_str(),
                   i.message.c_str());
    }
    return 2;
  }
  std::filesystem::create_directories(*out);
  const Simulation& sim = job.scene.sim;
  const Particles& p = sim.particles;
  geometry::write_svg(*out + "/geometry.svg", drawing_of(job));

  std::ostringstream csv;
  csv << "particle,body,motion,x_m,y_m,mass_kg_per_m\n";
  csv.precision(10);
  for (std::size_t i = 0; i < p.n; ++i) {
    csv << i << ',' << sim.bodies[p.body[i]].name << ',' << sim.motions[p.motion[i]].name << ','
        << p.x[i] << ',' << p.y[i] << ',' << p.mass[i] << '\n';
  }
  std::ofstream(*out + "/particles.csv") << csv.str();
  std::ostringstream ol;
  ol << "outline,body,point,x_m,y_m\n";
  ol.precision(10);
  for (const Outline& o : job.scene.outlines) {
    for (std::size_t k = 0; k < o.points.size(); ++k) {
      ol << o.name << ',' << o.body << ',' << k << ',' << o.points[k][0] << ',' << o.points[k][1]
         << '\n';
    }
  }
  std::ofstream(*out + "/outlines.csv") << ol.str();
  std::ofstream(*out + "/model.json") << job.scene.description.dump(2) << '\n';
  std::printf("%zu particles", p.n);
  for (const Body& b : sim.bodies) std::printf(", %s %zu", b.name.c_str(), b.count());
  std::printf("; wrote %s/geometry.svg, particles.csv, outlines.csv, model.json\n", out->c_str());
  return 0;
}

}  // namespace gearsph::cli
