#pragma once
// G1 and G2 Hermite interpolation with ALP curves (explicit Bezier curvature
// functions; seed 000 section 4, DESIGN.md section 4), and the inflection and
// curvature-monotonicity checks of seed 000 section 3.4.
//
// Free control curvatures. G^m Hermite interpolation with a curvature function of
// degree n needs n >= 2m - 1. For m = 2 the end curvatures fix kappa_0 = kappa_s and
// kappa_n = kappa_e; the unknowns are kappa_{m-1} and kappa_{n-m+1} (kappa_0, kappa_n
// for G1; kappa_1, kappa_{n-1} for G2), and the l = n - 2m + 1 control curvatures
// between them follow from those two and the user's p by seed 000 eq. 12:
//   v   = (i + 1)/(l + 1) (p_e - p_s) + p_s,
//   p_i = p (p_e - v) + v   if p >= 0,    p (v - p_s) + v   otherwise,   i = 0..l-1
// (p = 0: linear interpolation; |p| <= 1: monotone in i). The rational form's weights
// come from the same rule with p = p_w, p_s = w_0 = 1, p_e = w_n = w_e (seed 000
// section 4.2; w_e = 1 gives the polynomial).
//
// The solve (seed 000 section 4, with the scale taken out). The paper minimizes
// |P(s_t) - P_e| over the two free control curvatures, s_t following from the turning
// theta_d by eq. 8 or 11. Here the problem is moved to the normalized frame (start
// at the origin heading along +x, chord length 1) and written with the turning rates
// k_i = L kappa_i per unit tau, in which eq. 8/11 is linear: theta_d = sum_i mu_i k_i
// with mu_i = integral_0^1 w_i B_i^n / sum_j w_j B_j^n (1/(n+1) for the polynomial;
// the weights are fixed during a solve). The two unknowns are q = (log L, u), where
//   k(L, u) = c0 + L c1 + u c2,   mu . c0 = theta_d,  mu . c1 = mu . c2 = 0
// (c1 carries the given end curvatures of G2 and is 0 for G1; u = 0 with c1 = 0 is the
// circular arc of turning theta_d), so the turning is met exactly for every (L, u) and
// theta_d = 0 (an S curve) needs no special case. The end point L D(k) =
// L integral_0^1 (cos theta, sin theta) d tau must equal the normalized end; this 2x2
// system is solved by Levenberg-Marquardt (Newton near the solution) with the exact
// Jacobian (differentiating under the integral on the same Gauss-Legendre nodes),
// from a few starting points. The solution is then built as an AlpCurve in the user's
// frame and checked by its own, independent adaptive evaluation before it is returned.

#include <optional>
#include <vector>

#include "core/alp_curve.h"
#include "core/hermite_end.h"
#include "core/solve_report.h"

namespace la {

/// The user's shape parameters (seed 000 sections 4.1, 4.2).
struct AlpShape {
  int degree = 3;        // n of the curvature function
  double p = 0.0;        // eq. 12 parameter for the free interior control curvatures
  bool rational = false;
  double w_e = 1.0;      // last weight (the first is 1); rational only
  double p_w = 0.0;      // eq. 12 parameter for the interior weights; rational only
};

struct AlpCurvatureCheck {
  bool has_inflection = false;         // curvature changes sign inside (0, L)
  bool monotone = false;               // curvature monotone on [0, L]
  std::vector<double> inflections;     // arc lengths of sign changes
  std::vector<double> extrema;         // arc lengths of interior curvature extrema
};

/// Inflections are the sign changes of the curvature's (numerator's) Bezier function,
/// extrema those of curvatureDerivativeNumerator(); monotone = no interior extremum
/// (a touching zero of dkappa, and a constant curvature, are monotone). Seed 000
/// section 3.4; found by Bezier subdivision (core/bernstein.h).
AlpCurvatureCheck checkCurvature(const AlpCurve& curve);

struct AlpOptions {
  double tolerance = 1e-12;  // end-point gap relative to the chord |end - start|
  int max_iterations = 100;  // Levenberg-Marquardt iterations per starting point
};

struct AlpSolve {
  std::optional<AlpCurve> curve;  // set only when report.usable()
  SolveReport report;             // residual: end-point gap / chord, measured on the curve
  AlpCurvatureCheck check;
};

/// The control curvatures (or weights) between p_s and p_e by seed 000 eq. 12: l values.
std::vector<double> alpInterpolate(double p_s, double p_e, int l, double p);

/// The weights w_0..w_n of seed 000 section 4.2 (empty for a polynomial shape).
std::vector<double> alpWeights(const AlpShape& shape);

/// continuity 1: G1 (points and tangent directions; kappa ignored), 2: G2 (and
/// curvatures). n >= 2*continuity - 1. The total turning is end.theta - start.theta
/// exactly as given (the caller chooses the winding). kBadInput for NaN/inf, coincident
/// points, continuity other than 1 or 2, a degree too small (or above 40), non-positive
/// weights; kInfeasible when no starting point leads to a solution (the message gives
/// the smallest end gap reached); kIterationLimit when the last start ran out of
/// iterations while still improving.
AlpSolve solveAlpHermite(const HermiteEnd& start, const HermiteEnd& end, int continuity, const AlpShape& shape,
                         const AlpOptions& options = {});

}  // namespace la
