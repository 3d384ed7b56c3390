// Off-screen rendering: colour maps, text, PNG, field images and plots.
// Pixel checks use the layouts the renderers expose, so they test where
// things land, not hard-coded coordinates. Set GEARSPH_RENDER_SAMPLES to a
// directory to also keep the sample figures (gear field, zoom, plot).
#include <gtest/gtest.h>

#include <algorithm>
#include <barrier>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <numbers>
#include <numeric>
#include <string>
#include <thread>

#include "render/colormap.hpp"
#include "render/field_image.hpp"
#include "render/font.hpp"
#include "render/plot_image.hpp"
#include "render/png_io.hpp"

namespace gearsph::render {
namespace {

constexpr double kPi = std::numbers::pi;

double lightness(Rgb8 c) {
  return rgb8_to_lab(c).L;
}
bool is_white(Rgb8 c) {
  return c == Rgb8{255, 255, 255};
}
bool is_dark(Rgb8 c) {
  return lightness(c) < 50.0;
}
int colour_distance(Rgb8 p, Rgb8 q) {
  return std::max({std::abs(p.r - q.r), std::abs(p.g - q.g), std::abs(p.b - q.b)});
}
Rgb8 pixel_at(const RgbImage& img, Point p) {
  return img.at(static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)));
}
int count_pixels(const RgbImage& img, const Rect& r, const std::function<bool(Rgb8)>& pred) {
  int n = 0;
  for (int y = std::max(0, static_cast<int>(r.y0));
       y < std::min(img.height, static_cast<int>(r.y1)); ++y)
    for (int x = std::max(0, static_cast<int>(r.x0));
         x < std::min(img.width, static_cast<int>(r.x1)); ++x)
      n += pred(img.at(x, y)) ? 1 : 0;
  return n;
}

// ------------------------------------------------------------ colour maps --

TEST(RenderColormap, LabOfKnownColours) {
  const Lab white = rgb8_to_lab({255, 255, 255}), black = rgb8_to_lab({0, 0, 0});
  EXPECT_NEAR(white.L, 100.0, 1e-6);
  EXPECT_NEAR(white.a, 0.0, 1e-6);
  EXPECT_NEAR(white.b, 0.0, 1e-6);
  EXPECT_NEAR(black.L, 0.0, 1e-9);
  // sRGB red, D65: L* 53.24, a* 80.09, b* 67.20 (CIE 15 with IEC 61966-2-1).
  const Lab red = rgb8_to_lab({255, 0, 0});
  EXPECT_NEAR(red.L, 53.24, 0.02);
  EXPECT_NEAR(red.a, 80.09, 0.05);
  EXPECT_NEAR(red.b, 67.20, 0.05);
  EXPECT_FALSE(in_srgb_gamut({50.0, 0.0, -120.0}));
  EXPECT_TRUE(in_srgb_gamut({50.0, 0.0, 0.0}));
}

TEST(RenderColormap, LabRoundTripsEveryMapEntry) {
  for (const Colormap* map : {&sequential_colormap(), &diverging_colormap()})
    for (Rgb8 c : map->lut()) {
      const Lab lab = rgb8_to_lab(c);
      EXPECT_TRUE(in_srgb_gamut(lab));
      const auto back = lab_to_srgb(lab);
      EXPECT_NEAR(back[0] * 255.0, c.r, 1e-6);
      EXPECT_NEAR(back[1] * 255.0, c.g, 1e-6);
      EXPECT_NEAR(back[2] * 255.0, c.b, 1e-6);
    }
}

TEST(RenderColormap, SequentialLightnessStrictlyIncreases) {
  const auto& lut = sequential_colormap().lut();
  ASSERT_EQ(lut.size(), 256u);
  for (std::size_t i = 1; i < lut.size(); ++i)
    EXPECT_GT(lightness(lut[i]), lightness(lut[i - 1])) << "entry " << i;
}

TEST(RenderColormap, SequentialEndpointsDarkBlueToLightYellow) {
  const Lab first = rgb8_to_lab(sequential_colormap().lut().front());
  const Lab last = rgb8_to_lab(sequential_colormap().lut().back());
  EXPECT_NEAR(first.L, 15.0, 0.5);
  EXPECT_NEAR(last.L, 92.0, 0.5);
  EXPECT_LT(first.b, -20.0);  // blue
  EXPECT_GT(last.b, 60.0);    // yellow
  EXPECT_EQ(sequential_colormap().at(0.0), sequential_colormap().lut().front());
  EXPECT_EQ(sequential_colormap().at(1.0), sequential_colormap().lut().back());
  EXPECT_EQ(sequential_colormap().at(7.0), sequential_colormap().lut().back());  // clamped
  EXPECT_EQ(sequential_colormap().at(std::nan("")), no_data_colour());
}

