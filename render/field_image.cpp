#include "render/field_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <stdexcept>

#include "render/colormap.hpp"
#include "render/font.hpp"

namespace gearsph::render {

EngineeringUnit engineering_unit(double max_abs, std::string_view si_unit) {
  static const char* prefixes[] = {"p", "n", "µ", "m", "", "k", "M", "G", "T"};  // 1e-12..1e12
  int e = 0;
  if (std::isfinite(max_abs) && max_abs > 0.0)
    e = std::clamp(3 * static_cast<int>(std::floor(std::log10(max_abs) / 3.0)), -12, 12);
  return {prefixes[(e + 12) / 3] + std::string(si_unit), std::pow(10.0, -e)};
}

std::string format_length(double metres) {
  const EngineeringUnit u = engineering_unit(std::abs(metres), "m");
  std::array<char, 64> text{};
  std::snprintf(text.data(), text.size(), "%g %s", metres * u.scale, u.label.c_str());
  return text.data();
}

Point FieldLayout::to_pixel(double x_m, double y_m) const {
  return {view.x0 + (x_m - world.x0) * px_per_m, view.y1 - (y_m - world.y0) * px_per_m};
}

namespace {

using Colouring = FieldImage::Colouring;

const Rgb8 kInk{34, 34, 34};
const Rgb8 kFrame{170, 170, 170};
const Rgb8 kWhite{255, 255, 255};

struct FieldStyle {
  double scale;                      // 1 at 1280 x 800
  double title, stamp, tick, label;  // font sizes, px
  double margin, gap, bar_width, tick_length, scale_bar_thickness, swatch;
  explicit FieldStyle(const FieldImage& f)
      : scale(std::sqrt(f.width * static_cast<double>(f.height) / (1280.0 * 800.0))),
        title(30 * scale),
        stamp(26 * scale),
        tick(23 * scale),
        label(25 * scale),
        margin(20 * scale),
        gap(8 * scale),
        bar_width(std::round(28 * scale)),
        tick_length(std::round(7 * scale)),
        scale_bar_thickness(std::max(2.0, std::round(6 * scale))),
        swatch(std::round(22 * scale)) {}
};

bool categorical(const FieldImage& f) {
  return f.colouring == Colouring::Categorical;
}

void validate(const FieldImage& f) {
  const std::size_t n = f.x.size();
  if (f.y.size() != n) throw std::invalid_argument("field image: x and y differ in length");
  if (!categorical(f) && f.value.size() != n)
    throw std::invalid_argument("field image: need one value per particle");
  if (categorical(f) && f.body.size() != n)
    throw std::invalid_argument("field image: need one body index per particle");
  if (!(f.particle_size_m > 0.0))
    throw std::invalid_argument("field image: particle_size_m must be positive");
  if (f.zoom && !(f.zoom->x1 > f.zoom->x0 && f.zoom->y1 > f.zoom->y0))
    throw std::invalid_argument("field image: zoom window needs x1 > x0 and y1 > y0");
  for (const Polyline& line : f.outlines)
    if (line.x.size() != line.y.size())
      throw std::invalid_argument("field image: outline x and y differ in length");
  if (f.width < 200 || f.height < 150)
    throw std::invalid_argument("field image: at least 200 x 150 pixels");
  if (f.bands < 0) throw std::invalid_argument("field image: bands must not be negative");
}

// Colour range in SI: given, or from the finite data.
Range colour_range(const FieldImage& f) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : f.value)
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!std::isfinite(lo)) lo = 0.0, hi = 1.0;
  if (f.colouring == Colouring::Diverging) {
    const double m = std::max(std::abs(lo), std::abs(hi));
    lo = -m, hi = m;
  }
  Range r{f.vmin.value_or(lo), f.vmax.value_or(hi)};
  if (r.min == r.max && !f.vmin && !f.vmax) {
    const double d = r.min != 0.0 ? 0.01 * std::abs(r.min) : 1.0;
    r = {r.min - d, r.max + d};
  }
  if (!(r.max > r.min)) throw std::invalid_argument("field image: need vmax > vmin");
  return r;
}

// Particles (with their discs) and outlines, padded by 3 %.
Window data_window(const FieldImage& f) {
  Window w{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  auto grow = [&w](double x, double y, double r) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    w = {std::min(w.x0, x - r), std::min(w.y0, y - r), std::max(w.x1, x + r),
         std::max(w.y1, y + r)};
  };
  for (std::size_t i = 0; i < f.x.size(); ++i) grow(f.x[i], f.y[i], 0.5 * f.particle_size_m);
  for (const Polyline& p : f.outlines)
    for (std::size_t i = 0; i < p.x.size(); ++i) grow(p.x[i], p.y[i], 0.0);
  if (!std::isfinite(w.x0)) return {0.0, 0.0, 1.0, 1.0};
  const double pad = 0.03 * std::max({w.x1 - w.x0, w.y1 - w.y0, f.particle_size_m});
  return {w.x0 - pad, w.y0 - pad, w.x1 + pad, w.y1 + pad};
}

