#pragma once
// A stroke's corner-to-corner parts, each fitted on its own by stages 2-6
// (fitting/paper_stages.h) and stage 7 (fitting/stage7.h), and what a part's fit holds.

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "core/bspline.h"
#include "core/la_segment.h"
#include "core/solve_report.h"
#include "fitting/chain_fit.h"
#include "fitting/pipeline.h"
#include "fitting/segmentation.h"
#include "fitting/stroke.h"

namespace la {

struct Part {
  std::vector<Vec2> points;
  bool closed = false;
  bool starts_at_corner = false;  // its first point is a corner (stage 7 pins the curve's start to it)
  bool ends_at_corner = false;    // its last point is a corner (stage 7 pins the curve's end to it)
};

struct PartFit {
  std::vector<LaSegment> segments;
  std::vector<PieceReport> reports;
  std::optional<CubicBSpline> spline;  // none for a straight part
  std::vector<SplitPoint> splits;
  std::vector<PieceReport> spans;  // every piece of the final segmentation (segments may differ after a failed G2)
  std::vector<ChainFoot> feet;     // of the part's points on `spans` (from their spline parameters), or on `segments` without a spline
  std::vector<double> parameters;  // the points' spline parameters
  std::vector<std::string> warnings;
  double max_dev = NAN;            // largest distance of the part's points from `segments`, once known
  double stray = NAN;              // largest distance of `segments` from the part's polyline, once known
  SolveReport smoothing, g2;
  /// The cap on extrema shaped `segments` (merged them down to it, or made them the one LA
  /// segment or circle it leaves): a miss of the tolerance is then the cap's cost.
  bool capped = false;
};

/// The cleaned stroke cut at its corners (one part if it has none). A step more than
/// ten median steps long is filled with points along it (fillGaps in parts.cpp).
std::vector<Part> splitAtCorners(const CleanStroke& stroke);

/// Every point within `tol` of the chord from the first point to the last (and not
/// beyond its ends by more): a straight part.
bool withinChord(const std::vector<Vec2>& points, double tol);

/// Where a straight stroke (CleanStroke::straight) turns back along its line: indices of
/// its first point, of each point from which it runs back by more than `tolerance`, and
/// of its last point. Its curve is the lines between them (corners of pi).
std::vector<std::size_t> turnsAlongLine(const std::vector<Vec2>& points, double tolerance);

/// The largest distance from the points to a part's chain.
double maxDeviationOf(const std::vector<LaSegment>& segments, const std::vector<Vec2>& points, double diag);

}  // namespace la