// Equal steps along the map are equal perceived steps: CIE76 distance over
// 16-entry windows (long enough to average out 8-bit rounding) within 15 %.
TEST(RenderColormap, SequentialPerceptuallyUniform) {
  const auto& lut = sequential_colormap().lut();
  std::vector<double> d;
  for (std::size_t i = 0; i + 16 < lut.size(); i += 16)
    d.push_back(delta_e76(rgb8_to_lab(lut[i]), rgb8_to_lab(lut[i + 16])));
  const double mean = std::accumulate(d.begin(), d.end(), 0.0) / static_cast<double>(d.size());
  for (double x : d) EXPECT_NEAR(x / mean, 1.0, 0.15);
}

TEST(RenderColormap, DivergingSymmetricInLightness) {
  const auto& lut = diverging_colormap().lut();
  ASSERT_EQ(lut.size(), 256u);
  for (std::size_t i = 0; i < lut.size() / 2; ++i) {
    // Mirror entries share L* and C* by construction; 8-bit rounding only.
    EXPECT_NEAR(lightness(lut[i]), lightness(lut[lut.size() - 1 - i]), 0.5) << "entry " << i;
    if (i > 0) {
      EXPECT_GT(lightness(lut[i]), lightness(lut[i - 1]) - 0.3) << "entry " << i;
    }
  }
  const Lab centre = rgb8_to_lab(lut[128]), blue = rgb8_to_lab(lut.front()),
            red = rgb8_to_lab(lut.back());
  EXPECT_NEAR(centre.L, 92.0, 0.5);
  EXPECT_LT(std::hypot(centre.a, centre.b), 2.0);  // neutral centre
  EXPECT_LT(blue.b, -30.0);
  EXPECT_GT(red.a, 30.0);
  EXPECT_NEAR(blue.L, 36.0, 0.6);
}

TEST(RenderColormap, CategoricalColoursAreDistinct) {
  const int n = categorical_palette_size();
  ASSERT_GE(n, 6);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < i; ++j)
      EXPECT_GT(delta_e76(rgb8_to_lab(categorical_colour(i)), rgb8_to_lab(categorical_colour(j))),
                25.0)
          << i << " vs " << j;
  EXPECT_EQ(categorical_colour(n), categorical_colour(0));  // repeats
  EXPECT_EQ(categorical_colour(-1), categorical_colour(n - 1));
}

// ------------------------------------------------------------ ticks, units --

TEST(RenderTicks, OneTwoFiveSteps) {
  EXPECT_DOUBLE_EQ(nice_step(10.0, 5), 2.0);
  EXPECT_DOUBLE_EQ(nice_step(0.04, 4), 0.01);
  EXPECT_DOUBLE_EQ(nice_step(330.0, 6), 50.0);
  const Ticks t = nice_ticks(-3.7, 12.2, 6);
  EXPECT_DOUBLE_EQ(t.step, 2.0);
  EXPECT_EQ(t.values, (std::vector<double>{-2, 0, 2, 4, 6, 8, 10, 12}));
  const Ticks small = nice_ticks(0.0, 0.3, 3);
  ASSERT_EQ(small.values.size(), 4u);
  EXPECT_EQ(format_tick(small.values[3], small.step), "0.3");
  EXPECT_EQ(format_tick(-1e-5, 0.1), "0.0");
  EXPECT_EQ(format_tick(250.0, 50.0), "250");
  EXPECT_EQ(format_tick(-0.25, 0.05), "−0.25");
  EXPECT_DOUBLE_EQ(nice_floor(23.0), 20.0);
  EXPECT_DOUBLE_EQ(nice_floor(0.0049), 0.002);
  EXPECT_DOUBLE_EQ(nice_floor(5.0), 5.0);
}

