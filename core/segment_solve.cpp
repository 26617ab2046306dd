#include "core/segment_solve.h"

#include <cmath>
#include <numbers>

namespace la {

SolveReport analyzeTriangle(const Vec2& q0, const Vec2& q1, const Vec2& q2, ControlTriangle& out) {
  SolveReport report;
  report.status = SolveStatus::kBadInput;
  if (!allFinite(q0) || !allFinite(q1) || !allFinite(q2)) {
    report.message = "control point is NaN or infinite";
    return report;
  }
  const Vec2 a = q1 - q0, b = q2 - q1, c = q2 - q0;
  const double scale = std::max({a.norm(), b.norm(), c.norm()});
  // Coincidence relative to the triangle's own size: the construction is scale-free.
  constexpr double kCoincident = 1e-14;
  if (!(scale > 0.0) || a.norm() <= kCoincident * scale || b.norm() <= kCoincident * scale) {
    report.message = "coincident control points";
    return report;
  }
  const double turning = signedAngle(a, b);
  if (std::abs(turning) >= std::numbers::pi) {
    report.message = "turning angle >= pi: Q1 is not between the end tangents";
    return report;
  }
  out.turn_sign = turning < 0.0 ? -1.0 : 1.0;
  out.theta_d = std::abs(turning);
  out.chord_angle = out.turn_sign * signedAngle(a, c);
  out.chord = c.norm();
  out.heading = angleOf(a);
  if (out.theta_d > 0.0 && !(out.chord_angle > 0.0 && out.chord_angle < out.theta_d)) {
    report.message = "chord angle outside (0, turning angle): not a convex control triangle";
    return report;
  }
  report.status = SolveStatus::kConverged;
  report.residual = 0.0;
  report.message = "ok";
  return report;
}

}  // namespace la
