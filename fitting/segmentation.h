#pragma once
// Stage 3 (DESIGN.md section 3; seed 003 section 3): split the smoothed B-spline at its
// inflections and curvature extrema, so each piece has monotone curvature of one sign
// and can become one LA segment.
//
// Per span the spline is a cubic polynomial, so
//   inflections:        x'y'' - y'x'' = 0, a quadratic (the cubic terms cancel);
//   curvature extrema:  d kappa/dt = 0  <=>  (x'y''' - y'x''') |C'|^2 - 3 (x'y'' - y'x'') (C'.C'') = 0,
//                       a quintic; and on knots, where C''' jumps, by a sign change of
//                       d kappa/dt across the knot.
// Noise makes many small extrema. They are removed in pairs (a maximum with its
// neighbouring minimum) in order of increasing curvature difference, as long as the
// difference is below `significance` times the curve's largest |kappa| (topological
// persistence on the curvature profile); the user may also cap the number kept. After
// that, one inflection is kept between two retained extrema of opposite sign. Pieces
// turning more than max_piece_turning are cut into equal-turning parts, so every
// control triangle stays well shaped.

#include <vector>

#include "core/bspline.h"

namespace la {

enum class SplitKind { kEnd, kInflection, kExtremum, kTurning };
const char* toString(SplitKind kind);

struct SplitPoint {
  double t = 0.0;
  SplitKind kind = SplitKind::kEnd;
  double kappa = 0.0;  // curvature of the spline there (0 at an inflection)
};

struct SegmentationOptions {
  double significance = 0.2;        // relative curvature difference of an extremum pair worth keeping
  int max_extrema = -1;             // cap on curvature extrema kept (-1: no cap)
  double max_piece_turning = 2.0;   // radians
};

struct Segmentation {
  /// Split points in parameter order. Open curve: the first and last are the ends.
  /// Closed curve: a cyclic list; piece i runs from splits[i] to splits[i+1 mod n]
  /// (the last piece wraps through the parameter seam).
  std::vector<SplitPoint> splits;
  bool closed = false;
  std::size_t pieceCount() const { return closed ? splits.size() : splits.size() - 1; }
};

Segmentation segmentSpline(const CubicBSpline& spline, const SegmentationOptions& options = {});
/// The same on the part [t_begin, t_end] of an open spline (where the stroke's points
/// have their feet, so the curve does not run on past its first and last point).
Segmentation segmentSpline(const CubicBSpline& spline, double t_begin, double t_end,
                           const SegmentationOptions& options = {});

/// Tangent angle of the spline (continuous along [t0, t1] when no cusp lies between).
double splineTangentAngle(const CubicBSpline& spline, double t);

}  // namespace la