TEST(RenderTicks, EngineeringUnits) {
  const EngineeringUnit mpa = engineering_unit(2.4e8, "Pa");
  EXPECT_EQ(mpa.label, "MPa");
  EXPECT_DOUBLE_EQ(mpa.scale, 1e-6);
  EXPECT_EQ(engineering_unit(3e-4, "m").label, "µm");
  EXPECT_EQ(engineering_unit(0.0, "N").label, "N");
  EXPECT_EQ(format_length(0.01), "10 mm");
  EXPECT_EQ(format_length(5e-5), "50 µm");
}

// -------------------------------------------------------------- text, PNG --

TEST(RenderText, InkStaysInsideItsMeasuredBox) {
  RgbImage img(400, 120);
  const TextStyle style{32.0};
  const TextMetrics m = measure_text("von Mises [MPa]", style);
  draw_text(img, "von Mises [MPa]", 20, 30, style, HAlign::Left, VAlign::Top);
  const Rect box{20, 30, 20.0 + m.width, 30.0 + m.height()};
  EXPECT_GT(count_pixels(img, box, is_dark), 200);
  const Rect all{0, 0, 400, 120};
  EXPECT_EQ(count_pixels(img, all, [](Rgb8 c) { return !is_white(c); }),
            count_pixels(img, {box.x0 - 2, box.y0, box.x1 + 2, box.y1},
                         [](Rgb8 c) { return !is_white(c); }));
  EXPECT_GT(m.width, 150);
  EXPECT_GT(m.cap_height, 18);
}

TEST(RenderText, RotatedTextRunsUpwards) {
  RgbImage img(120, 400);
  draw_text(img, "stress [MPa]", 40, 200, {28.0}, HAlign::Centre, VAlign::Top, true);
  int x0 = 1000, x1 = -1, y0 = 1000, y1 = -1;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (is_dark(img.at(x, y)))
        x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
  EXPECT_GT(y1 - y0, 3 * (x1 - x0));       // tall, not wide
  EXPECT_NEAR(0.5 * (y0 + y1), 200.0, 6);  // centred on the anchor
  EXPECT_GE(x0, 40);                       // ascender side at the anchor column
}

TEST(RenderText, DecodesUtf8) {
  EXPECT_EQ(decode_utf8("aµ×⁻"), (std::vector<char32_t>{U'a', 0xB5, 0xD7, 0x207B}));
  EXPECT_EQ(decode_utf8("\xC3"), (std::vector<char32_t>{0xFFFD}));
  EXPECT_EQ(decode_utf8("\x80x"), (std::vector<char32_t>{0xFFFD, U'x'}));
}

TEST(RenderPng, EncodesAndDecodes) {
  RgbImage img(7, 5, {10, 20, 30});
  img.set(6, 4, {200, 100, 0});
  const auto bytes = encode_png(img);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes[1], 'P');
  const RgbImage back = decode_png(bytes);
  EXPECT_EQ(back.width, 7);
  EXPECT_EQ(back.height, 5);
  EXPECT_EQ(back.rgb, img.rgb);
  const std::vector<unsigned char> junk = {1, 2, 3, 4};
  EXPECT_THROW(decode_png(junk), std::runtime_error);

  const auto path = std::filesystem::temp_directory_path() / "gearsph_render_test.png";
  write_png(path, bytes);
  std::ifstream in(path, std::ios::binary);
  const std::vector<unsigned char> read((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(read, bytes);
  std::filesystem::remove(path);
}

// ----------------------------------------------------------- field images --

FieldImage single_particle(double value) {
  FieldImage f;
  f.x = {0.0};
  f.y = {0.0};
  f.value = {value};
  f.particle_size_m = 0.01;
  f.vmin = 0.0;
  f.vmax = 5e6;  // 5 MPa
  f.field_label = "von Mises stress";
  f.unit_label = "MPa";
  f.unit_scale = 1e-6;
  f.title = "one particle";
  f.time_s = 0.012345;
  return f;
}

TEST(RenderField, BigParticleShowsTopColourOnWhite) {
  const FieldImage f = single_particle(5e6);
  const FieldLayout L = field_layout(f);
  const RgbImage img = render_field(f);
  ASSERT_EQ(img.width, 1280);
  ASSERT_EQ(img.height, 800);
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.0, 0.0)), sequential_colormap().lut().back());
  EXPECT_TRUE(is_white(img.at(0, 0)));
  EXPECT_TRUE(is_white(img.at(img.width - 1, img.height - 1)));
  // The disc is "true size": its diameter in pixels is dx * px_per_m.
  const Point c = L.to_pixel(0.0, 0.0);
  const double r = 0.005 * L.px_per_m;
  EXPECT_EQ(pixel_at(img, {c.x + r - 2, c.y}), sequential_colormap().lut().back());
  EXPECT_TRUE(is_white(pixel_at(img, {c.x + r + 2, c.y})) || !L.view.contains({c.x + r + 2, c.y}));
}

