#pragma once
// An LA segment with an inflection (kappa = 0) at one end (seed 003 sections 2.2-2.3).
//
// A finite LA segment can have an inflection only at an end, and only for alpha < 0.
// Standard form, inflection at the origin heading +x (seed 003 eq. 2):
//   C(s) = integral_0^s exp(i t^q) dt,  q = (alpha - 1)/alpha > 1,
//   theta = s^q,  kappa = q s^(q-1)  (= (alpha-1)/alpha s^(-1/alpha), 0 at s = 0).
// With s_d = theta_d^(1/q) the end point is E = s_d integral_0^1 exp(i theta_d u^q) du,
// whose chord angle arg E falls monotonically from theta_d/2 (q -> 1, alpha -> -inf,
// a circle) to 0 (q -> inf, alpha -> 0-). Given the control triangle, the extra
// condition kappa = 0 at one end leaves alpha as the unknown: a safeguarded Newton on
// v = 1/q (bisection whenever Newton would leave the bracket) fits the chord angle.
// The integral has a power series in theta_d (see the .cpp), so no quadrature is needed.
// An inflection at the end is the reversed problem.

#include "core/segment_solve.h"

namespace la {

enum class InflectionEnd { kStart, kEnd };

struct InflectionOptions {
  double chord_tolerance = 1e-14;  // |chord angle - target| <= tol * theta_d
  int max_iterations = 100;
  /// Search range of alpha: alpha in [-max_abs_alpha, -min_abs_alpha].
  double min_abs_alpha = 1e-3;
  double max_abs_alpha = 1e6;
};

/// The LA segment through Q0, Q2 with end tangents along Q1-Q0, Q2-Q1 and zero
/// curvature at the chosen end; alpha (< 0) is solved for and returned in `shape`.
SegmentSolve solveInflectionSegment(const Vec2& q0, const Vec2& q1, const Vec2& q2, InflectionEnd end,
                                    const InflectionOptions& options = {});

/// Chord angles (measured at the inflection end) the construction reaches for a
/// turning angle theta_d: (chord(alpha = -min_abs_alpha), chord(alpha = -max_abs_alpha)),
/// inside (0, theta_d / 2).
ChordAngleRange reachableInflectionChordAngles(double theta_d, const InflectionOptions& options = {});

}  // namespace la
