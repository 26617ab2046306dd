#include "core/inflection_segment.h"

#include <cmath>
#include <numbers>
#include <string>

#include "core/root_finding.h"

namespace la {
namespace {

// F(v) = integral_0^1 exp(i theta_d u^(1/v)) du. Expanding the exponential and
// integrating term by term (u^(k/v) integrates to v/(k+v)) gives a series that
// converges like theta_d^k / k! for every v in (0, 1], with no quadrature:
//   F(v) = sum_k c_k v/(k+v),   dF/dv = sum_k c_k k/(k+v)^2,   c_k = (i theta_d)^k / k!.
// For theta_d < pi the terms are below 1e-17 of the sum after kSeriesTerms terms
// (pi^40 / 40! ~ 1e-28); the largest term is ~ e^pi, so ~2 digits cancel at worst.
constexpr int kSeriesTerms = 40;

struct InflectionEval {
  Vec2 f = Vec2::Zero();
  Vec2 df_dv = Vec2::Zero();
  double chordAngle() const { return std::atan2(f.y(), f.x()); }
  double dChordAngleDv() const { return cross(f, df_dv) / f.squaredNorm(); }
};

InflectionEval evalStandard(double theta_d, double v) {
  InflectionEval e;
  double cr = 1.0, ci = 0.0;  // c_k = (i theta_d)^k / k!
  for (int k = 0; k < kSeriesTerms; ++k) {
    const double w = v / (k + v), dw = k / ((k + v) * (k + v));
    e.f += Vec2(cr * w, ci * w);
    e.df_dv += Vec2(cr * dw, ci * dw);
    const double scale = theta_d / (k + 1);  // c_{k+1} = c_k * i theta_d / (k+1)
    const double nr = -ci * scale, ni = cr * scale;
    cr = nr;
    ci = ni;
  }
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
    last = evalStandard(theta_d, v);
    return std::pair{last.chordAngle() - target, last.dChordAngleDv()};
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
  return {evalStandard(theta_d, vOfAbsAlpha(options.min_abs_alpha)).chordAngle(),
          evalStandard(theta_d, vOfAbsAlpha(options.max_abs_alpha)).chordAngle()};
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
