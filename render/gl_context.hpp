#pragma once
// OpenGL drawing off screen through OSMesa (Debian libosmesa6, llvmpipe).
//
// One OSMesa context per thread (thread_local, created on first use), so
// worker threads render in parallel without sharing GL state. A GlCanvas
// draws filled shapes in image pixel coordinates (origin top-left, y down)
// into a framebuffer `supersample` times larger in each direction, then
// averages each supersample x supersample block in linear light: anti-aliased
// edges, and bit-identical output for identical input (llvmpipe rasterises
// deterministically, the average is integer arithmetic).
// A new image size replaces the thread's context (Mesa 22.3 leaks the old
// framebuffer otherwise, see gl_context.cpp), so keep sizes steady when
// rendering many frames. llvmpipe starts its own rasteriser threads per
// context (LP_NUM_THREADS, default: all cores).
#include <cstdint>
#include <span>
#include <vector>

#include "render/png_io.hpp"

namespace gearsph::render {

class Colormap;

struct Point {
  double x = 0, y = 0;
};

// Axis-aligned rectangle in pixels, [x0, x1) x [y0, y1).
struct Rect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
  bool contains(Point p) const { return p.x >= x0 && p.x < x1 && p.y >= y0 && p.y < y1; }
};

class GlCanvas {
 public:
  // Makes this thread's context current on a (width*supersample) x
  // (height*supersample) buffer. Only one canvas per thread at a time.
  GlCanvas(int width, int height, int supersample);
  ~GlCanvas();
  GlCanvas(const GlCanvas&) = delete;
  GlCanvas& operator=(const GlCanvas&) = delete;

  int width() const { return width_; }
  int height() const { return height_; }

  void clear(Rgb8 colour);
  // Later shapes are drawn only inside `clip` (GL scissor, whole pixels).
  void set_clip(const Rect& clip);
  void clear_clip();

  void fill_rect(const Rect& r, Rgb8 colour);
  // Filled circles of one radius, centres in pixels, one colour each;
  // drawn in order, so later discs cover earlier ones.
  void fill_discs(std::span<const Point> centres, double radius_px, std::span<const Rgb8> colours);
  // A line of the given width with round joins and caps.
  void stroke(std::span<const Point> points, double width_px, Rgb8 colour, bool closed = false);
  void fill_triangle(Point a, Point b, Point c, Rgb8 colour);
  // Triangles (three vertices each) coloured through `map` by a value t per
  // vertex (0: the map's first colour, 1: its last), interpolated across
  // each triangle and looked up per pixel (a 1D texture), so the colours
  // are the map's own, not blends of the corners' colours; t outside [0, 1]
  // takes the end colours. bands > 0: that many flat bands of the map
  // (filled contours), else continuous colours.
  void fill_mapped_triangles(std::span<const Point> vertices, std::span<const float> t,
                             const Colormap& map, int bands = 0);

  // Finishes drawing and returns the anti-aliased image.
  RgbImage resolve();

 private:
  void push(Point p, Rgb8 c);
  void push_disc(Point centre, double radius_px, Rgb8 colour);
  void flush();

  int width_, height_, supersample_;
  std::vector<float> xy_;  // pending triangle vertices
  std::vector<std::uint8_t> rgb_;
};

}  // namespace gearsph::render
