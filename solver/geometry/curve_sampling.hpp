#pragma once
// Adaptive sampling of an exact parametric curve into a polyline whose chords
// stay within a given distance of the curve: an interval is halved while the
// curve point at its middle lies farther than `tolerance` from the chord (for
// a smooth arc the mid-point deviation is the sagitta, the largest one).
#include <vector>

#include "solver/geometry/polygon.hpp"

namespace gearsph::geometry {

namespace detail {

double distance_to_chord(Point a, Point b, Point p);

template <class Curve>
void refine(const Curve& curve, double t0, Point p0, double t1, Point p1, double tolerance,
            int depth, std::vector<Point>& out) {
  const double tm = 0.5 * (t0 + t1);
  const Point pm = curve(tm);
  // 40 halvings resolve any interval to below 1e-12 of its length.
  if (depth < 40 && distance_to_chord(p0, p1, pm) > tolerance) {
    refine(curve, t0, p0, tm, pm, tolerance, depth + 1, out);
    refine(curve, tm, pm, t1, p1, tolerance, depth + 1, out);
  } else {
    out.push_back(p0);
  }
}

}  // namespace detail

// Appends curve(t) for t from t0 towards t1: the start point and the interior
// vertices, NOT the end point, so consecutive pieces join without duplicates.
// `min_segments` uniform pieces come first so that no wiggle hides between
// two samples.
template <class Curve>
void sample_curve(const Curve& curve, double t0, double t1, double tolerance,
                  std::vector<Point>& out, int min_segments = 16) {
  Point prev = curve(t0);
  for (int i = 1; i <= min_segments; ++i) {
    const double a = t0 + (t1 - t0) * (i - 1) / min_segments;
    const double b = i == min_segments ? t1 : t0 + (t1 - t0) * i / min_segments;
    const Point next = curve(b);
    detail::refine(curve, a, prev, b, next, tolerance, 0, out);
    prev = next;
  }
}

}  // namespace gearsph::geometry
