#pragma once
// Cubic Bezier approximation of arc-length curves (LA segments, ALP curves), for SVG
// paths and DXF splines.
//
// The curve is first cut into pieces of at most a quarter turn of total turning, then at arc lengths where the Bezier through the end points with
// the end tangents matches the curve within the tolerance; each piece uses the
// handle length of the best circular-arc cubic, (4/3) tan(dtheta/4) / dtheta times
// the piece length, which is exact to O(h^6) for a circle and O(h^4) in general.
// The error is measured, not assumed: the distance from points of the curve's piece to
// the Bezier (by Newton projection) is checked at several arc lengths.

#include <vector>

#include "core/arc_length_curve.h"
#include "core/la_segment.h"

namespace la {

struct CubicBezier {
  Vec2 p0, p1, p2, p3;
  Vec2 point(double t) const;
  Vec2 derivative(double t) const;
};

struct BezierApproximation {
  std::vector<CubicBezier> pieces;
  double max_error = 0.0;  // largest measured distance, same units as the curve
};

/// Beziers within `tolerance` (an absolute distance) of the segment.
BezierApproximation approximateWithBeziers(const LaSegment& segment, double tolerance);

/// Beziers within `tolerance` (an absolute distance) of any arc-length curve; for an
/// LA segment the same as the overload above.
BezierApproximation approximateWithBeziers(const ArcLengthCurve& curve, double tolerance);

}  // namespace la
