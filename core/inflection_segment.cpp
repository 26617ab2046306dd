#include "core/inflection_segment.h"

#include <cmath>
#include <numbers>
#include <string>

#include "core/quadrature.h"
#include "core/root_finding.h"

namespace la {
namespace {

// F(q) = integral_0^1 exp(i theta_d u^q) du and dF/dq, with v = 1/q.
struct InflectionEval {
  Vec2 f = Vec2::Zero();
  Vec2 df_dq = Vec2::Zero();
  double chordAngle() const { return std::atan2(f.y(), f.x()); }
  double dChordAngleDv(double v) const {  // dq/dv = -1/v^2
    return -cross(f, df_dq) / f.squaredNorm() / (v * v);
  }
};

InflectionEval evalStandard(double theta_d, double v, double relative_tolerance) {
  const double q = 1.0 / v;
  auto integrand = [&](double u) -> Eigen::Matrix<double, 4, 1> {
    const double uq = std::pow(u, q);
    const double th = theta_d * uq;
    const double c = std::cos(th), s = std::sin(th);
    const double g = theta_d * uq * std::log(u);  // d theta / dq; -> 0 as u -> 0
    Eigen::Matrix<double, 4, 1> out;
    out << c, s, -g * s, g * c;  // d/dq exp(i theta) = i g exp(i theta)
    return out;
  };
  // |F| >= cos(theta_d / 2) > 0 for theta_d < pi (every tangent within theta_d/2 of
  // the mean direction), a floor for the absolute tolerance.
  const double floor = std::max(std::cos(0.5 * theta_d), 1e-3);
  const auto r = integrateAdaptive(integrand, 0.0, 1.0, relative_tolerance * floor);
  InflectionEval e;
  e.f = r.value.head<2>();
  e.df_dq = r.value.tail<2>();
  return e;
}

double alphaOfV(double v) { return -v / (1.0 - v); }
double vOfAbsAlpha(double abs_alpha) { return abs_alpha / (1.0 + abs_alpha); }

// Inflection at Q0.
SegmentSolve solveAtStart(const Vec2& q0, const Vec2& q1, const Vec2& q2, const InflectionOptions& options) {
  SegmentSolve out;
  ControlTriangle tri;
  out.report = analyzeTriangle(q0, q1, q2, tri);
  if (!out.report.usable()) return out;
  out.theta_d = tri.theta_d;
  out.chord_angle = tri.chord_angle;
  if (tri.theta_d == 0.0) {
    out.segment = LaSegment::arc(tri.chord, q0, tri.heading, 0.0);
    out.report = {SolveStatus::kConverged, 0, 0.0, "collinear control points: straight line"};
    return out;
  }
  const double theta_d = tri.theta_d, target = tri.chord_angle;
  const double v_lo = vOfAbsAlpha(options.min_abs_alpha), v_hi = vOfAbsAlpha(options.max_abs_alpha);
  InflectionEval last;
  auto residual = [&](double v) {
    last = evalStandard(theta_d, v, options.relative_tolerance);
    return std::pair{last.chordAngle() - target, last.dChordAngleDv(v)};
  };
  RootOptions root_options;
  root_options.f_tol = options.chord_tolerance * theta_d;
  root_options.x_tol = 1e-15;
  root_options.max_iterations = options.max_iterations;
  // start at the clothoid (alpha = -1, v = 1/2)
  const RootResult root = solveMonotone(residual, v_lo, v_hi, 0.5, true, root_options);
  out.report = root.report;
  if (root.report.status == SolveStatus::kInfeasible) {
    out.reachable = reachableInflectionChordAngles(theta_d, options);
    out.report.message = "no LA segment with an inflection end fits this triangle: chord angle " +
                         std::to_string(target) + " rad at the inflection end, reachable (" +
                         std::to_string(out.reachable.lo) + ", " + std::to_string(out.reachable.hi) +
                         ") rad for turning angle " + std::to_string(theta_d) + " rad";
    return out;
  }
  if (!root.report.usable()) return out;
  // `last` was evaluated at root.x. Scale the standard curve (s_d = theta_d^v) to the chord.
  const double v = root.x, q = 1.0 / v;
  const double s_d = std::pow(theta_d, v);
  const double scale = tri.chord / (s_d * last.f.norm());
  const double kappa_end = q * std::pow(theta_d, 1.0 - v);  // q s_d^(q-1)
  out.shape = alphaOfV(v);
  out.segment = LaSegment(out.shape, scale * s_d, q0, tri.heading, 0.0, tri.turn_sign * kappa_end / scale);
  return out;
}

}  // namespace

ChordAngleRange reachableInflectionChordAngles(double theta_d, const InflectionOptions& options) {
  if (!(theta_d > 0.0 && theta_d < std::numbers::pi)) return {};
  return {evalStandard(theta_d, vOfAbsAlpha(options.min_abs_alpha), options.relative_tolerance).chordAngle(),
          evalStandard(theta_d, vOfAbsAlpha(options.max_abs_alpha), options.relative_tolerance).chordAngle()};
}

SegmentSolve solveInflectionSegment(const Vec2& q0, const Vec2& q1, const Vec2& q2, InflectionEnd end,
                                    const InflectionOptions& options) {
  if (end == InflectionEnd::kStart) return solveAtStart(q0, q1, q2, options);
  // Inflection at Q2: solve the reversed triangle, then reverse the curve. Its start
  // is Q0 with heading along Q1 - Q0, so no integration is needed to place it.
  SegmentSolve out = solveAtStart(q2, q1, q0, options);
  if (out.segment) {
    const LaSegment& r = *out.segment;
    out.segment = LaSegment(r.alpha(), r.length(), q0, angleOf(q1 - q0), -r.kappaEnd(), -r.kappaStart());
  }
  return out;
}

}  // namespace la
