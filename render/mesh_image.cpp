#include "render/mesh_image.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/colormap.hpp"

namespace gearsph::render {

namespace {

void validate(const MeshImage& m) {
  const std::size_t n = m.x.size();
  if (m.y.size() != n || m.value.size() != n)
    throw std::invalid_argument("mesh image: need x, y and a value for every vertex");
  auto bad = [n](int v) { return v < 0 || static_cast<std::size_t>(v) >= n; };
  for (const auto& t : m.triangles)
    if (bad(t[0]) || bad(t[1]) || bad(t[2]))
      throw std::invalid_argument("mesh image: a triangle names a vertex that does not exist");
  for (const auto& e : m.edges)
    if (bad(e[0]) || bad(e[1]))
      throw std::invalid_argument("mesh image: an edge names a vertex that does not exist");
  if (m.bands < 0) throw std::invalid_argument("mesh image: bands must not be negative");
}

// The field figure's frame for this mesh: vertices as (point-sized)
// particles choose the window and the colour range.
FieldImage frame_of(const MeshImage& m) {
  validate(m);
  FieldImage f;
  f.width = m.width;
  f.height = m.height;
  f.x = m.x;
  f.y = m.y;
  f.value = m.value;
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
  if (!m.x.empty()) {
    const auto [xa, xb] = std::minmax_element(m.x.begin(), m.x.end());
    const auto [ya, yb] = std::minmax_element(m.y.begin(), m.y.end());
    x0 = *xa, x1 = *xb, y0 = *ya, y1 = *yb;
  }
  // A vertex is a point: a size far below a pixel only keeps it positive.
  f.particle_size_m = 1e-9 * std::max({x1 - x0, y1 - y0, 1e-9});
  f.field_label = m.field_label;
  f.unit_label = m.unit_label;
  f.unit_scale = m.unit_scale;
  f.vmin = m.vmin;
  f.vmax = m.vmax;
  f.colouring = m.diverging ? FieldImage::Colouring::Diverging : FieldImage::Colouring::Sequential;
  f.bands = m.bands;
  f.outlines = m.outlines;
  f.title = m.title;
  f.time_s = m.time_s;
  f.zoom = m.zoom;
  f.supersample = m.supersample;
  return f;
}

void draw_mesh(GlCanvas& c, const MeshImage& m, const FieldLayout& L) {
  std::vector<Point> pixel(m.x.size());
  for (std::size_t i = 0; i < m.x.size(); ++i) pixel[i] = L.to_pixel(m.x[i], m.y[i]);
  std::vector<Point> corners;
  std::vector<float> t;
  std::vector<std::array<int, 3>> no_data;
  const double span = L.vmax - L.vmin;
  for (const auto& tri : m.triangles) {
    const bool finite = std::all_of(tri.begin(), tri.end(), [&m](int v) {
      return std::isfinite(m.value[static_cast<std::size_t>(v)]);
    });
    if (!finite) {
      no_data.push_back(tri);
      continue;
    }
    for (int v : tri) {
      const auto k = static_cast<std::size_t>(v);
      corners.push_back(pixel[k]);
      t.push_back(static_cast<float>((m.value[k] - L.vmin) / span));
    }
  }
  c.fill_mapped_triangles(corners, t, m.diverging ? diverging_colormap() : sequential_colormap(),
                          m.bands);
  for (const auto& tri : no_data) {
    c.fill_triangle(pixel[static_cast<std::size_t>(tri[0])],
                    pixel[static_cast<std::size_t>(tri[1])],
                    pixel[static_cast<std::size_t>(tri[2])], no_data_colour());
  }
  // Edges as thin quads (no caps: joins of hairlines do not show).
  const double half = 0.5 * m.edge_width_px;
  for (const auto& e : m.edges) {
    const Point a = pixel[static_cast<std::size_t>(e[0])],
                b = pixel[static_cast<std::size_t>(e[1])];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len == 0.0) continue;
    const double nx = -(b.y - a.y) / len * half, ny = (b.x - a.x) / len * half;
    c.fill_triangle({a.x + nx, a.y + ny}, {b.x + nx, b.y + ny}, {b.x - nx, b.y - ny},
                    m.edge_colour);
    c.fill_triangle({a.x + nx, a.y + ny}, {b.x - nx, b.y - ny}, {a.x - nx, a.y - ny},
                    m.edge_colour);
  }
}

}  // namespace

FieldLayout mesh_layout(const MeshImage& m) {
  return field_layout(frame_of(m));
}

RgbImage render_mesh(const MeshImage& m) {
  return render_field_frame(frame_of(m),
                            [&m](GlCanvas& c, const FieldLayout& L) { draw_mesh(c, m, L); });
}

std::vector<unsigned char> render_mesh_png(const MeshImage& m) {
  return encode_png(render_mesh(m));
}

}  // namespace gearsph::render
