#include "render/colormap.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <stdexcept>

namespace gearsph::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Chromaticities of the sRGB primaries and of the D65 white (IEC 61966-2-1).
// The RGB -> XYZ matrix is derived from them, so white maps to Y = 1.
Eigen::Matrix3d rgb_to_xyz_matrix() {
  const double xy[4][2] = {{0.64, 0.33}, {0.30, 0.60}, {0.15, 0.06}, {0.3127, 0.3290}};
  auto xyz = [&](int k) {
    return Eigen::Vector3d(xy[k][0] / xy[k][1], 1.0, (1.0 - xy[k][0] - xy[k][1]) / xy[k][1]);
  };
  Eigen::Matrix3d primaries;
  primaries << xyz(0), xyz(1), xyz(2);
  const Eigen::Vector3d scale = primaries.partialPivLu().solve(xyz(3));
  return primaries * scale.asDiagonal();
}

struct ColourSpace {
  Eigen::Matrix3d rgb_to_xyz = rgb_to_xyz_matrix();
  Eigen::Matrix3d xyz_to_rgb = rgb_to_xyz.inverse();
  Eigen::Vector3d white = rgb_to_xyz * Eigen::Vector3d::Ones();
};

const ColourSpace& space() {
  static const ColourSpace s;
  return s;
}

// CIE 15:2004 eq. 8.1: the cube-root compression with its linear toe.
constexpr double kEpsilon = 6.0 / 29.0;
double lab_f(double t) {
  return t > kEpsilon * kEpsilon * kEpsilon ? std::cbrt(t)
                                            : t / (3.0 * kEpsilon * kEpsilon) + 4.0 / 29.0;
}
double lab_f_inverse(double f) {
  return f > kEpsilon ? f * f * f : 3.0 * kEpsilon * kEpsilon * (f - 4.0 / 29.0);
}

Lab lch(double L, double C, double h_deg) {
  return {L, C * std::cos(h_deg * kDegree), C * std::sin(h_deg * kDegree)};
}

// Largest chroma at (L, h) still inside the sRGB gamut, by bisection: along a
// ray of constant L and h the gamut is one interval starting at the grey axis.
double max_chroma(double L, double h_deg) {
  double lo = 0.0, hi = 200.0;
  for (int i = 0; i < 50; ++i) {
    const double mid = 0.5 * (lo + hi);
    (in_srgb_gamut(lch(L, mid, h_deg)) ? lo : hi) = mid;
  }
  return lo;
}

std::uint8_t to_byte(double c01) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(c01, 0.0, 1.0) * 255.0));
}

Rgb8 to_rgb8(const Lab& lab) {
  const auto c = lab_to_srgb(lab);
  return {to_byte(c[0]), to_byte(c[1]), to_byte(c[2])};
}

using LabPath = std::function<Lab(double)>;

// Samples `path` at n points equally spaced in CIE76 arc length, so equal
// steps along the map are (approximately) equal perceived steps.
std::vector<Lab> sample_uniformly(const LabPath& path, int n) {
  constexpr int kFine = 4096;
  std::vector<double> arc(kFine + 1, 0.0);
  Lab prev = path(0.0);
  for (int k = 1; k <= kFine; ++k) {
    const Lab cur = path(static_cast<double>(k) / kFine);
    arc[k] = arc[k - 1] + delta_e76(prev, cur);
    prev = cur;
  }
  std::vector<Lab> out;
  for (int i = 0; i < n; ++i) {
    const double target = arc.back() * i / (n - 1);
    const auto it = std::lower_bound(arc.begin() + 1, arc.end() - 1, target);
    const int k = static_cast<int>(it - arc.begin());
    const double w = (target - arc[k - 1]) / std::max(arc[k] - arc[k - 1], 1e-300);
    out.push_back(path((k - 1 + std::clamp(w, 0.0, 1.0)) / kFine));
  }
  return out;
}

// Rounds to 8 bits but keeps L* strictly increasing. Where the map's L*
// steps (~0.3) are finer than one green code (~0.3 L* near green), plain
// rounding can step back, so each entry is the code within +-2 per channel
// nearest to its target with L* above the previous entry's. Errors in L*
// count three times: fine L* corrections then come from red and blue codes,
// and the entries do not drift above their targets.
double weighted_distance(const Lab& p, const Lab& q) {
  constexpr double kLightnessWeight = 3.0;
  const double dL = kLightnessWeight * (p.L - q.L);
  return dL * dL + (p.a - q.a) * (p.a - q.a) + (p.b - q.b) * (p.b - q.b);
}