std::string colour_bar_title(const FieldImage& f) {
  return f.unit_label.empty() ? f.field_label : f.field_label + " [" + f.unit_label + "]";
}

std::string body_name(const FieldImage& f, int b) {
  const auto k = static_cast<std::size_t>(b);
  return b >= 0 && k < f.body_names.size() ? f.body_names[k] : "body " + std::to_string(b);
}

std::vector<int> bodies_present(const FieldImage& f) {
  const std::set<int> s(f.body.begin(), f.body.end());
  return {s.begin(), s.end()};
}

Ticks bar_ticks(const FieldImage& f, Range r, double bar_height) {
  const int count = std::clamp(static_cast<int>(bar_height / 75.0), 3, 8);
  return nice_ticks(r.min * f.unit_scale, r.max * f.unit_scale, count);
}

int widest_tick(const Ticks& t, double size) {
  int w = 0;
  for (double v : t.values) w = std::max(w, measure_text(format_tick(v, t.step), {size}).width);
  return w;
}

// Width of the panel right of the view (colour bar + labels, or legend).
double panel_width(const FieldImage& f, const FieldStyle& st, Range r) {
  if (categorical(f)) {
    int w = 0;
    for (int b : bodies_present(f))
      w = std::max(w, measure_text(body_name(f, b), {st.label}).width);
    return 2 * st.gap + st.swatch + st.gap + w;
  }
  // Label widths depend on the tick count, unknown until the bar height is:
  // reserve for the widest of the possible counts.
  int widest = 0;
  for (int count = 3; count <= 8; ++count)
    widest = std::max(widest, widest_tick(bar_ticks(f, r, 75.0 * count), st.tick));
  const int title_height = measure_text("Ag", {st.label}).height();
  return 2 * st.gap + st.bar_width + st.tick_length + st.gap + widest + 1.5 * st.gap + title_height;
}

double top_band(const FieldImage& f, const FieldStyle& st) {
  if (f.title.empty() && std::isnan(f.time_s)) return st.margin;
  return st.margin + measure_text("Ag", {st.title, kInk, true}).height() + st.gap;
}

double bottom_band(const FieldStyle& st) {
  return st.margin +
         std::max(st.scale_bar_thickness,
                  static_cast<double>(measure_text("0 mm", {st.tick}).height())) +
         1.5 * st.gap;
}

// Fits the window into the free area at one scale for x and y, on whole
// pixels; the world window is re-centred to match the rounded view exactly.
void fit_view(FieldLayout& L, const FieldImage& f, const FieldStyle& st, double panel_w) {
  const Window want = f.zoom.value_or(data_window(f));
  const double top = top_band(f, st), avail_h = f.height - top - bottom_band(st);
  const double avail_w = f.width - 2 * st.margin - panel_w;
  if (avail_w < 50 || avail_h < 50)
    throw std::invalid_argument("field image: too small for the panel and labels");
  const double w_m = want.x1 - want.x0, h_m = want.y1 - want.y0;
  L.px_per_m = std::min(avail_w / w_m, avail_h / h_m);
  const double view_w = std::max(1.0, std::floor(w_m * L.px_per_m));
  const double view_h = std::max(1.0, std::floor(h_m * L.px_per_m));
  const double x0 = std::round(0.5 * (f.width - view_w - panel_w));
  const double y0 = std::round(top + 0.5 * (avail_h - view_h));
  L.view = {x0, y0, x0 + view_w, y0 + view_h};
  const double cx = 0.5 * (want.x0 + want.x1), cy = 0.5 * (want.y0 + want.y1);
  const double half_w = 0.5 * view_w / L.px_per_m, half_h = 0.5 * view_h / L.px_per_m;
  L.world = {cx - half_w, cy - half_h, cx + half_w, cy + half_h};
}

void place_panel(FieldLayout& L, const FieldImage& f, const FieldStyle& st, double panel_w,
                 Range r) {
  L.panel = {L.view.x1, L.view.y0, L.view.x1 + panel_w, L.view.y1};
  if (categorical(f)) return;
  const double avail_h = f.height - top_band(f, st) - bottom_band(st);
  const double bar_h = std::round(std::max(0.9 * L.view.height(), 0.5 * avail_h));
  const double bar_y0 = std::round(0.5 * (L.view.y0 + L.view.y1 - bar_h));
  const double bar_x0 = std::round(L.view.x1 + 2 * st.gap);
  L.colour_bar = {bar_x0, bar_y0, bar_x0 + st.bar_width, bar_y0 + bar_h};
  L.ticks = bar_ticks(f, r, bar_h);
}

