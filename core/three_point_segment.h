#pragma once
// The 3-point LA segment (Yoshida & Saito, "Interactive aesthetic curve segments",
// The Visual Computer 22, 2006; seed 003 section 2.1; DESIGN.md section 2).
//
// Given alpha and control points Q0 (start), Q1 (intersection of the end tangents),
// Q2 (end), find the LA segment from Q0 to Q2 whose end tangents point along Q1-Q0
// and Q2-Q1. In the standard form (Q0 at the origin, Q1-Q0 along +x, left turn,
// rho(0) = 1) the curve is a function of the tangent angle theta in [0, theta_d]:
//   rho(theta) = (1 + (w - 1) theta/theta_d)^(1/(alpha-1)),  w = exp((alpha-1) m)
//   rho(theta) = exp(m theta/theta_d)                          (alpha = 1)
//   E(m) = integral_0^theta_d rho(theta) e^{i theta} dtheta     (end point)
// where m = log(rho_end / rho_start) is the one shape parameter (m = 0: circle).
// This parameterization (ours, not the paper's Lambda) covers the whole domain of
// every alpha with m in R, and the chord angle arg E(m) increases monotonically with
// m, so a safeguarded Newton on m (dE/dm under the same integral) fits the chord
// angle of the triangle. It works on a logit of the chord angle between its limits
// for m -> -+inf (closed-form power-series moments), where the map is nearly linear,
// from a closed-form quadratic model at the circle m = 0: three evaluations of E for
// typical triangles, the last Newton step predicted rather than confirmed. A
// similarity transform then places the curve.
//
// Speed: on the fixed Gauss-Legendre nodes cos/sin theta_k are computed once per
// solve; each iteration re-evaluates only rho. Where rho varies too much for the fixed
// rule (|m| large, near the ends of the domain) the adaptive rule takes over.

#include "core/segment_solve.h"

namespace la {

struct ThreePointOptions {
  /// Convergence: |chord angle - target| <= chord_tolerance * theta_d (radians).
  double chord_tolerance = 1e-15;
  int max_iterations = 60;
  /// Shapes are searched for |m| <= max_log_radius_ratio (a curvature ratio of
  /// e^30 ~ 1e13 between the ends); beyond it the triangle is reported infeasible.
  double max_log_radius_ratio = 30.0;
  /// Compute the reachable range for an infeasible triangle (two more evaluations at the
  /// extreme shapes; a caller that only asks "is it feasible?" may skip them).
  bool report_reachable = true;
};

/// The LA segment with the given alpha (finite, or +-inf for a circular arc) through
/// the control triangle. Collinear points in order (Q1 between Q0 and Q2) give a
/// straight line. An unreachable triangle gives kInfeasible with the reachable range.
SegmentSolve solveThreePointSegment(double alpha, const Vec2& q0, const Vec2& q1, const Vec2& q2,
                                    const ThreePointOptions& options = {});

/// The chord angles phi(m) tends to as the curvature ratio goes to 0 or infinity
/// (m -> -+inf), in closed form: for alpha < 0 the limit shapes are the segments with an
/// inflection at one end, for alpha > 1 those with zero radius at one end (rho ~ tau^p,
/// p = 1/(alpha - 1)); for 0 <= alpha <= 1 they are (0, theta_d). The reachable range
/// (bounded |m|) lies strictly inside. alpha = +-inf: theta_d / 2 (lo == hi).
ChordAngleRange chordAngleLimits(double alpha, double theta_d);

/// The chord angles the construction reaches for this alpha and turning angle
/// (0 < theta_d < pi). For alpha = +-inf only theta_d / 2 (lo == hi).
ChordAngleRange reachableChordAngles(double alpha, double theta_d,
                                     const ThreePointOptions& options = {});

}  // namespace la