Rgb8 nearest_code_above(const Lab& target, double min_L) {
  const Rgb8 centre = to_rgb8(target);
  Rgb8 best = centre;
  double best_d = std::numeric_limits<double>::infinity();
  for (int dr = -2; dr <= 2; ++dr)
    for (int dg = -2; dg <= 2; ++dg)
      for (int db = -2; db <= 2; ++db) {
        const Rgb8 c{static_cast<std::uint8_t>(std::clamp(centre.r + dr, 0, 255)),
                     static_cast<std::uint8_t>(std::clamp(centre.g + dg, 0, 255)),
                     static_cast<std::uint8_t>(std::clamp(centre.b + db, 0, 255))};
        const Lab lab = rgb8_to_lab(c);
        if (lab.L > min_L && weighted_distance(lab, target) < best_d) {
          best_d = weighted_distance(lab, target);
          best = c;
        }
      }
  if (!std::isfinite(best_d)) throw std::logic_error("colour map: L* cannot increase here");
  return best;
}

std::vector<Rgb8> quantize_increasing_lightness(const std::vector<Lab>& labs) {
  std::vector<Rgb8> lut;
  double last_L = -1.0;
  for (const Lab& target : labs) {
    lut.push_back(nearest_code_above(target, last_L));
    last_L = rgb8_to_lab(lut.back()).L;
  }
  return lut;
}

// Sequential design: L* 15 -> 92 while the hue turns from violet-blue
// (290 deg) through blue, teal and green to yellow (98 deg); chroma grows
// towards the light end and is held at 92 % of the gamut limit where needed
// (the blue-teal middle, where sRGB has little chroma at these lightnesses).
// The top stops at L* 92 because above it the yellow gamut narrows so fast
// that the last steps would change chroma only, not lightness.
Lab sequential_design(double s) {
  const double L = 15.0 + 77.0 * s;
  const double h = 290.0 - 192.0 * s;
  const double C = std::min(30.0 + 50.0 * s * s, 0.92 * max_chroma(L, h));
  return lch(L, C, h);
}

// Diverging design, s = distance from the centre in [0, 1]: L* 92 -> 36 and
// chroma 0 -> C_end on both sides, so the two halves differ only in hue and
// the lightness is symmetric by construction. Chroma C_end * s^0.6 rises
// monotonically; C_end is the largest value that keeps both hues inside 95 %
// of the gamut all the way. The blue hue turns from 262 deg (near white) to
// 285 deg (dark end) because at one CIELAB hue angle light blues look
// lavender and dark ones greenish (the known blue non-uniformity of CIELAB).
constexpr double kCentreL = 92.0, kEndL = 36.0;
double diverging_L(double s) {
  return kCentreL - (kCentreL - kEndL) * s;
}
double diverging_s(double L) {
  return (kCentreL - L) / (kCentreL - kEndL);
}
double blue_hue(double s) {
  return 262.0 + 23.0 * s;
}
constexpr double kRedHue = 35.0;
constexpr double kChromaExponent = 0.6;

double diverging_end_chroma() {
  double c_end = 1e300;
  for (int k = 1; k <= 200; ++k) {
    const double s = k / 200.0;
    const double limit =
        std::min(max_chroma(diverging_L(s), blue_hue(s)), max_chroma(diverging_L(s), kRedHue));
    c_end = std::min(c_end, 0.95 * limit / std::pow(s, kChromaExponent));
  }
  return c_end;
}

std::vector<Rgb8> build_diverging(int n) {
  const int half = n / 2;  // n even: entries half-1-i and half+i mirror each other
  const double c_end = diverging_end_chroma();
  // Arc length in (L*, C*) only (hue 0 stands in for both): both halves get
  // the same spacing and stay mirror images in L* and C*. Entry i of a half
  // sits (i + 1/2) steps from the centre, i.e. at odd samples of a path
  // sampled at every half step.
  const auto path = sample_uniformly(
      [c_end](double s) { return lch(diverging_L(s), c_end * std::pow(s, kChromaExponent), 0.0); },
      2 * half + 1);
  std::vector<Rgb8> lut(n);
  for (int i = 0; i < half; ++i) {
    const Lab& p = path[2 * i + 1];  // a = chroma, b = 0
    const double s = diverging_s(p.L);
    lut[half - 1 - i] = to_rgb8(lch(p.L, p.a, blue_hue(s)));
    lut[half + i] = to_rgb8(lch(p.L, p.a, kRedHue));
  }
  return lut;
}

