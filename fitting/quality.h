#pragma once
// The quality figures of DESIGN.md section 6, one definition everywhere (lafit, the GUI,
// the tests): deviation of the input points from the curve, tangent and curvature gaps
// at joints, the number of curvature extrema and inflections, and the tightest radius.
// extrema_dense and extrema_per_part are counted as the independent checker
// ../shared/tools/lacheck.py counts them, so that its figures and ours compare.

#include <cmath>
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
  /// Reversals of the curvature along the whole curve in order, a jump at a corner
  /// against the trend included (lacheck.py's extrema_dense; DESIGN.md section 6).
  int extrema_dense = 0;
  /// Per smooth part (between corners): reversals of the curvature's trend at its
  /// joints, arcs and lines skipped; a closed curve without corners counts its seam.
  /// Inflections are not counted. The figure to hold against the user's cap
  /// (SegmentationOptions::max_extrema).
  std::vector<int> extrema_per_part;
  int max_extrema_per_part = 0;  // the largest of extrema_per_part
  double max_abs_kappa = 0.0;
  double min_radius = INFINITY;  // 1 / max_abs_kappa: the tightest bend (infinite for a line)
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
/// Beyond a diagonal from the points' bounding box it is the distance to that box (a
/// lower bound: such a curve has run away, and how far matters no more).
double strayFromPoints(const Curve& curve, std::vector<Vec2> points, double diagonal);

/// True where strayFromPoints(curve, points, diagonal) is surely at most `limit`, told
/// from samples `limit` apart (the dense measure's are 0.2% of the diagonal apart);
/// false where they cannot tell. (Where a stray matters only beyond a limit, and most
/// curves stay well inside it.)
bool strayWithin(const Curve& curve, std::vector<Vec2> points, double diagonal, double limit);

/// strayFromPoints where it exceeds `limit`, else 0: strayWithin's samples first, the
/// dense measure only where they cannot tell (on one grid of the points).
double strayBeyond(const Curve& curve, std::vector<Vec2> points, double diagonal, double limit);

QualityFigures measureQuality(const Curve& curve, const std::vector<Vec2>& points);

/// The reversals of the curvature along the curve, a jump at a corner against the trend
/// included (QualityFigures::extrema_dense), against this diagonal.
int curvatureReversals(const Curve& curve, double diagonal);

/// +1 for curvature rising along the segment, -1 falling, 0 for an arc or a line (its
/// curvature changes by less than 1e-12 of its larger end value, or of 1 / diagonal).
int curvatureTrend(const LaSegment& segment, double diagonal);

/// The curvature extrema of each smooth part (between corners), as
/// QualityFigures::extrema_per_part counts them: per part, the joints where the trend
/// reverses (segment index of the joint; 0 for a closed curve's seam).
std::vector<std::vector<std::size_t>> extremumJoints(const Curve& curve, double diagonal);

/// Some smooth part of the curve has more curvature extrema than `cap` (extremumJoints;
/// a negative cap: none).
bool overExtremaCap(const Curve& curve, double diagonal, int cap);

}  // namespace la
