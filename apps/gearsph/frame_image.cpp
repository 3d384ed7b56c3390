// One frame of results.h5 drawn with the field renderer. Outlines are stored
// in the reference configuration; each is carried along with its body by the
// body's best-fit rigid motion, so a turned pinion is drawn turned.
#include "apps/gearsph/frame_image.hpp"

#if defined(GEARSPH_WITH_RESULTS) && defined(GEARSPH_WITH_RENDER)

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "render/field_image.hpp"
#include "render/mesh_image.hpp"
#include "render/particle_mesh.hpp"
#include "results/results_reader.hpp"

namespace gearsph::cli {

namespace {

using render::FieldImage;

// Characters of a job's name shown in an image's title.
constexpr std::size_t kMaxTitleName = 24;

// A window about as tall as wide (a tooth) is drawn on the canvas of the FE
// check's tooth figures (fe/fe_images.cpp), so the two sit side by side at
// one size; a wider one on the usual 1280 x 800.
constexpr double kTallWindow = 0.75;  // height / width
constexpr int kToothWidth = 1100, kToothHeight = 1000;

// What every failure to read or draw a frame says first.
constexpr const char* kNotRendered = "the image could not be rendered: ";

struct FieldChoice {
  std::string label;
  std::string unit;  // SI
  FieldImage::Colouring colouring;
};

// The fields a frame can be drawn by; vectors are drawn as magnitudes.
const std::map<std::string, FieldChoice>& field_choices() {
  using C = FieldImage::Colouring;
  static const std::map<std::string, FieldChoice> choices = {
      {"von_mises", {"von Mises stress", "Pa", C::Sequential}},
      {"max_principal", {"largest principal stress", "Pa", C::Diverging}},
      {"pressure", {"pressure", "Pa", C::Diverging}},
      {"stress_xx", {"stress xx", "Pa", C::Diverging}},
      {"stress_yy", {"stress yy", "Pa", C::Diverging}},
      {"stress_xy", {"stress xy", "Pa", C::Diverging}},
      {"velocity", {"speed |v|", "m/s", C::Sequential}},
      {"displacement", {"displacement |u|", "m", C::Sequential}},
      {"density", {"density", "kg/m^3", C::Sequential}},
      {"body", {"body", "", C::Categorical}},
  };
  return choices;
}

std::string known_fields() {
  std::string out;
  for (const auto& [name, choice] : field_choices()) out += (out.empty() ? "" : ", ") + name;
  return out;
}

// The in-plane largest principal stress, sigma_1 = (sxx + syy) / 2 +
// sqrt(((sxx - syy) / 2)^2 + sxy^2), per particle.
std::vector<double> max_principal(const std::vector<double>& xx, const std::vector<double>& yy,
                                  const std::vector<double>& xy) {
  std::vector<double> out(std::min({xx.size(), yy.size(), xy.size()}));
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = 0.5 * (xx[i] + yy[i]) + std::hypot(0.5 * (xx[i] - yy[i]), xy[i]);
  }
  return out;
}

std::vector<double> magnitudes(const std::vector<double>& xyz) {
  std::vector<double> out(xyz.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = std::hypot(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  }
  return out;
}

// Rotation and translation that best carry a body's reference positions to
// its current ones (least squares, 2D), applied to the body's outlines.
struct RigidMotion {
  double cx0 = 0, cy0 = 0, cx = 0, cy = 0, angle = 0;
  std::array<double, 2> apply(const std::array<double, 2>& p) const {
    const double c = std::cos(angle), s = std::sin(angle);
    const double dx = p[0] - cx0, dy = p[1] - cy0;
    return {cx + c * dx - s * dy, cy + s * dx + c * dy};
  }
};

RigidMotion fit_motion(const std::vector<double>& ref, const std::vector<double>& cur,
                       std::int64_t begin, std::int64_t end) {
  RigidMotion m;
  const double n = static_cast<double>(end - begin);
  if (n < 1) return m;
  for (std::int64_t i = begin; i < end; ++i) {
    const auto k = static_cast<std::size_t>(3 * i);
    m.cx0 += ref[k] / n;
    m.cy0 += ref[k + 1] / n;
    m.cx += cur[k] / n;
    m.cy += cur[k + 1] / n;
  }
  double dot = 0, cross = 0;
  for (std::int64_t i = begin; i < end; ++i) {
    const auto k = static_cast<std::size_t>(3 * i);
    const double ax = ref[k] - m.cx0, ay = ref[k + 1] - m.cy0;
    const double bx = cur[k] - m.cx, by = cur[k + 1] - m.cy;
    dot += ax * bx + ay * by;
    cross += ax * by - ay * bx;
  }
  m.angle = std::atan2(cross, dot);
  return m;
}

// How the requested field is drawn; refuses a field the renderer does not
// know, and a colour range for a field drawn in categories.
const FieldChoice& checked_choice(const FrameImageRequest& request) {
  const auto choice = field_choices().find(request.field);
  if (choice == field_choices().end()) {
    throw FrameImageError(FrameImageFault::unknown_field,
                          "no field \"" + request.field + "\"; known fields: " + known_fields());
  }
  if (request.range && choice->second.colouring == FieldImage::Colouring::Categorical) {
    throw FrameImageError(
        FrameImageFault::no_colour_scale,
        "range sets a colour scale; the field \"" + request.field + "\" has none");
  }
  return choice->second;
}

results::ResultsFile open_results(const std::filesystem::path& run_dir) {
  try {
    return results::ResultsFile(run_dir / "results.h5");
  } catch (const std::exception& e) {
    throw FrameImageError(FrameImageFault::no_results, kNotRendered + std::string(e.what()));
  }
}

// The index of the requested frame in the file (any negative frame: the last).
std::size_t checked_frame_index(const results::ResultsFile& file, std::int64_t frame) {
  const std::size_t frames = file.frame_count();
  if (frames == 0) {
    throw FrameImageError(FrameImageFault::no_frames,
                          "this job wrote no frames (output.frames = 0)");
  }
  if (frame >= static_cast<std::int64_t>(frames)) {
    throw FrameImageError(FrameImageFault::no_such_frame,
                          "frame " + std::to_string(frame) + " does not exist; this job has " +
                              std::to_string(frames) + " frames, 0 to " +
                              std::to_string(frames - 1));
  }
  return frame < 0 ? frames - 1 : static_cast<std::size_t>(frame);
}

// The canvas: a tall zoom window gets the FE check's tooth canvas.
void size_canvas(FieldImage& f, const std::optional<std::array<double, 4>>& zoom_m) {
  f.width = 1280;
  f.height = 800;
  if (zoom_m) {
    const auto& z = *zoom_m;
    if (z[3] - z[1] >= kTallWindow * (z[2] - z[0])) {
      f.width = kToothWidth;
      f.height = kToothHeight;
    }
  }
  f.supersample = 2;
}

// Spacing from the particles' areas: mass per metre / density = dx^2.
double particle_spacing_m(std::size_t n, const results::InitialState& initial,
                          const std::vector<results::BodyInfo>& bodies) {
  double area = 0;
  for (std::size_t i = 0; i < n && i < initial.mass.size(); ++i) {
    const auto b = static_cast<std::size_t>(initial.body_id[i]);
    if (b < bodies.size() && bodies[b].rho_kg_m3 > 0) area += initial.mass[i] / bodies[b].rho_kg_m3;
  }
  return n > 0 && area > 0 ? std::sqrt(area / static_cast<double>(n)) : 1e-3;
}

// The particles where the frame has them, drawn at their spacing.
void place_particles(FieldImage& f, const results::Frame& frame,
                     const results::InitialState& initial,
                     const std::vector<results::BodyInfo>& bodies) {
  const std::size_t n = frame.position.size() / 3;
  f.x.resize(n);
  f.y.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    f.x[i] = frame.position[3 * i];
    f.y[i] = frame.position[3 * i + 1];
  }
  f.body.assign(frame.body_id.begin(), frame.body_id.end());
  f.particle_size_m = particle_spacing_m(n, initial, bodies);
}

// The value of `field` at each particle; none for "body", which is
// coloured by the body ids.
std::vector<double> field_values(const results::ResultsFile& file, std::size_t index,
                                 const results::Frame& frame, const std::string& field) {
  if (field == "velocity") return magnitudes(frame.velocity);
  if (field == "displacement") return magnitudes(frame.displacement);
  if (field == "max_principal") {
    return max_principal(file.field(index, "stress_xx"), file.field(index, "stress_yy"),
                         file.field(index, "stress_xy"));
  }
  if (field == "body") return {};
  return file.field(index, field);
}

// The colour bar: its label, its unit, and its range (the request's, or
// from the values).
void set_colour_scale(FieldImage& f, const FieldChoice& choice, const FrameImageRequest& request) {
  f.colouring = choice.colouring;
  f.field_label = choice.label;
  double max_abs = 0;
  bool off_scale = false;
  for (double v : f.value) {
    if (std::isfinite(v)) max_abs = std::max(max_abs, std::abs(v));
    if (request.range && ((*request.range)[0] > v || v > (*request.range)[1])) off_scale = true;
  }
  if (request.range) {
    // The bar spans the range and is labelled in its unit; values beyond
    // take the end colours, and the label says there are some.
    max_abs = std::max(std::abs((*request.range)[0]), std::abs((*request.range)[1]));
    if (off_scale) f.field_label += " (off scale beyond the ends)";
  }
  if (!choice.unit.empty()) {
    const auto unit = render::engineering_unit(max_abs, choice.unit);
    f.unit_label = unit.label;
    f.unit_scale = unit.scale;
  }
  if (request.range) {
    f.vmin = (*request.range)[0];
    f.vmax = (*request.range)[1];
  } else if (f.colouring == FieldImage::Colouring::Sequential && request.field != "density") {
    // Magnitudes start at zero; a field that is zero everywhere (the stress
    // of the initial state) still needs a range: one displayed unit.
    f.vmin = 0.0;
    if (!(max_abs > 0)) f.vmax = 1.0 / f.unit_scale;
  }
}

// The job's name as the title shows it. The title shares its line with the
// time stamp above a view that may be narrow (a tall scene): a long name is
// cut to keep them apart.
std::string title_name(const results::ResultsFile& file) {
  std::string name = file.job().value("name", std::string("job"));
  if (name.size() > kMaxTitleName) {
    std::size_t cut = kMaxTitleName - 3;
    // Not inside a UTF-8 sequence (continuation bytes are 10xxxxxx).
    while (cut > 0 && (static_cast<unsigned char>(name[cut]) & 0xC0) == 0x80) --cut;
    name = name.substr(0, cut) + "...";
  }
  return name;
}

// The stored outlines, each moved with its body as the frame has it.
std::vector<render::Polyline> moved_outlines(const results::ResultsFile& file,
                                             const results::Frame& frame,
                                             const results::InitialState& initial,
                                             const std::vector<results::BodyInfo>& bodies) {
  std::vector<render::Polyline> lines;
  for (const auto& o : file.outlines()) {
    render::Polyline line;
    line.colour = {20, 20, 20};
    line.closed = o.closed;
    line.width_px = 1.5;
    if (o.name == "crack") {  // a crack's path (results.h5 /cracks), over the field
      line.colour = {200, 0, 0};
      line.width_px = 2.5;
    }
    const bool moves = o.body >= 0 && static_cast<std::size_t>(o.body) < bodies.size();
    const RigidMotion m = moves ? fit_motion(initial.position, frame.position, bodies[o.body].begin,
                                             bodies[o.body].end)
                                : RigidMotion{};
    for (const auto& p : o.points) {
      const auto q = moves ? m.apply(p) : p;
      line.x.push_back(q[0]);
      line.y.push_back(q[1]);
    }
    lines.push_back(std::move(line));
  }
  return lines;
}

// Bands of a field drawn as contours: about one per 8 % of its range.
constexpr int kContourBands = 12;

// The field as contours inside the outlines (particle_mesh.hpp): the
// particles triangulated within their bodies, the field smoothed for the
// drawing, the same frame, colour bar and outlines as the particle figure.
// The particles the window shows (all without a zoom).
std::vector<unsigned char> in_window(const FieldImage& f) {
  std::vector<unsigned char> in(f.x.size(), 1);
  if (!f.zoom) return in;
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    in[i] = f.x[i] >= f.zoom->x0 && f.x[i] <= f.zoom->x1 && f.y[i] >= f.zoom->y0 &&
            f.y[i] <= f.zoom->y1;
  }
  return in;
}

