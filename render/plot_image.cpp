#include "render/plot_image.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "render/colormap.hpp"
#include "render/font.hpp"

namespace gearsph::render {

// ---------------------------------------------------------------- ticks --

double nice_step(double span, int target_count) {
  const double raw = std::abs(span) / std::max(target_count, 1);
  if (!(raw > 0.0) || !std::isfinite(raw)) return 1.0;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double r = raw / magnitude;
  // Round the mantissa to 1, 2, 5 or 10 at the geometric-ish midpoints.
  const double mantissa = r < 1.5 ? 1.0 : r < 3.5 ? 2.0 : r < 7.5 ? 5.0 : 10.0;
  return mantissa * magnitude;
}

Ticks nice_ticks(double lo, double hi, int target_count) {
  if (hi < lo) std::swap(lo, hi);
  Ticks t;
  t.step = nice_step(hi - lo, target_count);
  // Integer multiples, not accumulated sums: no drift like 0.30000000000000004.
  const double slack = 1e-9 * t.step;
  const auto first = static_cast<long long>(std::ceil((lo - slack) / t.step));
  const auto last = static_cast<long long>(std::floor((hi + slack) / t.step));
  for (long long i = first; i <= last; ++i) t.values.push_back(static_cast<double>(i) * t.step);
  return t;
}

double nice_floor(double limit) {
  if (!(limit > 0.0)) throw std::invalid_argument("nice_floor: limit must be positive");
  const double magnitude = std::pow(10.0, std::floor(std::log10(limit) + 1e-12));
  const double r = limit / magnitude;
  return (r >= 5.0 - 1e-9 ? 5.0 : r >= 2.0 - 1e-9 ? 2.0 : 1.0) * magnitude;
}

std::string format_tick(double value, double step) {
  const int decimals = std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
  std::array<char, 64> text{};
  std::snprintf(text.data(), text.size(), "%.*f", decimals, value);
  std::string s(text.data());
  if (s.front() != '-') return s;
  if (s.find_first_not_of("-0.") == std::string::npos) return s.substr(1);  // no "-0.0"
  return "−" + s.substr(1);  // typographic minus sign, as in print
}

namespace {

// ---------------------------------------------------------------- layout --

struct PlotStyle {
  double scale;                       // 1 at 1280 x 800
  double title, label, tick, legend;  // font sizes, px
  double margin, gap, tick_length, line_width, frame_width;
  explicit PlotStyle(const Plot& p)
      : scale(std::sqrt(p.width * static_cast<double>(p.height) / (1280.0 * 800.0))),
        title(30 * scale),
        label(26 * scale),
        tick(23 * scale),
        legend(23 * scale),
        margin(24 * scale),
        gap(8 * scale),
        tick_length(8 * scale),
        line_width(2.75 * scale),
        frame_width(std::max(1.0, std::round(1.5 * scale))) {}
};

const Rgb8 kInk{34, 34, 34};
const Rgb8 kGrid{222, 222, 222};
const Rgb8 kLegendBorder{190, 190, 190};

Range data_range(const std::vector<Series>& series, bool use_x) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Series& s : series)
    for (double v : use_x ? s.x : s.y)
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  if (!std::isfinite(lo)) return {0.0, 1.0};
  if (lo == hi) {
    const double d = lo != 0.0 ? 0.05 * std::abs(lo) : 1.0;
    return {lo - d, hi + d};
  }
  return {lo, hi};
}

// Tick labels show value / 10^exponent when plain numbers would get long.
int axis_exponent(const Ticks& t) {
  double m = 0.0;
  for (double v : t.values) m = std::max(m, std::abs(v));
  if (m == 0.0 || (m >= 1e-2 && m < 1e4)) return 0;
  return 3 * static_cast<int>(std::floor(std::log10(m) / 3.0));
}

std::string tick_label(double v, const Ticks& t, int exponent) {
  const double f = std::pow(10.0, exponent);
  return format_tick(v / f, t.step / f);
}

std::string superscript(int n) {
  static const char* digits[] = {"⁰", "¹", "²", "³", "⁴", "⁵", "⁶", "⁷", "⁸", "⁹"};
  std::string out = n < 0 ? "⁻" : "";
  for (char c : std::to_string(std::abs(n))) out += digits[c - '0'];
  return out;
}

