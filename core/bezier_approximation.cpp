#include "core/bezier_approximation.h"

#include <algorithm>
#include <cmath>

namespace la {
namespace {

constexpr int kCheckPoints = 7;    // interior arc lengths checked per piece
constexpr int kMaxDepth = 30;      // halvings of one piece; 2^-30 of a segment
// A piece is kept when its checked points are within this share of the tolerance: the
// error between them (a smooth function of the arc length) can exceed theirs a little,
// and on the shared airfoils the distance at the checked points alone reached 0.998 of it.
constexpr double kCheckedShare = 0.9;

// Distance from p to the Bezier, starting the projection at parameter t0.
double distanceToBezier(const CubicBezier& b, const Vec2& p, double t0) {
  double t = t0;
  for (int i = 0; i < 8; ++i) {  // Newton on (B(t) - p) . B'(t) = 0
    const Vec2 d = b.point(t) - p, d1 = b.derivative(t);
    const Vec2 d2 = 6.0 * (1 - t) * (b.p2 - 2.0 * b.p1 + b.p0) + 6.0 * t * (b.p3 - 2.0 * b.p2 + b.p1);
    const double g = d.dot(d1), h = d1.squaredNorm() + d.dot(d2);
    if (!(h > 0.0)) break;
    t = std::clamp(t - g / h, 0.0, 1.0);
  }
  return (b.point(t) - p).norm();
}

void approximate(const ArcLengthCurve& seg, double s0, double s1, const Vec2& a, const Vec2& b,
                 double tolerance, int depth, BezierApproximation& out) {
  const double h = s1 - s0;
  const double th0 = seg.theta(s0), th1 = seg.theta(s1);
  const double dth = th1 - th0;
  const double handle = std::abs(dth) < 1e-8 ? h / 3.0 : h * (4.0 / 3.0) * std::tan(dth / 4.0) / dth;
  const CubicBezier bez{a, a + handle * unitVector(th0), b - handle * unitVector(th1), b};
  double err = 0.0;
  for (int k = 1; k <= kCheckPoints; ++k) {
    const double f = static_cast<double>(k) / (kCheckPoints + 1);
    err = std::max(err, distanceToBezier(bez, seg.position(s0 + f * h, 1e-12), f));
  }
  if (err > kCheckedShare * tolerance && depth < kMaxDepth) {
    const double sm = 0.5 * (s0 + s1);
    const Vec2 m = seg.position(sm, 1e-12);
    approximate(seg, s0, sm, a, m, tolerance, depth + 1, out);
    approximate(seg, sm, s1, m, b, tolerance, depth + 1, out);
    return;
  }
  out.pieces.push_back(bez);
  out.max_error = std::max(out.max_error, err);
}

}  // namespace

Vec2 CubicBezier::point(double t) const {
  const double u = 1.0 - t;
  return u * u * u * p0 + 3.0 * u * u * t * p1 + 3.0 * u * t * t * p2 + t * t * t * p3;
}

Vec2 CubicBezier::derivative(double t) const {
  const double u = 1.0 - t;
  return 3.0 * u * u * (p1 - p0) + 6.0 * u * t * (p2 - p1) + 3.0 * t * t * (p3 - p2);
}

BezierApproximation approximateWithBeziers(const LaSegment& segment, double tolerance) {
  return approximateWithBeziers(LaSegmentView(segment), tolerance);
}

BezierApproximation approximateWithBeziers(const ArcLengthCurve& segment, double tolerance) {
  BezierApproximation out;
  // Start from pieces of at most a quarter turn: one cubic per quarter circle is the
  // classic bound, and it keeps the handle formula away from tan's pole. (Equal
  // pieces in s: for a curve with an inflection some get less, none more than the
  // subdivision below fixes.)
  const int pieces = ceilWithin(segment.totalTurning() / (0.5 * std::numbers::pi), 1, 1 << 16);
  Vec2 a = segment.position(0.0, 1e-12);
  for (int i = 0; i < pieces; ++i) {
    const double s0 = segment.length() * i / pieces, s1 = segment.length() * (i + 1) / pieces;
    const Vec2 b = segment.position(s1, 1e-12);
    approximate(segment, s0, s1, a, b, tolerance, 0, out);
    a = b;
  }
  return out;
}

}  // namespace la