std::string draw_contours(const FieldImage& f, const results::ResultsFile& file,
                          const results::InitialState& initial, DrawnFieldStats* stats) {
  // Triangulated in the reference configuration, against the outlines as
  // stored; drawn where the particles are now.
  std::vector<double> x0, y0;
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    x0.push_back(initial.position[3 * i]);
    y0.push_back(initial.position[3 * i + 1]);
  }
  std::vector<render::Polyline> reference;
  std::vector<int> outline_body;
  for (const auto& o : file.outlines()) {
    render::Polyline line;
    line.closed = o.closed;
    for (const auto& p : o.points) {
      line.x.push_back(p[0]);
      line.y.push_back(p[1]);
    }
    reference.push_back(std::move(line));
    outline_body.push_back(o.body);
  }
  const render::ParticleMesh mesh =
      render::particle_mesh(x0, y0, f.body, reference, outline_body, 3.0 * f.particle_size_m);
  render::MeshImage m;
  m.width = f.width;
  m.height = f.height;
  m.x = f.x;
  m.y = f.y;
  m.triangles = mesh.triangles;
  m.value = render::smoothed_for_drawing(f.x, f.y, f.value, mesh);
  if (stats) {
    const std::vector<unsigned char> in = in_window(f);
    stats->particles_zigzag = render::zigzag_indicator(f.x, f.y, f.value, mesh, &in);
    stats->drawn_zigzag = render::zigzag_indicator(f.x, f.y, m.value, mesh, &in);
    stats->counted = static_cast<std::size_t>(std::count(in.begin(), in.end(), 1));
    stats->particles_max = stats->drawn_max = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < in.size(); ++i) {
      if (!in[i]) continue;
      if (std::isfinite(f.value[i]))
        stats->particles_max = std::max(stats->particles_max, f.value[i]);
      if (std::isfinite(m.value[i])) stats->drawn_max = std::max(stats->drawn_max, m.value[i]);
    }
  }
  m.field_label = f.field_label;
  m.unit_label = f.unit_label;
  m.unit_scale = f.unit_scale;
  m.vmin = f.vmin;
  m.vmax = f.vmax;
  m.diverging = f.colouring == FieldImage::Colouring::Diverging;
  m.bands = kContourBands;
  m.outlines = f.outlines;
  m.title = f.title;
  m.time_s = f.time_s;
  m.zoom = f.zoom;
  m.supersample = f.supersample;
  const auto png = render::render_mesh_png(m);
  return std::string(png.begin(), png.end());
}