int widest_label(const Ticks& t, int exponent, const TextStyle& style) {
  int w = 0;
  for (double v : t.values) w = std::max(w, measure_text(tick_label(v, t, exponent), style).width);
  return w;
}

void check_series(const Series& s) {
  if (s.x.size() != s.y.size())
    throw std::invalid_argument("plot series \"" + s.name + "\": x and y differ in length");
}

// x: the data range as is (time axes start and end where the run does);
// y: the data range plus 5 % each side, keeping lines off the frame.
void set_ranges(PlotLayout& L, const Plot& plot) {
  L.x = plot.x_range.value_or(data_range(plot.series, true));
  if (plot.y_range) {
    L.y = *plot.y_range;
  } else {
    const Range d = data_range(plot.series, false);
    const double pad = 0.05 * (d.max - d.min);
    L.y = {d.min - pad, d.max + pad};
  }
  if (!(L.x.max > L.x.min) || !(L.y.max > L.y.min))
    throw std::invalid_argument("plot: axis range must have max > min");
}

// Margins from the text they hold; y ticks first (their labels set the left
// margin), x ticks once the axes width is known. About one tick per 90 px
// of height and per 150 px of width.
void place_axes(PlotLayout& L, const Plot& plot, const PlotStyle& st) {
  const TextStyle tick_style{st.tick};
  const int tick_h = measure_text("0", tick_style).height();
  const int label_h = measure_text("Ag", {st.label}).height();
  const double top =
      st.margin +
      (plot.title.empty() ? 0.0 : measure_text("Ag", {st.title, kInk, true}).height() + st.gap);
  const double bottom =
      st.margin + (plot.x_label.empty() ? 0 : label_h + st.gap) + tick_h + st.gap + st.tick_length;
  const double axes_height = plot.height - top - bottom;
  L.y_ticks = nice_ticks(L.y.min, L.y.max, std::clamp(static_cast<int>(axes_height / 90.0), 3, 10));
  L.y_exponent = axis_exponent(L.y_ticks);
  const double left = st.margin + (plot.y_label.empty() ? 0 : label_h + st.gap) +
                      widest_label(L.y_ticks, L.y_exponent, tick_style) + st.gap + st.tick_length;
  const double right = st.margin + 0.5 * measure_text("0.000", tick_style).width;
  L.axes = {std::round(left), std::round(top), std::round(plot.width - right),
            std::round(plot.height - bottom)};
  if (L.axes.width() < 50 || L.axes.height() < 50)
    throw std::invalid_argument("plot: image too small for axes and labels");
  L.x_ticks =
      nice_ticks(L.x.min, L.x.max, std::clamp(static_cast<int>(L.axes.width() / 150.0), 3, 12));
  L.x_exponent = axis_exponent(L.x_ticks);
}

}  // namespace

Point PlotLayout::to_pixel(double x_value, double y_value) const {
  return {axes.x0 + (x_value - x.min) / (x.max - x.min) * axes.width(),
          axes.y1 - (y_value - y.min) / (y.max - y.min) * axes.height()};
}

PlotLayout plot_layout(const Plot& plot) {
  for (const Series& s : plot.series) check_series(s);
  PlotLayout L;
  set_ranges(L, plot);
  place_axes(L, plot, PlotStyle(plot));
  return L;
}

namespace {

// ------------------------------------------------------------- geometry --

// A whole-pixel-wide line at the pixel nearest `x` (crisp after resolve).
Rect vertical_line(double x, double y0, double y1, double width) {
  const double x0 = std::round(x - 0.5 * width);
  return {x0, y0, x0 + std::max(1.0, std::round(width)), y1};
}
Rect horizontal_line(double y, double x0, double x1, double width) {
  const double y0 = std::round(y - 0.5 * width);
  return {x0, y0, x1, y0 + std::max(1.0, std::round(width))};
}

void draw_grid(GlCanvas& c, const PlotLayout& L) {
  for (double v : L.x_ticks.values)
    c.fill_rect(vertical_line(L.to_pixel(v, 0).x, L.axes.y0, L.axes.y1, 1.0), kGrid);
  for (double v : L.y_ticks.values)
    c.fill_rect(horizontal_line(L.to_pixel(0, v).y, L.axes.x0, L.axes.x1, 1.0), kGrid);
}

// Runs of finite points in pixels; points closer than a fifth of a pixel to
// the last kept one are dropped (invisible, and keeps long histories cheap;
// spikes survive because they move far in y).
std::vector<std::vector<Point>> pixel_runs(const Series& s, const PlotLayout& L) {
  std::vector<std::vector<Point>> runs(1);
  for (std::size_t i = 0; i < s.x.size(); ++i) {
    if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
      if (!runs.back().empty()) runs.emplace_back();
      continue;
    }
    const Point p = L.to_pixel(s.x[i], s.y[i]);
    auto& run = runs.back();
    const bool last = i + 1 == s.x.size();
    if (run.empty() || last || std::hypot(p.x - run.back().x, p.y - run.back().y) >= 0.2)
      run.push_back(p);
  }
  return runs;
}

