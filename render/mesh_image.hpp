#pragma once
// A scalar field on triangles as a figure: the triangles filled with the
// value interpolated linearly inside each one and coloured per pixel through
// the colour map (smooth, or in flat bands: filled contours), optional
// edges, outlines on top, and the same colour bar, scale bar, title and time
// stamp as the particle figures of field_image.hpp.
//
// Any triangulation will do: the sub-triangles of a finite-element mesh, or
// a triangulation of particles clipped to a body's outline (a particle field
// drawn as contours). Plain data in, PNG out.
#include <array>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "render/field_image.hpp"

namespace gearsph::render {

struct MeshImage {
  int width = 1280, height = 800;
  std::vector<double> x, y;                   // vertices [m]
  std::vector<std::array<int, 3>> triangles;  // vertex indices
  std::vector<double> value;                  // per vertex, SI; NaN: no data (grey triangles)
  std::string field_label;                    // e.g. "von Mises stress"
  std::string unit_label;                     // e.g. "MPa"
  double unit_scale = 1.0;                    // shown number = value * unit_scale
  // Colour range in SI; values beyond it take the end colours. Default: the
  // finite data's range; diverging: +-max|value| (zero on the neutral colour).
  std::optional<double> vmin, vmax;
  bool diverging = false;
  int bands = 0;  // > 0: that many flat colour bands (filled contours); 0: continuous
  // Lines drawn over the field (vertex index pairs), e.g. element edges.
  std::vector<std::array<int, 2>> edges;
  double edge_width_px = 1.0;
  Rgb8 edge_colour{90, 90, 90};
  std::vector<Polyline> outlines;  // on top of everything, e.g. the body's outline
  std::string title;
  double time_s = std::numeric_limits<double>::quiet_NaN();  // shown unless NaN
  std::optional<Window> zoom;                                // default: all vertices and outlines
  int supersample = 3;
};

FieldLayout mesh_layout(const MeshImage& image);
RgbImage render_mesh(const MeshImage& image);
std::vector<unsigned char> render_mesh_png(const MeshImage& image);

}  // namespace gearsph::render
