#pragma once
// Stages 2-6 of the paper (seed 003 section 3, DESIGN.md section 3) for one corner-free
// part: a B-spline within the tolerance, split at its inflections and curvature
// extrema, alpha per piece, one LA segment per piece from its control triangle, G2 by
// rotating the joint tangents. Without stage 7 to follow, pieces whose segment strays
// from the points or has none are cut and the stages run again (at most 16 passes).

#include <vector>

#include "core/bspline.h"
#include "core/lcg.h"
#include "fitting/fit_context.h"
#include "fitting/parts.h"

namespace la {

/// Alpha every segment of stage 7's start takes where the stages before say nothing
/// better (the centre of its alpha prior, ChainFitOptions::alpha_prior).
inline constexpr double kStage7StartAlpha = 0.5;

/// Stages 2-6 on `part`. With `stage7_follows`, they only prepare stage 7's start: the
/// spline is fitted to the tolerance (not tighter), alphas start at kStage7StartAlpha
/// and no piece is cut where its segment strays.
PartFit fitPart(const Part& part, const FitContext& context, bool stage7_follows);

/// LCG points of the spline between t0 and t1 (analytic curvature and its derivative),
/// its ends trimmed where d kappa/ds -> 0 would dominate the regression; and their
/// regression line, whose slope is the piece's LCG alpha (PieceReport::lcg_alpha).
std::vector<LcgPoint> lcgPointsOfPiece(const CubicBSpline& spline, double t0, double t1);
LcgFit lcgOfPiece(const CubicBSpline& spline, double t0, double t1);

/// Where to cut a spline piece that failed: at its curvature zero nearest its middle
/// when it has one, else at its middle.
SplitPoint halvingPoint(const CubicBSpline& spline, double t0, double t1);

/// Each point's foot on pieces spanning the spline parameters [t0, t1] (a closed
/// spline's last piece runs through the seam): the piece its parameter falls in, and
/// where.
std::vector<ChainFoot> feetOnSpans(const std::vector<PieceReport>& spans, const std::vector<double>& parameters,
                                   bool periodic, double period);

}  // namespace la
