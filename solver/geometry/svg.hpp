#pragma once
// A plain SVG picture of outlines and particle points, for a person to look
// at: y up, drawn to scale (px_per_mm), with a millimetre scale bar and a
// title. Coordinates come in metres.
#include <string>
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

struct SvgPolyline {
  std::vector<Point> points;
  std::string colour = "#222222";
  bool closed = true;
  double width_px = 1.0;
};

struct SvgDots {
  std::vector<Point> points;
  std::string colour = "#1f77b4";
  double radius_m = 0.0;  // 0: a fixed 1.5 px dot
};

struct SvgDrawing {
  std::string title;
  std::vector<SvgPolyline> lines;
  std::vector<SvgDots> dots;
  double px_per_mm = 20.0;
  double margin_px = 24.0;  // blank border around the drawing
};

std::string svg_document(const SvgDrawing& drawing);
// Throws std::runtime_error when the file cannot be written.
void write_svg(const std::string& path, const SvgDrawing& drawing);

}  // namespace gearsph::geometry
