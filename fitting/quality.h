#pragma once
// The quality figures of DESIGN.md section 6, one definition everywhere (lafit, the GUI,
// the tests): deviation of the input points from the curve, tangent and curvature gaps
// at joints, and the number of curvature extrema and inflections.

#include <vector>

#include "core/curve.h"
#include "core/geometry.h"

namespace la {

struct QualityFigures {
  double max_dev = 0.0;   // largest distance from an input point to the curve
  double rms_dev = 0.0;
  double g0_gap = 0.0;    // largest distance between a segment's end and the next one's start / diagonal
  double g1_gap = 0.0;    // largest tangent-angle jump at a (non-corner) joint, radians
  double g2_gap = 0.0;    // largest relative curvature jump at a (non-corner) joint
  int extrema = 0;        // curvature extrema along the curve (trend changes at joints)
  int inflections = 0;    // curvature sign changes
  int segments = 0;
  int corners = 0;
  double diagonal = 0.0;  // bounding-box diagonal of the input points
};

/// Distances from each point to the curve: to a polyline of the curve whose chords stay
/// within `resolution` * diagonal of it (their sagitta kappa h^2 / 8); the nearest edge is
/// found exactly (a uniform grid of the edges, searched in rings around the point). The
/// default, 1e-5, is 0.2% of the default tolerance.
std::vector<double> distancesToCurve(const Curve& curve, const std::vector<Vec2>& points, double diagonal,
                                     double resolution = 1e-5);

/// Largest distance from the curve (sampled every 0.2% of `diagonal`) to the polyline
/// of `points` (closed if the curve is): where the curve goes that the stroke never went.
double strayFromPoints(const Curve& curve, std::vector<Vec2> points, double diagonal);

QualityFigures measureQuality(const Curve& curve, const std::vector<Vec2>& points);

}  // namespace la