void place_scale_bar(FieldLayout& L, const FieldStyle& st) {
  L.scale_bar_m = nice_floor(0.2 * (L.world.x1 - L.world.x0));
  L.scale_bar_label = format_length(L.scale_bar_m);
  const double length = std::round(L.scale_bar_m * L.px_per_m);
  const double y0 = std::round(L.view.y1 + 1.5 * st.gap);
  L.scale_bar = {L.view.x0, y0, L.view.x0 + length, y0 + st.scale_bar_thickness};
}

}  // namespace

FieldLayout field_layout(const FieldImage& f) {
  validate(f);
  const FieldStyle st(f);
  FieldLayout L;
  const Range r = categorical(f) ? Range{0, 1} : colour_range(f);
  L.vmin = r.min;
  L.vmax = r.max;
  const double panel_w = std::round(panel_width(f, st, r));
  fit_view(L, f, st, panel_w);
  place_panel(L, f, st, panel_w, r);
  place_scale_bar(L, st);
  return L;
}

namespace {

// ------------------------------------------------------------- geometry --

// A position on the map, t in [0, 1], moved to the middle of its band.
double banded(const FieldImage& f, double t) {
  if (f.bands <= 0) return t;
  const double n = f.bands;
  return (std::clamp(std::floor(t * n), 0.0, n - 1.0) + 0.5) / n;
}

Rgb8 particle_colour(const FieldImage& f, const FieldLayout& L, std::size_t i) {
  if (categorical(f)) return categorical_colour(f.body[i]);
  const Colormap& map =
      f.colouring == Colouring::Diverging ? diverging_colormap() : sequential_colormap();
  const double v = f.value[i];
  return std::isnan(v) ? no_data_colour() : map.at(banded(f, (v - L.vmin) / (L.vmax - L.vmin)));
}

void draw_particles(GlCanvas& c, const FieldImage& f, const FieldLayout& L) {
  // True size, but never below half a pixel so a coarse view still shows them.
  const double radius = std::max(0.5, 0.5 * f.particle_size_m * L.px_per_m);
  std::vector<Point> centres;
  std::vector<Rgb8> colours;
  for (std::size_t i = 0; i < f.x.size(); ++i) {
    const Point p = L.to_pixel(f.x[i], f.y[i]);
    const bool visible = p.x > L.view.x0 - radius && p.x < L.view.x1 + radius &&
                         p.y > L.view.y0 - radius && p.y < L.view.y1 + radius;
    if (!visible) continue;  // culled: only matters for zoomed views
    centres.push_back(p);
    colours.push_back(particle_colour(f, L, i));
  }
  c.fill_discs(centres, radius, colours);
}

void draw_outlines(GlCanvas& c, const FieldImage& f, const FieldLayout& L, double scale) {
  for (const Polyline& line : f.outlines) {
    std::vector<Point> pts;
    for (std::size_t i = 0; i < line.x.size(); ++i)
      if (std::isfinite(line.x[i]) && std::isfinite(line.y[i]))
        pts.push_back(L.to_pixel(line.x[i], line.y[i]));
    c.stroke(pts, line.width_px * scale, line.colour, line.closed);
  }
}

void draw_box(GlCanvas& c, const Rect& r, double w, Rgb8 colour) {
  c.fill_rect({r.x0 - w, r.y0 - w, r.x1 + w, r.y0}, colour);
  c.fill_rect({r.x0 - w, r.y1, r.x1 + w, r.y1 + w}, colour);
  c.fill_rect({r.x0 - w, r.y0, r.x0, r.y1}, colour);
  c.fill_rect({r.x1, r.y0, r.x1 + w, r.y1}, colour);
}

double bar_y(const FieldLayout& L, double shown_value, double unit_scale) {
  const double t = (shown_value / unit_scale - L.vmin) / (L.vmax - L.vmin);
  return L.colour_bar.y1 - t * L.colour_bar.height();
}

// One flat rectangle per pixel row, coloured at the row centre: the bar
// shows exactly the map's colours, bottom = vmin, top = vmax.
void draw_colour_bar(GlCanvas& c, const FieldImage& f, const FieldLayout& L, const FieldStyle& st) {
  const Colormap& map =
      f.colouring == Colouring::Diverging ? diverging_colormap() : sequential_colormap();
  const Rect& b = L.colour_bar;
  for (double y = b.y0; y < b.y1; y += 1.0)
    c.fill_rect({b.x0, y, b.x1, y + 1.0}, map.at(banded(f, (b.y1 - y - 0.5) / b.height())));
  draw_box(c, b, 1.0, kInk);
  for (double v : L.ticks.values) {
    const double y = std::round(bar_y(L, v, f.unit_scale) - 0.5);
    c.fill_rect({b.x1, y, b.x1 + 1.0 + st.tick_length, y + 1.0}, kInk);
  }
}

double legend_row(const FieldLayout& L, const FieldStyle& st, std::size_t k, std::size_t n) {
  const double row = 1.6 * st.swatch;
  return std::round(0.5 * (L.view.y0 + L.view.y1) - 0.5 * row * static_cast<double>(n) +
                    row * static_cast<double>(k));
}

void draw_body_swatches(GlCanvas& c, const FieldImage& f, const FieldLayout& L,
                        const FieldStyle& st) {
  const auto bodies = bodies_present(f);
  const double x0 = L.panel.x0 + 2 * st.gap;
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const double y0 = legend_row(L, st, k, bodies.size());
    c.fill_rect({x0, y0, x0 + st.swatch, y0 + st.swatch}, categorical_colour(bodies[k]));
  }
}