std::string draw(const std::filesystem::path& run_dir, const FrameImageRequest& request,
                 DrawnFieldStats* stats) {
  const FieldChoice& choice = checked_choice(request);
  const results::ResultsFile file = open_results(run_dir);
  const std::size_t index = checked_frame_index(file, request.frame);
  const results::Frame frame = file.frame(index);
  const results::InitialState initial = file.initial();
  const std::vector<results::BodyInfo> bodies = file.bodies();

  FieldImage f;
  size_canvas(f, request.zoom_m);
  place_particles(f, frame, initial, bodies);
  f.value = field_values(file, index, frame, request.field);
  set_colour_scale(f, choice, request);
  for (const auto& b : bodies) f.body_names.push_back(b.name);
  f.time_s = frame.time_s;
  f.title = title_name(file) + ": " + choice.label;
  if (request.zoom_m) {
    const auto& z = *request.zoom_m;
    f.zoom = render::Window{z[0], z[1], z[2], z[3]};
  }
  f.outlines = moved_outlines(file, frame, initial, bodies);
  if (!request.particles && choice.colouring != FieldImage::Colouring::Categorical) {
    return draw_contours(f, file, initial, stats);
  }
  const auto png = render::render_field_png(f);
  return std::string(png.begin(), png.end());
}

}  // namespace

std::string draw_frame_png(const std::filesystem::path& run_dir, const FrameImageRequest& request,
                           DrawnFieldStats* stats) {
  if (stats) *stats = DrawnFieldStats{};
  try {
    return draw(run_dir, request, stats);
  } catch (const FrameImageError&) {
    throw;
  } catch (const std::exception& e) {
    throw FrameImageError(FrameImageFault::drawing_failed, kNotRendered + std::string(e.what()));
  }
}

}  // namespace gearsph::cli

#endif