TEST(RenderField, ColourBarRunsDarkToLightBottomToTop) {
  const FieldImage f = single_particle(1e6);
  const FieldLayout L = field_layout(f);
  const RgbImage img = render_field(f);
  const Rect& b = L.colour_bar;
  ASSERT_GT(b.height(), 200);
  const double x = 0.5 * (b.x0 + b.x1);
  double previous = -1.0;
  for (double y = b.y1 - 1; y >= b.y0; y -= 1.0) {
    const double l = lightness(pixel_at(img, {x, y}));
    EXPECT_GE(l, previous) << "row " << y;
    previous = l;
  }
  EXPECT_EQ(pixel_at(img, {x, b.y1 - 1}), sequential_colormap().lut().front());
  EXPECT_EQ(pixel_at(img, {x, b.y0}), sequential_colormap().lut().back());
  // Ticks 0..5 MPa in 1 MPa steps, labels right of the bar.
  EXPECT_EQ(L.ticks.values.front(), 0.0);
  EXPECT_EQ(L.ticks.values.back(), 5.0);
  const Rect labels{b.x1 + 4, b.y0 - 15, L.panel.x1, b.y1 + 15};
  EXPECT_GT(count_pixels(img, labels, is_dark), 300);
}

TEST(RenderField, ZoomShowsExactlyTheWindow) {
  FieldImage f = single_particle(5e6);
  f.x = {0.010, 0.030, 0.060};  // inside, inside, outside the window
  f.y = {0.010, 0.010, 0.010};
  f.value = {5e6, 0.0, 2.5e6};
  f.particle_size_m = 0.004;
  f.zoom = Window{0.0, 0.0, 0.04, 0.02};
  const FieldLayout L = field_layout(f);
  EXPECT_NEAR(L.view.width() / L.view.height(), 2.0, 0.01);
  EXPECT_NEAR(L.world.x0, 0.0, 1.0 / L.px_per_m);
  EXPECT_NEAR(L.world.x1, 0.04, 1.0 / L.px_per_m);
  EXPECT_NEAR(L.world.y1, 0.02, 1.0 / L.px_per_m);
  const Point corner = L.to_pixel(0.0, 0.0);
  EXPECT_NEAR(corner.x, L.view.x0, 1.0);
  EXPECT_NEAR(corner.y, L.view.y1, 1.0);
  const RgbImage img = render_field(f);
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.010, 0.010)), sequential_colormap().lut().back());
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.030, 0.010)), sequential_colormap().lut().front());
  EXPECT_TRUE(is_white(pixel_at(img, L.to_pixel(0.020, 0.018))));
  // The particle outside the window leaves no trace in the panel beyond it.
  const Point outside = L.to_pixel(0.060, 0.010);
  EXPECT_FALSE(L.view.contains(outside));
  const Rgb8 mid = sequential_colormap().at(0.5);
  EXPECT_EQ(count_pixels(img, {L.view.x1 + 1, L.view.y0, L.colour_bar.x0 - 1, L.view.y1},
                         [&](Rgb8 c) { return c == mid; }),
            0);
}

TEST(RenderField, ScaleBarLengthMatchesItsLabel) {
  FieldImage f = single_particle(1e6);
  f.zoom = Window{-0.03, -0.02, 0.03, 0.02};
  const FieldLayout L = field_layout(f);
  const RgbImage img = render_field(f);
  EXPECT_EQ(L.scale_bar_label, "10 mm");  // 20 % of 60 mm, rounded down to 1-2-5
  EXPECT_DOUBLE_EQ(L.scale_bar_m, 0.01);
  const int row = static_cast<int>(0.5 * (L.scale_bar.y0 + L.scale_bar.y1));
  int run = 0, longest = 0;
  for (int x = 0; x < img.width; ++x) {
    run = is_dark(img.at(x, row)) && lightness(img.at(x, row)) < 20 ? run + 1 : 0;
    longest = std::max(longest, run);
  }
  EXPECT_NEAR(longest, L.scale_bar_m * L.px_per_m, 1.0);
  // Its label is drawn to the right of the bar.
  EXPECT_GT(
      count_pixels(
          img, {L.scale_bar.x1 + 2, L.scale_bar.y0 - 12, L.scale_bar.x1 + 120, L.scale_bar.y1 + 12},
          is_dark),
      50);
}

