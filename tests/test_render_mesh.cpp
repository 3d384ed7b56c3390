// A scalar field on triangles (render/mesh_image.hpp): colours come from
// the map at the value interpolated to each pixel (not blended corner
// colours), in flat bands when asked, clamped beyond the range; edges,
// outlines and no-data triangles drawn. Pixel checks go through the layout.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>

#include "render/colormap.hpp"
#include "render/fillet_plot.hpp"
#include "render/mesh_image.hpp"

namespace gearsph::render {
namespace {

int colour_distance(Rgb8 p, Rgb8 q) {
  return std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
}

Rgb8 pixel_at(const RgbImage& img, Point p) {
  return img.at(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)));
}

// The square [0, 1] x [0, 1] cm in two triangles, value v = x / 1 cm.
MeshImage square() {
  MeshImage m;
  m.x = {0.0, 0.01, 0.01, 0.0};
  m.y = {0.0, 0.0, 0.01, 0.01};
  m.value = {0.0, 1.0, 1.0, 0.0};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  m.vmin = 0.0;
  m.vmax = 1.0;
  m.field_label = "value";
  m.supersample = 1;
  return m;
}

TEST(RenderMesh, ColoursFollowTheMapAtTheInterpolatedValue) {
  const MeshImage m = square();
  const FieldLayout L = mesh_layout(m);
  const RgbImage img = render_mesh(m);
  const Colormap& map = sequential_colormap();
  for (double t : {0.1, 0.3, 0.5, 0.7, 0.9}) {
    for (double y : {0.2, 0.5, 0.8}) {  // both triangles, the same value down a column
      const Rgb8 c = pixel_at(img, L.to_pixel(0.01 * t, 0.01 * y));
      EXPECT_LE(colour_distance(c, map.at(t)), 3) << "t " << t << " y " << y;
    }
  }
  // Interpolating the corners' colours instead would put the middle on the
  // straight line between the map's ends in RGB, far from its own colour.
  const Rgb8 lo = map.at(0.0), hi = map.at(1.0);
  const Rgb8 blend{static_cast<std::uint8_t>((lo.r + hi.r) / 2),
                   static_cast<std::uint8_t>((lo.g + hi.g) / 2),
                   static_cast<std::uint8_t>((lo.b + hi.b) / 2)};
  EXPECT_GT(colour_distance(map.at(0.5), blend), 20);
}

TEST(RenderMesh, BandsAreFlatAndValuesBeyondTheRangeTakeTheEndColours) {
  MeshImage m = square();
  m.bands = 4;
  m.vmin = 0.25;  // the left quarter is below the range
  m.vmax = 0.75;  // the right quarter above
  const FieldLayout L = mesh_layout(m);
  const RgbImage img = render_mesh(m);
  const Colormap& map = sequential_colormap();
  std::set<std::tuple<int, int, int>> seen;
  for (int k = 1; k < 40; ++k) {
    const Rgb8 c = pixel_at(img, L.to_pixel(0.01 * k / 40.0, 0.005));
    seen.insert({c.r, c.g, c.b});
  }
  EXPECT_LE(seen.size(), 4u + 3u);  // four bands, a few anti-aliased band edges at most
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.001, 0.005)), map.at(0.125));
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.0099, 0.005)), map.at(0.875));
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.0045, 0.005)), map.at(0.375));
  // The colour bar shows the same bands.
  const Rect& b = L.colour_bar;
  const double x = 0.5 * (b.x0 + b.x1);
  EXPECT_EQ(pixel_at(img, {x, b.y1 - 0.1 * b.height()}), map.at(0.125));
  EXPECT_EQ(pixel_at(img, {x, b.y0 + 0.1 * b.height()}), map.at(0.875));
}

TEST(RenderMesh, NoDataEdgesAndOutlines) {
  MeshImage m = square();
  m.value[3] = std::numeric_limits<double>::quiet_NaN();  // the upper-left triangle
  m.edges = {{0, 2}};                                     // the diagonal
  m.edge_width_px = 4.0;
  m.edge_colour = {255, 0, 0};
  Polyline frame;
  frame.x = {0.0, 0.01, 0.01, 0.0};
  frame.y = {0.0, 0.0, 0.01, 0.01};
  frame.colour = {0, 0, 255};
  frame.width_px = 4.0;
  m.outlines = {frame};
  const FieldLayout L = mesh_layout(m);
  const RgbImage img = render_mesh(m);
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.002, 0.008)), no_data_colour());
  EXPECT_NE(pixel_at(img, L.to_pixel(0.008, 0.002)), no_data_colour());
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.005, 0.005)), (Rgb8{255, 0, 0}));
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.005, 0.0)), (Rgb8{0, 0, 255}));
}

TEST(RenderMesh, DivergingRangeIsSymmetricAndBadInputIsRefused) {
  MeshImage m = square();
  m.vmin.reset();
  m.vmax.reset();
  m.value = {-1.0, 3.0, 3.0, -1.0};
  m.diverging = true;
  const FieldLayout L = mesh_layout(m);
  EXPECT_DOUBLE_EQ(L.vmin, -3.0);
  EXPECT_DOUBLE_EQ(L.vmax, 3.0);
  const RgbImage img = render_mesh(m);
  // Value 0 (a quarter of the way across) on the map's neutral centre.
  EXPECT_LE(colour_distance(pixel_at(img, L.to_pixel(0.0025, 0.005)), diverging_colormap().at(0.5)),
            3);
  MeshImage bad = square();
  bad.triangles.push_back({0, 1, 7});
  EXPECT_THROW(render_mesh(bad), std::invalid_argument);
  bad = square();
  bad.value.pop_back();
  EXPECT_THROW(render_mesh(bad), std::invalid_argument);
  bad = square();
  bad.bands = -1;
  EXPECT_THROW(render_mesh(bad), std::invalid_argument);
}

}  // namespace
}  // namespace gearsph::render

// The static check's fillet curves as a picture: SPH alone, and with the FE
// curves beside them (render/fillet_plot.hpp).
TEST(FilletPlot, DrawsTheCurvesWithAndWithoutFe) {
  const nlohmann::json sc = {
      {"load_radius_m", 0.024},
      {"fillet_curves",
       {{"tension", {{"arc_m", {0.0, 0.001, 0.002}}, {"sigma1_Pa", {1e7, 4e7, 2e7}}}},
        {"compression", {{"arc_m", {0.0, 0.001, 0.002}}, {"sigma3_Pa", {-1e7, -4e7, -2e7}}}}}}};
  const nlohmann::json fe = {{"meshes",
                              {{{"arc_m", {0.0, 0.002}},
                                {"tension_sigma1_Pa", {1e7, 2e7}},
                                {"compression_sigma3_Pa", {-1e7, -2e7}}}}}};
  const std::vector<unsigned char> alone = gearsph::render::fillet_plot_png(sc, nullptr);
  const std::vector<unsigned char> both = gearsph::render::fillet_plot_png(sc, fe);
  ASSERT_GT(alone.size(), 1000u);
  EXPECT_EQ(alone[1], 'P');  // \x89PNG
  EXPECT_NE(alone, both);
}