Rgb8 series_colour(const Plot& plot, std::size_t k) {
  return plot.series[k].colour.value_or(categorical_colour(static_cast<int>(k)));
}

void draw_series(GlCanvas& c, const Plot& plot, const PlotLayout& L, double width) {
  c.set_clip(L.axes);
  for (std::size_t k = 0; k < plot.series.size(); ++k)
    for (const auto& run : pixel_runs(plot.series[k], L))
      c.stroke(run, width, series_colour(plot, k));
  c.clear_clip();
}

void draw_frame_and_ticks(GlCanvas& c, const PlotLayout& L, const PlotStyle& st) {
  const Rect& a = L.axes;
  const double w = st.frame_width;
  c.fill_rect({a.x0 - w, a.y0 - w, a.x1 + w, a.y0}, kInk);
  c.fill_rect({a.x0 - w, a.y1, a.x1 + w, a.y1 + w}, kInk);
  c.fill_rect({a.x0 - w, a.y0, a.x0, a.y1}, kInk);
  c.fill_rect({a.x1, a.y0, a.x1 + w, a.y1}, kInk);
  for (double v : L.x_ticks.values)
    c.fill_rect(vertical_line(L.to_pixel(v, 0).x, a.y1, a.y1 + w + st.tick_length, w), kInk);
  for (double v : L.y_ticks.values)
    c.fill_rect(horizontal_line(L.to_pixel(0, v).y, a.x0 - w - st.tick_length, a.x0, w), kInk);
}

// -------------------------------------------------------------- legend --

struct LegendBox {
  Rect box;
  double row_height, sample_length, pad;
};

LegendBox legend_box(const Plot& plot, const PlotLayout& L, const PlotStyle& st) {
  int name_width = 0;
  for (const Series& s : plot.series)
    name_width = std::max(name_width, measure_text(s.name, {st.legend}).width);
  LegendBox lb{{}, 1.6 * st.legend, 2.0 * st.legend, 0.6 * st.legend};
  const double w = 2 * lb.pad + lb.sample_length + st.gap + name_width;
  const double h = 2 * lb.pad + lb.row_height * static_cast<double>(plot.series.size());
  const double inset = 1.5 * st.gap;
  // Corners in order of preference; the one covering the fewest data points wins.
  const Rect& a = L.axes;
  const std::array<Point, 4> corners = {
      Point{a.x1 - inset - w, a.y0 + inset}, Point{a.x0 + inset, a.y0 + inset},
      Point{a.x1 - inset - w, a.y1 - inset - h}, Point{a.x0 + inset, a.y1 - inset - h}};
  std::size_t best_count = std::numeric_limits<std::size_t>::max();
  for (const Point& c : corners) {
    const Rect r{std::round(c.x), std::round(c.y), std::round(c.x + w), std::round(c.y + h)};
    std::size_t count = 0;
    for (const Series& s : plot.series)
      for (const auto& run : pixel_runs(s, L))
        count += static_cast<std::size_t>(
            std::count_if(run.begin(), run.end(), [&](Point p) { return r.contains(p); }));
    if (count < best_count) best_count = count, lb.box = r;
  }
  return lb;
}

bool has_legend(const Plot& plot) {
  return std::any_of(plot.series.begin(), plot.series.end(),
                     [](const Series& s) { return !s.name.empty(); });
}