TEST(RenderField, TitleAndTimeStampAreDrawn) {
  const FieldImage f = single_particle(1e6);
  const FieldLayout L = field_layout(f);
  const RgbImage img = render_field(f);
  const Rect title{L.view.x0, 0, L.view.x0 + 250, L.view.y0 - 2};
  const Rect stamp{L.panel.x1 - 250, 0, L.panel.x1, L.view.y0 - 2};
  EXPECT_GT(count_pixels(img, title, is_dark), 150);
  EXPECT_GT(count_pixels(img, stamp, is_dark), 150);
  FieldImage untimed = f;
  untimed.time_s = std::nan("");
  EXPECT_EQ(count_pixels(render_field(untimed), stamp, is_dark), 0);
}

TEST(RenderField, CategoricalBodiesDivergingRangeAndNaN) {
  FieldImage f = single_particle(0.0);
  f.x = {0.0, 0.02};
  f.y = {0.0, 0.0};
  f.body = {0, 1};
  f.body_names = {"pinion", "rack"};
  f.colouring = FieldImage::Colouring::Categorical;
  FieldLayout L = field_layout(f);
  RgbImage img = render_field(f);
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.0, 0.0)), categorical_colour(0));
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.02, 0.0)), categorical_colour(1));
  EXPECT_GT(count_pixels(img, L.panel, [](Rgb8 c) { return c == categorical_colour(1); }), 100);

  f.colouring = FieldImage::Colouring::Diverging;
  f.value = {-1e6, std::nan("")};
  f.vmin.reset();
  f.vmax.reset();
  L = field_layout(f);
  EXPECT_DOUBLE_EQ(L.vmin, -1e6);
  EXPECT_DOUBLE_EQ(L.vmax, 1e6);
  img = render_field(f);
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.0, 0.0)), diverging_colormap().lut().front());
  EXPECT_EQ(pixel_at(img, L.to_pixel(0.02, 0.0)), no_data_colour());
}

TEST(RenderField, RejectsInconsistentInput) {
  FieldImage f = single_particle(1e6);
  f.value = {};
  EXPECT_THROW(field_layout(f), std::invalid_argument);
  f = single_particle(1e6);
  f.particle_size_m = 0.0;
  EXPECT_THROW(field_layout(f), std::invalid_argument);
  f = single_particle(1e6);
  f.vmin = 2e6;
  f.vmax = 1e6;
  EXPECT_THROW(field_layout(f), std::invalid_argument);
  f = single_particle(1e6);
  f.zoom = Window{0.0, 0.0, 0.0, 1.0};
  EXPECT_THROW(field_layout(f), std::invalid_argument);
  f = single_particle(1e6);
  f.outlines.push_back({{0.0, 1.0}, {0.0}, {}, false, 1.0});
  EXPECT_THROW(field_layout(f), std::invalid_argument);
}

TEST(RenderField, PngDecodesToTheSamePixels) {
  FieldImage f = single_particle(2e6);
  f.width = 640;
  f.height = 400;
  const auto bytes = render_field_png(f);
  const RgbImage back = decode_png(bytes);
  EXPECT_EQ(back.width, 640);
  EXPECT_EQ(back.height, 400);
  EXPECT_EQ(back.rgb, render_field(f).rgb);
  EXPECT_EQ(render_field_png(f), bytes);  // deterministic
}

long resident_megabytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6)) / 1024;
  return -1;
}

// Mesa 22.3's OSMesa leaks a context's framebuffer when it is rebound at
// another size; the renderer must not (gl_context.cpp). One leaked 1280 x 800
// x 3^2 buffer would be 37 MB, so 6 size changes stay far below 100 MB.
TEST(RenderField, SizeChangesDoNotLeakFramebuffers) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "ASan's quarantine keeps freed buffers resident";
#endif
  FieldImage f = single_particle(1e6);
  render_field(f);
  const long before = resident_megabytes();
  for (int k = 0; k < 6; ++k) {
    f.width = k % 2 ? 1280 : 1240;
    render_field(f);
  }
  EXPECT_LT(resident_megabytes() - before, 100);
}

