#pragma once
// Stage 7's start where stages 5-6 found no G2 chain (a piece whose tangents form no
// control triangle, a joint no tangent angle makes G2): a chain read off the smoothing
// spline in intrinsic form, segment by segment, each shot from the previous one's end
// towards the next split point. G2 by construction.

#include <optional>
#include <vector>

#include "core/bspline.h"
#include "core/la_segment.h"
#include "fitting/budget.h"
#include "fitting/pipeline.h"

namespace la {

/// Where a chain starts: position, tangent angle, signed curvature.
struct ChainStart {
  Vec2 point = Vec2::Zero();
  double theta = 0.0, kappa = 0.0;
};

/// The chain over the spline's pieces `spans` (spline parameters t0, t1 per piece; a
/// piece turning against both its neighbours is cut at its largest curvature, and
/// `spans` updated). With `halve`, where a shot segment comes out far longer or shorter
/// than the spline between its splits (it set off away from the points), its span is
/// halved and the chain shot again, unless `budget` is spent.
/// With `from`, the first segment starts there (a chain fitted before this one ends
/// there) instead of at the spline's start, with its curvature.
/// Empty if some piece has no LA segment, or `budget` is spent before the chain is shot.
std::vector<LaSegment> chainFromSpline(
    const CubicBSpline& spline, std::vector<PieceReport>& spans, bool closed, double min_alpha, double max_alpha,
    bool halve, const Budget& budget = {}, const std::optional<ChainStart>& from = std::nullopt);

/// One LA segment from `start` with tangent `theta0` and curvature `kappa_start`,
/// turning by `turning`, whose end curvature (unless `kappa_end` is 0: an inflection end
/// stays) and alpha (within [min_alpha, max_alpha]) bring its end closest to `target`:
/// Gauss-Newton from `kappa_end` and `alpha`, a few steps, each kept only if it gets
/// closer. Nullopt if no LA segment has the start values.
std::optional<LaSegment> shootSegment(double turning, const Vec2& start, double theta0, double kappa_start,
                                      double kappa_end, double alpha, double min_alpha, double max_alpha,
                                      const Vec2& target);

}  // namespace la