// Categorical palette: greedy farthest-point selection (max of the minimum
// CIE76 distance to the colours already chosen) over in-gamut candidates of
// moderate lightness, so every colour reads on white and against the others.
std::vector<Rgb8> build_categorical(int n) {
  std::vector<Lab> candidates;
  for (double L = 42.0; L <= 68.0; L += 2.0)
    for (double h = 0.0; h < 360.0; h += 5.0)
      for (double C = 40.0; C <= 80.0; C += 10.0)
        if (in_srgb_gamut(lch(L, C, h))) candidates.push_back(lch(L, C, h));
  std::vector<Lab> chosen{lch(48.0, 50.0, 270.0)};  // start with a medium blue
  while (static_cast<int>(chosen.size()) < n) {
    const Lab* best = nullptr;
    double best_d = -1.0;
    for (const Lab& c : candidates) {
      double d = 1e300;
      for (const Lab& q : chosen) d = std::min(d, delta_e76(c, q));
      if (d > best_d) best_d = d, best = &c;
    }
    chosen.push_back(*best);
  }
  std::vector<Rgb8> out;
  for (const Lab& c : chosen) out.push_back(to_rgb8(c));
  return out;
}

constexpr int kMapSize = 256;
constexpr int kPaletteSize = 8;

const std::vector<Rgb8>& categorical_palette() {
  static const std::vector<Rgb8> palette = build_categorical(kPaletteSize);
  return palette;
}

}  // namespace

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double linear_to_srgb(double c) {
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
}

Lab srgb_to_lab(const std::array<double, 3>& srgb01) {
  const Eigen::Vector3d lin(srgb_to_linear(srgb01[0]), srgb_to_linear(srgb01[1]),
                            srgb_to_linear(srgb01[2]));
  const Eigen::Vector3d xyz = space().rgb_to_xyz * lin;
  const Eigen::Vector3d& w = space().white;
  const double fx = lab_f(xyz[0] / w[0]), fy = lab_f(xyz[1] / w[1]), fz = lab_f(xyz[2] / w[2]);
  return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

Lab rgb8_to_lab(Rgb8 c) {
  return srgb_to_lab({c.r / 255.0, c.g / 255.0, c.b / 255.0});
}

namespace {
Eigen::Vector3d lab_to_linear_rgb(const Lab& lab) {
  const double fy = (lab.L + 16.0) / 116.0;
  const Eigen::Vector3d& w = space().white;
  const Eigen::Vector3d xyz(w[0] * lab_f_inverse(fy + lab.a / 500.0), w[1] * lab_f_inverse(fy),
                            w[2] * lab_f_inverse(fy - lab.b / 200.0));
  return space().xyz_to_rgb * xyz;
}
}  // namespace

std::array<double, 3> lab_to_srgb(const Lab& lab) {
  const Eigen::Vector3d lin = lab_to_linear_rgb(lab);
  std::array<double, 3> out{};
  for (int k = 0; k < 3; ++k)
    out[k] = lin[k] < 0.0 ? -linear_to_srgb(-lin[k]) : linear_to_srgb(lin[k]);
  return out;
}

bool in_srgb_gamut(const Lab& lab) {
  const Eigen::Vector3d lin = lab_to_linear_rgb(lab);
  constexpr double kTolerance = 1e-9;
  return lin.minCoeff() >= -kTolerance && lin.maxCoeff() <= 1.0 + kTolerance;
}

double delta_e76(const Lab& p, const Lab& q) {
  return std::sqrt((p.L - q.L) * (p.L - q.L) + (p.a - q.a) * (p.a - q.a) +
                   (p.b - q.b) * (p.b - q.b));
}

Colormap::Colormap(std::vector<Rgb8> lut) : lut_(std::move(lut)) {
  if (lut_.size() < 2) throw std::invalid_argument("Colormap needs at least two entries");
}

Rgb8 Colormap::at(double t) const {
  if (std::isnan(t)) return no_data_colour();
  const double n = static_cast<double>(lut_.size());
  const double k = std::floor(std::clamp(t, 0.0, 1.0) * n);
  return lut_[static_cast<std::size_t>(std::min(k, n - 1.0))];
}

const Colormap& sequential_colormap() {
  static const Colormap map(
      quantize_increasing_lightness(sample_uniformly(sequential_design, kMapSize)));
  return map;
}

const Colormap& diverging_colormap() {
  static const Colormap map(build_diverging(kMapSize));
  return map;
}

Rgb8 categorical_colour(int k) {
  const auto& palette = categorical_palette();
  const int n = static_cast<int>(palette.size());
  return palette[static_cast<std::size_t>(((k % n) + n) % n)];
}

int categorical_palette_size() {
  return kPaletteSize;
}

Rgb8 no_data_colour() {
  return {128, 128, 128};
}

}  // namespace gearsph::render