// ------------------------------------------------------------------ plots --

Plot line_plot() {
  Plot p;
  p.title = "a line";
  p.x_label = "time [ms]";
  p.y_label = "velocity [m/s]";
  Series s{"y = 2x", {}, {}, {}};
  for (int i = 0; i <= 100; ++i) {
    s.x.push_back(0.1 * i);
    s.y.push_back(0.2 * i);
  }
  p.series.push_back(s);
  return p;
}

TEST(RenderPlot, AxesTicksAndSeriesWhereExpected) {
  const Plot p = line_plot();
  const PlotLayout L = plot_layout(p);
  const RgbImage img = render_plot(p);
  EXPECT_TRUE(L.x_ticks.step == 1.0 || L.x_ticks.step == 2.0) << L.x_ticks.step;
  EXPECT_EQ(L.x_ticks.values.front(), 0.0);
  EXPECT_EQ(L.x_ticks.values.back(), 10.0);
  // The series passes through (5, 10) and (2, 4).
  for (double x : {2.0, 5.0})
    EXPECT_LT(colour_distance(pixel_at(img, L.to_pixel(x, 2 * x)), categorical_colour(0)), 8);
  // Frame left of the axes, tick marks below them, labels below the ticks.
  const double mid_y = 0.5 * (L.axes.y0 + L.axes.y1);
  EXPECT_TRUE(is_dark(pixel_at(img, {L.axes.x0 - 1, mid_y})));
  for (double v : L.x_ticks.values) {
    const Point t = L.to_pixel(v, L.y.min);
    EXPECT_TRUE(is_dark(pixel_at(img, {t.x, t.y + 5}))) << "tick at " << v;
    EXPECT_GT(count_pixels(img, {t.x - 20, t.y + 12, t.x + 20, t.y + 45}, is_dark), 20)
        << "label at " << v;
  }
  // Grid lines: light grey on a tick position away from the line.
  const Point g = L.to_pixel(8.0, 2.7);
  const Rgb8 grid = pixel_at(img, g);
  EXPECT_FALSE(is_white(grid));
  EXPECT_GT(lightness(grid), 80.0);
  EXPECT_TRUE(is_white(pixel_at(img, {g.x + 10, g.y})));
}

TEST(RenderPlot, NaNBreaksTheLine) {
  Plot p = line_plot();
  for (double& y : p.series[0].y) y = 1.0;
  for (int i = 41; i < 60; ++i) p.series[0].y[static_cast<std::size_t>(i)] = std::nan("");
  p.y_range = Range{0.0, 2.0};
  const PlotLayout L = plot_layout(p);
  const RgbImage img = render_plot(p);
  EXPECT_LT(colour_distance(pixel_at(img, L.to_pixel(2.0, 1.0)), categorical_colour(0)), 8);
  EXPECT_GT(colour_distance(pixel_at(img, L.to_pixel(5.0, 1.0)), categorical_colour(0)), 100);
}

TEST(RenderPlot, LegendShowsEverySeriesColour) {
  Plot p = line_plot();
  p.series.push_back({"second", {0, 10}, {20, 0}, {}});
  p.series.push_back({"third", {0, 10}, {5, 5}, {}});
  const RgbImage img = render_plot(p);
  const PlotLayout L = plot_layout(p);
  for (int k = 0; k < 3; ++k)
    EXPECT_GT(count_pixels(img, L.axes,
                           [&](Rgb8 c) { return colour_distance(c, categorical_colour(k)) < 6; }),
              200)
        << "series " << k;
}

TEST(RenderPlot, LargeValuesGetAnExponent) {
  Plot p = line_plot();
  for (double& y : p.series[0].y) y *= 1e8;
  const PlotLayout L = plot_layout(p);
  EXPECT_EQ(L.y_exponent, 9);
  EXPECT_EQ(L.x_exponent, 0);
  Plot bad = line_plot();
  bad.series[0].y.pop_back();
  EXPECT_THROW(plot_layout(bad), std::invalid_argument);
}

// ------------------------------------------------- synthetic gear samples --

// A pinion (12 teeth, module 4 mm) meshing with a rack, on a 1 mm lattice,
// with a stress-like field: a contact peak where they touch, bending
// stress at the loaded tooth's root, and a mild background.
constexpr double kModule = 0.004, kTeeth = 12, kDx = 0.001;
constexpr double kPitchRadius = 0.5 * kModule * kTeeth;

