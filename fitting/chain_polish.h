#pragma once
// Least-squares polish of an open G2 chain of LA segments (ours; not in seed 003).
//
// The pipeline builds each segment from a control triangle whose end tangents come
// from the smoothing spline, so a tangent error there is absorbed by alpha: on a noisy
// logarithmic spiral the triangle's best alpha can be -0.7 instead of 1. This stage fits
// the whole chain to the points directly, in intrinsic form, where G2 holds by
// construction:
//   unknowns  start point, start tangent theta0, the curvature kappa_j at every joint
//             (sign kept; an inflection joint stays at kappa = 0), each segment's length
//             L_i and alpha_i (bounded to [min_alpha, max_alpha]; below 0 where a segment
//             has a zero-curvature end, DESIGN.md section 2);
//   segment i LaSegment(alpha_i, L_i, end of segment i-1, its end tangent, kappa_i, kappa_i+1);
//   residual  for each point X_k with foot point s_k on the chain: n(s_k) . (P(s_k) - X_k)
//             (the tangent-distance of Wang, Pottmann & Liu 2006, which lets points slide
//             along the curve); the first and last point use both components, which pins
//             the chain's ends to the stroke's ends.
// Levenberg-Marquardt (Ceres) with the foot points held, then the foot points projected
// again, a few rounds. The start may be held fixed (a part that starts at a corner).
// The result is kept only if it is closer to the points than the chain it started from;
// the caller decides (e.g. against the tolerance) whether to use it.

#include <vector>

#include "core/la_segment.h"
#include "core/solve_report.h"

namespace la {

struct PolishOptions {
  double min_alpha = -3.0, max_alpha = 3.0;
  bool fix_start = false;      // keep the chain's start point where it is
  int rounds = 3;              // foot-point projections
  int max_iterations = 15;     // Levenberg-Marquardt steps per round
  /// At most this many points take part (evenly spaced along the stroke, ends kept);
  /// more add little to a fit of a few dozen unknowns and cost time.
  std::size_t max_points = 100;
};

struct PolishResult {
  std::vector<LaSegment> segments;   // the polished chain (the input chain if not improved)
  double rms_before = 0.0, rms_after = 0.0;  // rms of the residuals at the first and last round
  bool improved = false;
  SolveReport report;
};

/// `segments` must form an open G2 chain (each starts where the previous ends, same tangent
/// and curvature) of finite-alpha segments; `points` are the stroke's points in order from
/// the chain's start to its end. A chain it cannot take (an infinite alpha, a straight
/// segment) comes back unchanged with kBadInput.
PolishResult polishChain(const std::vector<LaSegment>& segments, const std::vector<Vec2>& points,
                         const PolishOptions& options = {});

}  // namespace la
