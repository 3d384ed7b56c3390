#pragma once
// A contact pressure read from particles, fitted with the Hertz line-contact
// ellipse p(s) = p0 sqrt(1 - (s - centre)^2 / a^2) (Johnson 1985, eq. 4.45):
// the peak and half-width of a resolved contact, measured, not assumed.
#include <vector>

namespace gearsph::diagnostics {

struct HertzEllipseFit {
  double p0 = 0.0;   // peak pressure [Pa]
  double a = 0.0;    // half-width [m]
  double rms = 0.0;  // root-mean-square misfit [Pa]
};

// Least squares over a scan of a from 0.3 to 3 times a_guess in steps of
// a_guess / 1000 (for fixed a the best p0 is linear); s: positions along
// the surface, p: the pressure there, centre: the contact's middle.
HertzEllipseFit fit_hertz_ellipse(const std::vector<double>& s, const std::vector<double>& p,
                                  double a_guess, double centre = 0.0);

}  // namespace gearsph::diagnostics
