#pragma once
// What the segment constructions (3-point, inflection end) return.

#include <limits>
#include <optional>

#include "core/la_segment.h"
#include "core/solve_report.h"

namespace la {

/// Open interval of chord angles phi a construction can reach for a given turning
/// angle: phi is the angle at Q0 between Q1 - Q0 and Q2 - Q0, in the standard
/// (left-turning) form, so 0 < lo < hi < theta_d.
struct ChordAngleRange {
  double lo = std::numeric_limits<double>::quiet_NaN();
  double hi = std::numeric_limits<double>::quiet_NaN();
  bool contains(double phi) const { return lo < phi && phi < hi; }
};

struct SegmentSolve {
  std::optional<LaSegment> segment;  // set only when report.usable()
  SolveReport report;
  /// The solved shape parameter: for the 3-point construction m = log(rho_end /
  /// rho_start) (0 is the circle); for the inflection construction, alpha.
  double shape = std::numeric_limits<double>::quiet_NaN();
  double theta_d = std::numeric_limits<double>::quiet_NaN();  // |turning angle|
  double chord_angle = std::numeric_limits<double>::quiet_NaN();  // requested phi, standard form
  ChordAngleRange reachable;  // filled when infeasible
};

/// The control triangle in the standard form of DESIGN.md section 2: turning angle
/// theta_d = |angle from Q1-Q0 to Q2-Q1| and chord angle phi at Q0, both positive
/// after mirroring a right turn. Returns a kBadInput report for NaN, coincident points,
/// |theta_d| >= pi, or a chord angle outside (0, theta_d) (Q1 is not the tangent
/// intersection of a convex arc). Collinear points in order give theta_d = 0.
struct ControlTriangle {
  double theta_d = 0.0;
  double chord_angle = 0.0;
  double turn_sign = 1.0;  // +1 left, -1 right
  double chord = 0.0;      // |Q2 - Q0|
  double heading = 0.0;    // angle of Q1 - Q0
};
SolveReport analyzeTriangle(const Vec2& q0, const Vec2& q1, const Vec2& q2, ControlTriangle& out);

}  // namespace la
