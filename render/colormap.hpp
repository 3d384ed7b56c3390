#pragma once
// Colour maps computed here from their design in CIELAB, not copied tables:
//  - sequential: lightness L* rises linearly-in-arc-length from dark violet
//    blue through teal and green to light yellow, for magnitudes (von Mises);
//  - diverging: blue - light grey - red with L* symmetric about the centre,
//    for signed fields (displacement components, pressure);
//  - categorical: well separated colours for bodies and plot series.
// Colour science: IEC 61966-2-1 (sRGB), CIE 15:2004 (CIELAB, D65 white).
#include <array>
#include <cstddef>
#include <vector>

#include "render/png_io.hpp"

namespace gearsph::render {

struct Lab {
  double L = 0, a = 0, b = 0;
};

// sRGB component (0..1, gamma encoded) <-> linear light (0..1).
double srgb_to_linear(double c);
double linear_to_srgb(double c);

Lab srgb_to_lab(const std::array<double, 3>& srgb01);
Lab rgb8_to_lab(Rgb8 c);
// Gamma-encoded sRGB in 0..1 per channel; may lie outside 0..1 when the Lab
// colour is outside the sRGB gamut (see in_srgb_gamut).
std::array<double, 3> lab_to_srgb(const Lab& lab);
bool in_srgb_gamut(const Lab& lab);
// CIE 1976 colour difference (Euclidean distance in L*a*b*).
double delta_e76(const Lab& p, const Lab& q);

// A colour map as a lookup table of 8-bit sRGB colours; t in [0, 1] picks the
// nearest entry (t is clamped; NaN gives no_data_colour()).
class Colormap {
 public:
  explicit Colormap(std::vector<Rgb8> lut);
  Rgb8 at(double t) const;
  const std::vector<Rgb8>& lut() const { return lut_; }
  std::size_t size() const { return lut_.size(); }

 private:
  std::vector<Rgb8> lut_;
};

// 256-entry maps, computed once per process on first use (thread-safe).
const Colormap& sequential_colormap();
const Colormap& diverging_colormap();
// Colour k of the categorical palette (k >= 0; the palette repeats after
// categorical_palette_size() colours).
Rgb8 categorical_colour(int k);
int categorical_palette_size();
// Particles whose value is NaN: a neutral mid grey that no map contains.
Rgb8 no_data_colour();

}  // namespace gearsph::render