// Trapezoidal teeth: full height within +-0.12 of a pitch around the tooth
// centre, down to the root at +-0.30 (about half a pitch thick at the pitch
// line, as real teeth are). phase in [-0.5, 0.5] pitches from a tooth centre.
double tooth_height_fraction(double phase) {
  return std::clamp((0.30 - std::abs(phase)) / 0.18, 0.0, 1.0);
}

// One pinion tooth points straight down (theta = -pi/2) into the rack gap
// at x = 0; the centre sits a little high so the trapezoids do not overlap.
constexpr double kCentreY = kPitchRadius + 0.4 * kModule;

double pinion_radius(double theta) {
  const double phase = std::remainder((theta + kPi / 2) * kTeeth / (2 * kPi), 1.0);
  return kPitchRadius - 1.25 * kModule + 2.25 * kModule * tooth_height_fraction(phase);
}

// Rack teeth centred at p/2 + k p, addendum m above the pitch line y = 0.
double rack_top(double x) {
  const double phase = std::remainder(x / (kPi * kModule) - 0.5, 1.0);
  return -1.25 * kModule + 2.25 * kModule * tooth_height_fraction(phase);
}

double stress_like(double x, double y) {
  auto bump = [](double dx, double dy, double s) {
    return std::exp(-(dx * dx + dy * dy) / (2 * s * s));
  };
  return 4.2e8 * bump(x - 0.0026, y - 0.0003, 0.0015) +  // contact on the right flank
         1.6e8 * bump(x + 0.0030, y - 0.0068, 0.0018) +  // root of the loaded tooth
         0.4e8 * (1.0 + std::sin(180.0 * x) * std::cos(140.0 * (y - kCentreY)));
}

FieldImage gear_field() {
  FieldImage f;
  const double cy = kCentreY;
  for (double x = -0.045; x <= 0.045; x += kDx)
    for (double y = -0.016; y <= 0.056; y += kDx) {
      const double r = std::hypot(x, y - cy), theta = std::atan2(y - cy, x);
      const int body = r < pinion_radius(theta) ? 0 : (y > -0.015 && y < rack_top(x) ? 1 : -1);
      if (body < 0 || (body == 0 && r < 0.006)) continue;  // bore of the pinion
      f.x.push_back(x);
      f.y.push_back(y);
      f.body.push_back(body);
      f.value.push_back(stress_like(x, y));
    }
  Polyline pinion{{}, {}, {20, 20, 20}, true, 1.5};
  for (int k = 0; k < 720; ++k) {
    const double t = 2 * kPi * k / 720;
    pinion.x.push_back(pinion_radius(t) * std::cos(t));
    pinion.y.push_back(cy + pinion_radius(t) * std::sin(t));
  }
  Polyline rack{{-0.0455}, {-0.0155}, {20, 20, 20}, true, 1.5};
  for (double x = -0.0455; x <= 0.0455; x += 0.00025) {
    rack.x.push_back(x);
    rack.y.push_back(rack_top(x));
  }
  rack.x.push_back(0.0455);
  rack.y.push_back(-0.0155);
  f.outlines = {pinion, rack};
  f.particle_size_m = kDx;
  f.field_label = "von Mises stress";
  const EngineeringUnit u = engineering_unit(4.6e8, "Pa");
  f.unit_label = u.label;
  f.unit_scale = u.scale;
  f.title = "Rack and pinion, von Mises stress";
  f.time_s = 0.012345;
  f.body_names = {"pinion", "rack"};
  return f;
}

Plot velocity_plot() {
  Plot p;
  p.title = "Probe velocities";
  p.x_label = "time [ms]";
  p.y_label = "velocity [m/s]";
  const char* names[] = {"pinion tooth tip", "pinion hub", "rack back"};
  for (int k = 0; k < 3; ++k) {
    Series s{names[k], {}, {}, {}};
    for (int i = 0; i <= 2000; ++i) {
      const double t = 40.0 * i / 2000;  // ms
      const double ramp = 0.353 * (1.0 - std::exp(-t / (3.0 + 2.0 * k)));
      s.x.push_back(t);
      s.y.push_back(ramp + 0.05 / (1 + k) * std::exp(-t / 15.0) * std::sin(2.2 * t + k));
    }
    p.series.push_back(s);
  }
  return p;
}