void draw_legend_geometry(GlCanvas& c, const Plot& plot, const LegendBox& lb, double width) {
  const Rect& b = lb.box;
  c.fill_rect({b.x0 - 1, b.y0 - 1, b.x1 + 1, b.y1 + 1}, kLegendBorder);
  c.fill_rect(b, {255, 255, 255});
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const double y = b.y0 + lb.pad + (static_cast<double>(k) + 0.5) * lb.row_height;
    const std::array<Point, 2> line = {Point{b.x0 + lb.pad, y},
                                       Point{b.x0 + lb.pad + lb.sample_length, y}};
    c.stroke(line, width, series_colour(plot, k));
  }
}

// ---------------------------------------------------------------- text --

void draw_axis_text(RgbImage& img, const Plot& plot, const PlotLayout& L, const PlotStyle& st) {
  const TextStyle tick{st.tick, kInk}, label{st.label, kInk};
  const Rect& a = L.axes;
  const int below = static_cast<int>(a.y1 + st.frame_width + st.tick_length + st.gap);
  for (double v : L.x_ticks.values)
    draw_text(img, tick_label(v, L.x_ticks, L.x_exponent), static_cast<int>(L.to_pixel(v, 0).x),
              below, tick, HAlign::Centre, VAlign::Top);
  const int left_of = static_cast<int>(a.x0 - st.frame_width - st.tick_length - st.gap);
  for (double v : L.y_ticks.values)
    draw_text(img, tick_label(v, L.y_ticks, L.y_exponent), left_of,
              static_cast<int>(std::round(L.to_pixel(0, v).y)), tick, HAlign::Right,
              VAlign::Middle);
  if (L.y_exponent != 0)
    draw_text(img, "×10" + superscript(L.y_exponent), static_cast<int>(a.x0),
              static_cast<int>(a.y0 - st.gap), tick, HAlign::Left, VAlign::Bottom);
  if (L.x_exponent != 0)
    draw_text(img, "×10" + superscript(L.x_exponent), static_cast<int>(a.x1),
              static_cast<int>(below + measure_text("0", tick).height()), tick, HAlign::Right,
              VAlign::Top);
  draw_text(img, plot.x_label, static_cast<int>(0.5 * (a.x0 + a.x1)),
            static_cast<int>(plot.height - st.margin), label, HAlign::Centre, VAlign::Bottom);
  draw_text(img, plot.y_label, static_cast<int>(st.margin), static_cast<int>(0.5 * (a.y0 + a.y1)),
            label, HAlign::Centre, VAlign::Top, true);
  draw_text(img, plot.title, static_cast<int>(0.5 * (a.x0 + a.x1)), static_cast<int>(st.margin),
            {st.title, kInk, true}, HAlign::Centre, VAlign::Top);
}

void draw_legend_text(RgbImage& img, const Plot& plot, const LegendBox& lb, const PlotStyle& st) {
  for (std::size_t k = 0; k < plot.series.size(); ++k) {
    const double y = lb.box.y0 + lb.pad + (static_cast<double>(k) + 0.5) * lb.row_height;
    draw_text(img, plot.series[k].name,
              static_cast<int>(lb.box.x0 + lb.pad + lb.sample_length + st.gap),
              static_cast<int>(std::round(y)), {st.legend, kInk}, HAlign::Left, VAlign::Middle);
  }
}

}  // namespace

RgbImage render_plot(const Plot& plot) {
  const PlotLayout L = plot_layout(plot);
  const PlotStyle st(plot);
  const bool legend = has_legend(plot);
  const LegendBox lb = legend ? legend_box(plot, L, st) : LegendBox{};
  RgbImage img;
  {
    GlCanvas c(plot.width, plot.height, plot.supersample);
    c.clear({255, 255, 255});
    draw_grid(c, L);
    draw_series(c, plot, L, st.line_width);
    draw_frame_and_ticks(c, L, st);
    if (legend) draw_legend_geometry(c, plot, lb, st.line_width);
    img = c.resolve();
  }
  draw_axis_text(img, plot, L, st);
  if (legend) draw_legend_text(img, plot, lb, st);
  return img;
}

std::vector<unsigned char> render_plot_png(const Plot& plot) {
  return encode_png(render_plot(plot));
}

}  // namespace gearsph::render
