#pragma once
// Text rasterised with FreeType (DejaVu Sans from Debian's fonts-dejavu-core)
// and blended on the CPU into an RgbImage. Grey-scale anti-aliasing, glyph
// origins on whole pixels: the same text always gives the same pixels.
// FreeType objects are per thread (an FT_Library must not be shared between
// threads without a lock), so renders on worker threads do not contend.
#include <string>
#include <string_view>
#include <vector>

#include "render/png_io.hpp"

namespace gearsph::render {

struct TextStyle {
  double size_px = 20.0;  // em size in pixels
  Rgb8 colour{0, 0, 0};
  bool bold = false;
};

enum class HAlign { Left, Centre, Right };
// Vertical anchor: top of the ascender, middle of the capital letters (what
// a tick label is centred on), the baseline, or bottom of the descender.
enum class VAlign { Top, Middle, Baseline, Bottom };

struct TextMetrics {
  int width = 0;       // advance width of the whole string, pixels
  int ascent = 0;      // font ascender above the baseline, pixels
  int descent = 0;     // font descender below the baseline (positive), pixels
  int cap_height = 0;  // height of "H" above the baseline, pixels
  int height() const { return ascent + descent; }
};

TextMetrics measure_text(std::string_view utf8, const TextStyle& style);

// Draws `utf8` so that its (halign, valign) anchor lands on pixel (x, y).
// rotated = true turns the text 90 degrees counter-clockwise (reading
// bottom-to-top, as on a y axis); the anchor is then in the rotated frame,
// e.g. HAlign::Centre + VAlign::Top centres the label along y with its top
// (the ascender side) at column x. Pixels outside the image are clipped.
void draw_text(RgbImage& image, std::string_view utf8, int x, int y, const TextStyle& style,
               HAlign halign = HAlign::Left, VAlign valign = VAlign::Baseline,
               bool rotated = false);

// UTF-8 to code points; malformed sequences become U+FFFD.
std::vector<char32_t> decode_utf8(std::string_view utf8);

}  // namespace gearsph::render