// ---------------------------------------------------------------- text --

std::string time_stamp(double t) {
  std::array<char, 64> text{};
  std::snprintf(text.data(), text.size(), "t = %.3f ms", t * 1e3);
  return text.data();
}

void draw_header(RgbImage& img, const FieldImage& f, const FieldLayout& L, const FieldStyle& st) {
  const int top = static_cast<int>(st.margin);
  draw_text(img, f.title, static_cast<int>(L.view.x0), top, {st.title, kInk, true}, HAlign::Left,
            VAlign::Top);
  if (!std::isnan(f.time_s))
    draw_text(img, time_stamp(f.time_s), static_cast<int>(L.panel.x1), top, {st.stamp, kInk},
              HAlign::Right, VAlign::Top);
  draw_text(img, L.scale_bar_label, static_cast<int>(L.scale_bar.x1 + 1.5 * st.gap),
            static_cast<int>(std::round(0.5 * (L.scale_bar.y0 + L.scale_bar.y1))), {st.tick, kInk},
            HAlign::Left, VAlign::Middle);
}

void draw_colour_bar_text(RgbImage& img, const FieldImage& f, const FieldLayout& L,
                          const FieldStyle& st) {
  const Rect& b = L.colour_bar;
  const int x = static_cast<int>(b.x1 + 1.0 + st.tick_length + st.gap);
  int widest = 0;
  for (double v : L.ticks.values) {
    const std::string s = format_tick(v, L.ticks.step);
    widest = std::max(widest, measure_text(s, {st.tick}).width);
    draw_text(img, s, x, static_cast<int>(std::round(bar_y(L, v, f.unit_scale))), {st.tick, kInk},
              HAlign::Left, VAlign::Middle);
  }
  draw_text(img, colour_bar_title(f), static_cast<int>(x + widest + 1.5 * st.gap),
            static_cast<int>(0.5 * (b.y0 + b.y1)), {st.label, kInk}, HAlign::Centre, VAlign::Top,
            true);
}

void draw_body_names(RgbImage& img, const FieldImage& f, const FieldLayout& L,
                     const FieldStyle& st) {
  const auto bodies = bodies_present(f);
  const int x = static_cast<int>(L.panel.x0 + 3 * st.gap + st.swatch);
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    const double y = legend_row(L, st, k, bodies.size()) + 0.5 * st.swatch;
    draw_text(img, body_name(f, bodies[k]), x, static_cast<int>(y), {st.label, kInk}, HAlign::Left,
              VAlign::Middle);
  }
}

}  // namespace

RgbImage render_field(const FieldImage& f) {
  return render_field_frame(f,
                            [&f](GlCanvas& c, const FieldLayout& L) { draw_particles(c, f, L); });
}

RgbImage render_field_frame(const FieldImage& f, const ViewContent& draw_content) {
  const FieldLayout L = field_layout(f);
  const FieldStyle st(f);
  RgbImage img;
  {
    GlCanvas c(f.width, f.height, f.supersample);
    c.clear(kWhite);
    c.set_clip(L.view);
    draw_content(c, L);
    draw_outlines(c, f, L, st.scale);
    c.clear_clip();
    draw_box(c, L.view, 1.0, kFrame);
    if (categorical(f))
      draw_body_swatches(c, f, L, st);
    else
      draw_colour_bar(c, f, L, st);
    c.fill_rect(L.scale_bar, kInk);
    img = c.resolve();
  }
  draw_header(img, f, L, st);
  if (categorical(f))
    draw_body_names(img, f, L, st);
  else
    draw_colour_bar_text(img, f, L, st);
  return img;
}

std::vector<unsigned char> render_field_png(const FieldImage& f) {
  return encode_png(render_field(f));
}

}  // namespace gearsph::render
