#pragma once
// A particle field as a figure: every particle a filled disc of its true
// size (diameter = spacing) coloured by a field, outlines on top, a labelled
// colour bar (or a body legend), a scale bar, title and time stamp.
// Plain data in, PNG out: no dependency on the solver's classes.
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "render/gl_context.hpp"
#include "render/plot_image.hpp"
#include "render/png_io.hpp"

namespace gearsph::render {

// A world-space window [m].
struct Window {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

struct Polyline {
  std::vector<double> x, y;  // [m]
  Rgb8 colour{0, 0, 0};
  bool closed = true;
  double width_px = 1.5;
};

struct FieldImage {
  int width = 1280, height = 800;
  std::vector<double> x, y;    // particle centres [m]
  std::vector<double> value;   // field value per particle, SI (unused if Categorical)
  std::vector<int> body;       // body index per particle (used if Categorical)
  double particle_size_m = 0;  // spacing dx: discs of diameter dx ("true size")
  std::string field_label;     // e.g. "von Mises stress"
  std::string unit_label;      // e.g. "MPa"
  double unit_scale = 1.0;     // shown number = value * unit_scale (1e-6 for MPa)
  // Colour range in SI. Default: data min/max ignoring NaN/inf; for a
  // Diverging map +-max|value|, so zero sits on the neutral centre colour.
  std::optional<double> vmin, vmax;
  enum class Colouring { Sequential, Diverging, Categorical };
  Colouring colouring = Colouring::Sequential;
  int bands = 0;  // > 0: the map in that many flat bands (filled contours), bar included
  std::vector<std::string> body_names;  // legend for Categorical; default "body k"
  std::vector<Polyline> outlines;       // drawn on top, e.g. pinion and rack outlines
  std::string title;
  double time_s = 0;           // shown as "t = 12.345 ms"; NaN hides it
  std::optional<Window> zoom;  // show exactly this window; default: all particles
  int supersample = 3;         // anti-aliasing samples per pixel per axis
};

// Where everything lands; exposed so callers and tests can annotate/check.
struct FieldLayout {
  Rect view;     // pixels showing `world`, same scale in x and y
  Window world;  // [m]
  double px_per_m = 1;
  double vmin = 0, vmax = 1;  // colour range, SI
  Rect panel;                 // right of the view: colour bar with labels, or body legend
  Rect colour_bar;            // empty for Categorical
  Ticks ticks;                // colour-bar ticks, in displayed units
  Rect scale_bar;
  double scale_bar_m = 0;
  std::string scale_bar_label;  // e.g. "10 mm"
  Point to_pixel(double x_m, double y_m) const;
};

FieldLayout field_layout(const FieldImage& image);
RgbImage render_field(const FieldImage& image);
// The same figure with other content in the view: `draw_content` draws
// into the view (cleared to white, clipped to it) before the outlines go on
// top. render_field draws the particles; render_mesh (mesh_image.hpp) a
// shaded triangle field. image.x, y and value still choose the window and
// the colour range.
using ViewContent = std::function<void(GlCanvas&, const FieldLayout&)>;
RgbImage render_field_frame(const FieldImage& image, const ViewContent& draw_content);
std::vector<unsigned char> render_field_png(const FieldImage& image);

// An SI prefix with an exponent that is a multiple of 3 for values up to
// max_abs, e.g. (2.4e8, "Pa") -> {"MPa", 1e-6}, (3e-4, "m") -> {"µm", 1e6}.
struct EngineeringUnit {
  std::string label;
  double scale = 1.0;
};
EngineeringUnit engineering_unit(double max_abs, std::string_view si_unit);

// "12.345 mm", "50 µm": a length with the unit that keeps it readable.
std::string format_length(double metres);

}  // namespace gearsph::render
