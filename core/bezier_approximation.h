#pragma once
// Cubic Bezier approximation of LA segments, for SVG paths and DXF splines.
//
// The segment is cut at arc lengths where the Bezier through the end points with
// the end tangents matches the curve within the tolerance; each piece uses the
// handle length of the best circular-arc cubic, (4/3) tan(dtheta/4) / dtheta times
// the piece length, which is exact to O(h^6) for a circle and O(h^4) in general.
// The error is measured, not assumed: the distance from points of the LA piece to
// the Bezier (by Newton projection) is checked at several arc lengths.

#include <vector>

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

}  // namespace la
