#pragma once
// The compound-rhythm LA curve from four control points (Agari, Kawata, Fujisawa,
// Miura, "Generation of compounded-rhythm aesthetic curves from control points";
// seed 001; DESIGN.md section 4).
//
// Two LA segments, alpha0 then alpha1, joined G3 at a joint of given tangent angle
// theta_c: position, tangent, radius rho and d rho/ds continuous there. Like a cubic
// Bezier curve the result starts at Q0 heading along Q1 - Q0 and ends at Q3 heading
// along Q3 - Q2. In the seed's notation (eq. 4) rho^alpha_i = c_i s + d_i on piece i
// (s the arc length from Q0), and G3 fixes the second piece from the first (eqs. 8-11):
//   rho_c^alpha0 = c0 s_c + d0 = c1 s_c + d1,
//   d rho/ds = c0 / (alpha0 rho_c^(alpha0-1)) = c1 / (alpha1 rho_c^(alpha1-1))
//   =>  c1 = (alpha1/alpha0) c0 rho_c^(alpha1-alpha0),   d1 = rho_c^alpha1 - c1 s_c,
// which we checked against the math (the seed's eqs. 10 and 11 are right). Because
// d rho/ds keeps its sign across the joint, rho is monotone along the whole curve: the
// polygon Q0 Q1 Q2 Q3 must turn one way only (seed sec. 4.1); an S-shaped one has no
// compound-rhythm curve.
//
// Method. Every LA law is written per piece in its turning angle t (from the piece's
// start), with the radius relative to the piece's start radius rho_a and the
// dimensionless rate r_a = d rho/ds there:
//   (rho/rho_a)^(alpha-1) = 1 + (alpha-1) r_a t        (alpha != 1; alpha = 0 included)
//   rho/rho_a = exp(r_a t)                             (alpha = 1, the log spiral)
// (from d rho/ds = K rho^(1-alpha) with K constant along an LA piece, i.e. c/alpha for
// alpha != 0 and c for alpha = 0 where log rho = c s + d). G3 is then just "r continuous
// at the joint". The turning of each piece is known (theta_c - theta_0 and
// theta_3 - theta_c), so the curve is fixed by its start radius (a scale) and one shape
// number: we take m = log(rho_c / rho_0), the first piece's log radius ratio; the
// second piece's m1 = log(rho_end / rho_c) follows from r at the joint and increases
// with m. The seed's 2D Newton on (c0, d0) is this problem: scaling a curve by k maps
// (c_i, d_i) to (k^(alpha_i-1) c_i, k^alpha_i d_i), so one direction of (c0, d0) is pure
// scale. We therefore solve the chord angle of Q3 at Q0 (a function of m alone,
// increasing: a larger m moves weight to the later, more turned, part; we found no
// exception in the tests' sweeps, and the bracketed solve needs only a sign change) by
// Newton kept inside a bracket (core/root_finding.h), then take the scale from the
// chord length. Where piece 1 nears the end of its domain (1 + (alpha1-1) r phi1 -> 0)
// m1 reacts to the rounding of m, so the solve is polished with m1 as the unknown. This deviates from the seed's procedure, not its result; it replaces
// the seed's initial guess (a 3-point segment to the centroid) and its step halving
// for the positivity constraints (12)-(13), which hold by construction here: m and m1
// are limited to |log radius ratio| <= 30 per piece, so c s + d stays positive.
// Inside Newton, positions are fixed composite Gauss-Legendre rules in t (graded
// towards the branch point of the law when it is near); lengths are closed forms; the
// built Curve's end is then checked against Q3 with LaSegment's own evaluation.
//
// The work is done in a normalized frame (Q0 at the origin, Q1 - Q0 along +x, unit
// chord, right turns mirrored), so the result is invariant under rotation,
// translation, uniform scaling and reflection. Any finite alpha0, alpha1 is accepted,
// 0 (Nielsen's spiral, log rho linear in s) and 1 (log spiral) included. A curvature
// of zero (an inflection, allowed at an end with alpha < 0) would need an infinite
// radius ratio and is only approached, not reached.

#include <array>
#include <limits>
#include <optional>

#include "core/curve.h"
#include "core/geometry.h"
#include "core/solve_report.h"

namespace la {

struct CompoundRhythmOptions {
  double tolerance = 1e-12;   // end-point miss, relative to |Q3 - Q0|
  int max_iterations = 60;
};

struct CompoundRhythmSolve {
  std::optional<Curve> curve;  // two LA pieces (alpha0 then alpha1), set only when report.usable()
  SolveReport report;
  double joint_theta = std::numeric_limits<double>::quiet_NaN();  // joint tangent direction used (radians, world frame)
};

/// Q0..Q3 as the control polygon of a cubic Bezier: the curve starts at Q0 heading along Q1-Q0 and ends at Q3
/// heading along Q3-Q2. joint_theta = NaN takes the default direction (from the midpoint of Q0Q1 to the midpoint of Q2Q3).
///
/// The polygon must turn one way (both corner angles of one sign, total turning below
/// 2 pi), and the joint direction must lie strictly inside the turning, from Q1 - Q0 to
/// Q3 - Q2 (taken modulo 2 pi). report.status: kConverged (residual = end-point miss /
/// |Q3 - Q0| of the built curve, iterations = Newton steps), kBadInput (NaN, infinite
/// alpha, coincident points, a straight polygon, a corner of +-pi, an alpha LaSegment
/// cannot represent), kInfeasible (an S-shaped polygon, a joint direction outside the
/// turning, or Q3 outside the reachable chord angles, which the message gives),
/// kIterationLimit (out of iterations, or the built curve misses Q3 by more than the
/// tolerance: seen only for |alpha| ~ 1e-9, where LaSegment's evaluation loses digits).
CompoundRhythmSolve solveCompoundRhythm(double alpha0, double alpha1, const std::array<Vec2, 4>& q,
                                        double joint_theta = std::numeric_limits<double>::quiet_NaN(),
                                        const CompoundRhythmOptions& options = {});

}  // namespace la
