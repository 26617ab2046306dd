#pragma once
// G2 Hermite interpolation by a triple LA curve (seed 002: "G2 Hermite interpolation
// with log-aesthetic curves", after Ran et al.'s triple clothoid; DESIGN.md section 4).
//
// Problem. Given alpha and two ends (point, tangent angle, curvature), find three LA
// pieces of that one alpha, of lengths L/4, L/2, L/4 (joints at 0.25 L and 0.75 L,
// seed eq. 1), curvature and tangent continuous at the joints, from the start to the
// end. The seed states it as 10 unknowns (c_i0, c_i1, c_i2 per piece and the length
// h) and 10 equations (eqs. 2-7 and the four joint continuity conditions).
//
// Our formulation (replaces the seed's 10x10 system). In intrinsic form a piece is
// fixed by its length and its two end curvatures: |kappa|^(-alpha) (alpha != 0) or
// log|kappa| (alpha = 0) is linear in arc length between them. Curvature continuity
// is then built in by sharing the joint curvatures k1, k2, and tangent continuity by
// integrating theta along the chain, which leaves three unknowns (L, k1, k2) and three
// equations: the end tangent angle (1, closed form, linear in L) and the end point (2).
// In the normalized frame (start at the origin, chord along +x, unit chord) the
// curvature profile kappa(sigma) over sigma = s/L in [0, 1] depends on k1, k2 only, so
//   T = theta(L) - theta(0) = L * integral_0^1 kappa(sigma) d sigma,
//   E = P(L) - P(0)         = integral_0^L exp(i theta(s)) ds,
//   dE/dlog L = E + i integral_0^L (theta(s) - theta(0)) exp(i theta(s)) ds,
//   dE/dk_j   = i integral_0^L (d kappa(s)/dk_j) (E - P(s)) ds   (bending at s turns the rest),
// all on fixed Gauss-Legendre panels (core/quadrature.h); positions P(s) at the nodes
// come from the Gauss collocation integration matrix of each panel. Newton runs on
// x = (log L, y1, y2) with y = log|k| for alpha >= 0 (the curvature keeps the sign of
// the end curvatures and cannot reach 0) and y = sign(k) |k|^(-alpha) for alpha < 0,
// the variable in which the LA law is linear. Both are unconstrained, so every
// iterate is a valid curve; a backtracking line search on the residual keeps Newton
// from wandering.
//
// Inflections. For alpha < 0 the law |kappa|^(-alpha) = |c s + d| extends through
// kappa = 0 with a sign change (the LCG stays one straight line on both sides, seed
// 002 sec. 2.1 allows the sign change), so a piece whose end curvatures have opposite
// signs has one inflection inside; it is stored as two LaSegments joined (G2) at the
// inflection. The Curve therefore has 3 LaSegments, plus one per such inflection.
// On the fast panels such a part (or a piece ending at a zero end curvature) takes its
// curvature and angle from the distance r to the zero: kappa = kappa_far (r/l)^beta,
// theta = theta_zero +- kappa r / (1 + beta) (l the part's length, beta = -1/alpha),
// exact where the general closed forms would cancel, and one log and exp per node.
// For alpha >= 0 a curvature cannot reach 0: opposite-sign or zero end curvatures are
// infeasible, and so is a turning whose sign differs from the curvature's.
//
// Initial values (instead of the seed's optimized quintic Bezier, sec. 2.4): the
// small-deflection model of a triple clothoid. With L from the cubic Bezier through
// the end tangents (handles at a third of the chord) and kappa piecewise linear in
// s through k0, k1, k2, k3, the two conditions
//   L * integral kappa = T   and   integral_0^1 theta(sigma) d sigma = 0 (y(L) ~ 0)
// are linear in k1, k2 (exact for a clothoid with small deflection). For alpha != -1
// the same two conditions are then solved with the LA law of the problem in place of
// the linear profile (2x2 Newton from the clothoid values, kappa on 8 Gauss nodes per
// piece): for alpha = -3 or 3 the clothoid values are off by ~20% and cost Newton on
// the fast model two to four extra iterations. When Newton from there fails, it is
// tried from the clothoid values, then repeated from the alpha = -1 (triple clothoid)
// solution by continuation in alpha, then from a few other lengths.
//
// Every result is verified: the Curve is rebuilt from its LaSegments with positions
// by LaSegment::end (adaptive quadrature, and the exact inflection series within 1 rad
// of a zero-curvature end), independent of the fast panels, and only if the end point
// and angle match to the tolerance is the status kConverged. Newton's last step is not
// evaluated on the fast panels when the previous step's quadratic contraction predicts
// it lands far below the target; the verification checks it instead. A miss after
// Newton on the fast panels is corrected by a few steps with the verified residual and
// the fast Jacobian.

#include <limits>
#include <optional>

#include "core/curve.h"
#include "core/hermite_end.h"
#include "core/solve_report.h"

namespace la {

struct TripleLaHermiteOptions {
  double tolerance = 1e-12;  // end position miss relative to |P1 - P0|; angle miss in radians
  int max_iterations = 50;  // per Newton run; a failing solve makes a few (other starts, continuation)
};

struct TripleLaHermiteSolve {
  std::optional<Curve> curve;  // three LA pieces with the same alpha, G2 at both joints; set only when report.usable()
  SolveReport report;
  /// The solved total length and joint curvatures (at 0.25 L and 0.75 L); NaN unless usable.
  double length = std::numeric_limits<double>::quiet_NaN();
  double kappa1 = std::numeric_limits<double>::quiet_NaN();
  double kappa2 = std::numeric_limits<double>::quiet_NaN();
};

/// Three LA pieces of one alpha, joints at 0.25 and 0.75 of the total length, G2 everywhere, from
/// start.point with direction start.theta and curvature start.kappa to end.point with end.theta, end.kappa.
/// The total turning is end.theta - start.theta exactly as given (not wrapped): the caller chooses the winding.
/// alpha = +-inf: the only G2 chain of circular arcs is one circle, so that is solved when the ends lie on it
/// (kInfeasible otherwise). A piece with an inflection (alpha < 0 only) is two LaSegments (see above).
TripleLaHermiteSolve solveTripleLaHermite(double alpha, const HermiteEnd& start, const HermiteEnd& end,
                                          const TripleLaHermiteOptions& options = {});

}  // namespace la
