#pragma once
// Line charts to PNG for histories (probe velocities, contact force, peak
// stress against time): round 1-2-5 ticks, grid, legend, anti-aliased lines.
// Geometry goes through the GL canvas, text through FreeType; deterministic.
// The tick helpers are shared with the field image's colour bar.
#include <optional>
#include <string>
#include <vector>

#include "render/gl_context.hpp"
#include "render/png_io.hpp"

namespace gearsph::render {

struct Range {
  double min = 0, max = 1;
};

// "Nice" numbers: steps of 1, 2 or 5 times a power of ten.
struct Ticks {
  double step = 1;
  std::vector<double> values;  // multiples of step inside [lo, hi]
};
// The 1-2-5 step giving about target_count intervals over `span`.
double nice_step(double span, int target_count);
Ticks nice_ticks(double lo, double hi, int target_count = 6);
// Largest 1-2-5 number not above `limit` (> 0), e.g. for a scale bar.
double nice_floor(double limit);
// Fixed-point text with as many decimals as `step` needs, for display:
// negative numbers get the minus sign U+2212, and "-0" never appears.
std::string format_tick(double value, double step);

struct Series {
  std::string name;
  std::vector<double> x, y;    // NaN in either breaks the line
  std::optional<Rgb8> colour;  // default: categorical colour of its index
};

struct Plot {
  std::string title;
  std::string x_label;  // with units, e.g. "time [ms]"
  std::string y_label;
  std::vector<Series> series;
  std::optional<Range> x_range;  // default: data range
  std::optional<Range> y_range;  // default: data range widened to whole ticks
  int width = 1280, height = 800;
  int supersample = 3;  // anti-aliasing samples per pixel per axis
};

// Where everything lands; exposed so callers and tests can annotate/check.
struct PlotLayout {
  Rect axes;  // plotting area in pixels
  Range x, y;
  Ticks x_ticks, y_ticks;
  int x_exponent = 0, y_exponent = 0;  // tick labels show value / 10^exponent
  Point to_pixel(double x_value, double y_value) const;
};

PlotLayout plot_layout(const Plot& plot);
RgbImage render_plot(const Plot& plot);
std::vector<unsigned char> render_plot_png(const Plot& plot);

}  // namespace gearsph::render