void keep_sample(const std::string& name, const std::vector<unsigned char>& png) {
  if (const char* dir = std::getenv("GEARSPH_RENDER_SAMPLES")) {
    std::filesystem::create_directories(dir);
    write_png(std::filesystem::path(dir) / name, png);
  }
}

TEST(RenderSamples, GearFieldZoomBodiesAndPlot) {
  FieldImage f = gear_field();
  EXPECT_GT(f.x.size(), 1800u);
  const auto full = render_field_png(f);
  keep_sample("gear_von_mises.png", full);
  FieldImage zoom = f;
  zoom.zoom = Window{-0.012, -0.008, 0.012, 0.008};
  zoom.title = "Meshing zone";
  keep_sample("gear_von_mises_zoom.png", render_field_png(zoom));
  FieldImage bodies = f;
  bodies.colouring = FieldImage::Colouring::Categorical;
  bodies.title = "Bodies";
  keep_sample("gear_bodies.png", render_field_png(bodies));
  FieldImage signed_field = f;
  signed_field.colouring = FieldImage::Colouring::Diverging;
  for (std::size_t i = 0; i < f.x.size(); ++i)
    signed_field.value[i] = 2e-5 * std::sin(150.0 * f.x[i]) * (f.y[i] + 0.016) / 0.07;
  const EngineeringUnit um = engineering_unit(2e-5, "m");
  signed_field.field_label = "displacement x";
  signed_field.unit_label = um.label;
  signed_field.unit_scale = um.scale;
  signed_field.title = "Displacement, x component";
  keep_sample("gear_displacement_x.png", render_field_png(signed_field));
  keep_sample("probe_velocities.png", render_plot_png(velocity_plot()));
  Plot peak{"Peak stress", "time [ms]", "max von Mises stress [Pa]", {}, {}, {}};
  Series pinion{"pinion", {}, {}, {}}, rack{"rack", {}, {}, {}};
  for (int i = 0; i <= 400; ++i) {
    const double t = 0.1 * i, mesh = std::pow(std::sin(kPi * t / 12.0), 2);
    pinion.x.push_back(t);
    pinion.y.push_back(4.2e8 * mesh * (1.0 - std::exp(-t / 4.0)));
    rack.x.push_back(t);
    rack.y.push_back(3.1e8 * mesh * (1.0 - std::exp(-t / 4.0)));
  }
  peak.series = {pinion, rack};
  const auto peak_png = render_plot_png(peak);
  EXPECT_EQ(plot_layout(peak).y_exponent, 6);
  keep_sample("peak_stress.png", peak_png);
  const RgbImage img = decode_png(full);
  EXPECT_EQ(img.width, 1280);
  EXPECT_EQ(img.height, 800);
}

// -------------------------------------------------------------- threading --

// Each thread has its own GL context and FreeType library: renders running
// at the same time must give the same bytes as one after another.
TEST(RenderThreads, ParallelRenderingEqualsSerial) {
  std::vector<std::function<std::vector<unsigned char>()>> jobs;
  jobs.emplace_back([] { return render_field_png(gear_field()); });
  jobs.emplace_back([] {
    FieldImage f = gear_field();
    f.zoom = Window{-0.012, -0.008, 0.012, 0.008};
    return render_field_png(f);
  });
  jobs.emplace_back([] { return render_plot_png(velocity_plot()); });
  jobs.emplace_back([] {
    FieldImage f = gear_field();
    f.colouring = FieldImage::Colouring::Categorical;
    f.width = 900;
    return render_field_png(f);
  });
  std::vector<std::vector<unsigned char>> serial;
  for (auto& job : jobs) serial.push_back(job());

  std::vector<std::vector<unsigned char>> parallel(jobs.size());
  std::barrier start(static_cast<std::ptrdiff_t>(jobs.size()));
  std::vector<std::thread> threads;
  for (std::size_t k = 0; k < jobs.size(); ++k)
    threads.emplace_back([&, k] {
      start.arrive_and_wait();  // all render at the same time
      for (int repeat = 0; repeat < 2; ++repeat) parallel[k] = jobs[k]();
    });
  for (auto& t : threads) t.join();
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    EXPECT_EQ(parallel[k], serial[k]) << "image " << k;
    EXPECT_NO_THROW(decode_png(parallel[k]));
  }
}

}  // namespace
}  // namespace gearsph::render
