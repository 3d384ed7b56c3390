#pragma once
// Where a loaded tooth breaks: the two root fillets of one pinion tooth as
// curves on the true (generated) outline, and the stress along them.
//
// A fillet runs from the middle of the tooth space (root circle) up the
// trochoid to the form circle, where the involute begins. On that traction-
// free boundary the only in-plane stress is the tangential one, so the
// largest principal stress of the tension fillet and the lowest of the
// compression fillet are read along the curve from a stress tensor given
// at each of its points (recovered from particles, or interpolated from a
// finite-element solution: the same curve and the same numbers for both).
//
// ISO 6336-3 rates the tooth by the stress at its 30-degree point, where the
// fillet's tangent makes 30 degrees with the tooth axis; the peak of a
// loaded tooth sits near it (Linke 1996; ISO 6336-3:2006, 6.2).
#include <array>
#include <vector>

#include "solver/geometry/gear_profile.hpp"
#include "solver/geometry/polygon.hpp"

namespace gearsph::gear {

// One fillet, sampled at an even arc-length step.
struct FilletCurve {
  std::vector<geometry::Point> points;   // on the outline [m]
  std::vector<geometry::Point> tangent;  // unit, pointing up the fillet (toward the flank)
  std::vector<geometry::Point> normal;   // unit, outward (out of the material)
  std::vector<double> arc;               // arc length from the space centre [m]
  std::vector<double> radius;            // distance from the gear centre [m]
  // Angle between the tangent and the tooth axis [rad]: pi/2 at the space
  // centre, about 0 where the flank begins.
  std::vector<double> tangent_angle;
  // ISO's 30-degree point, interpolated between samples i30 and i30 + 1.
  std::size_t i30 = 0;
  double f30 = 0.0;
  // The outline beyond both ends at the same step, nearest first: `before`
  // past the space centre (the neighbouring tooth's fillet, the mirror image
  // of this one), `after` up the flank. A derivative along the fillet (its
  // stretch) then needs no one-sided window at either end.
  std::vector<geometry::Point> before, after;
  std::size_t size() const { return points.size(); }
};

// The fillet with its reach (FilletCurve::before, after) as one curve in
// order along the outline; `arc` gets each point's arc length (negative
// past the space centre). The fillet's own samples start at before.size().
std::vector<geometry::Point> with_reach(const FilletCurve& c, std::vector<double>* arc);

// The two fillets of one tooth, placed in the world.
struct ToothFillets {
  int tooth = 0;
  FilletCurve tension;      // under the loaded flank: bending stretches it
  FilletCurve compression;  // under the unloaded flank
  geometry::Point centre;   // gear centre in the world [m]
};

// Tooth k of `pinion` (gear frame of gear_profile.hpp) placed by `placement`,
// sampled every `step` metres, with `reach` metres of outline beyond either
// end. The tension side is the one whose flank the force `load_direction`
// (world, the force on the tooth) pushes into.
ToothFillets tooth_fillets(const geometry::PinionGeometry& pinion, int k,
                           const geometry::Transform& placement, geometry::Point load_direction,
                           double step, double reach = 0.0);

// The involute flank that the force `load_direction` pushes into, from the
// form circle to the tip (tooth k placed as in tooth_fillets): where a
// graded spacing is made fine for contact.
std::vector<geometry::Point> loaded_flank(const geometry::PinionGeometry& pinion, int k,
                                          const geometry::Transform& placement,
                                          geometry::Point load_direction);

// A window around one tooth for a figure of its root, the same for the FE
// check's tooth images and the SPH static check's tooth0_box_m: across, the
// two space centres (where the fillets start) and 15 % more each side;
// along the tooth axis, from 4 % of the tooth height beyond the tip down to
// a quarter of it below the space centres. In the world as {x0, y0, x1, y1}
// [m]: that rectangle for a tooth along an axis; for a turned one a box of
// the same size centred on it (a figure keeps the upright tooth's scale),
// grown only where the fillets or the tip would leave it.
std::array<double, 4> tooth_window(const ToothFillets& f, double tip_radius);

// In-plane Cauchy stress [Pa].
struct PlaneStress {
  double xx = 0.0, yy = 0.0, xy = 0.0;
  double max_principal() const;
  double min_principal() const;
  // t . sigma . t for a unit vector t.
  double along(geometry::Point t) const;
};

// What a gear engineer reads off one fillet.
struct FilletPeak {
  double stress_Pa = 0.0;    // largest sigma_1 (tension) or lowest sigma_3 (compression)
  double arc_m = 0.0;        // where, along the curve
  double radius_m = 0.0;     // where, from the gear centre
  double angle_rad = 0.0;    // tangent against the tooth axis there
  double at_iso30_Pa = 0.0;  // the same principal stress at ISO's 30-degree point
};

struct FilletStress {
  FilletPeak tension, compression;
  // Along each curve, per sample: sigma_1 of the tension fillet, sigma_3 of
  // the compression fillet [Pa] (the curves a plot shows against `arc`).
  std::vector<double> tension_curve, compression_curve;
};

// `tension_stress[i]` is the stress at f.tension.points[i] (and the same for
// compression). The peak is refined by a parabola through the largest
// sample and its neighbours.
FilletStress fillet_stress(const ToothFillets& f, const std::vector<PlaneStress>& tension_stress,
                           const std::vector<PlaneStress>& compression_stress);

// The same from the tangential stress sigma_tt alone, one per sample: on the
// traction-free fillet the in-plane stress is sigma_tt t t, so sigma_1 is
// max(sigma_tt, 0) and sigma_3 min(sigma_tt, 0).
FilletStress fillet_stress(const ToothFillets& f, const std::vector<double>& tension_tangential,
                           const std::vector<double>& compression_tangential);

}  // namespace gearsph::gear
