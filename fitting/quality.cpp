#include "fitting/quality.h"

#include <algorithm>
#include <cmath>

#include "fitting/g2_joints.h"

namespace la {
namespace {

constexpr int kSearchWindow = 24;  // polyline edges either side of the previous foot, to start with



}  // namespace

std::vector<double> distancesToCurve(const Curve& curve, const std::vector<Vec2>& points, double diagonal,
                                     double resolution) {
  std::vector<Vec2> poly;
  CurveSamples smp;
  for (const CurvePiece& piece : curve.pieces) {
    const LaSegment& seg = piece.segment;
    const double kmax = std::max(std::abs(seg.kappaStart()), std::abs(seg.kappaEnd()));
    const double h = std::sqrt(8.0 * resolution * diagonal / std::max(kmax, 1e-300));
    const int n = std::clamp(static_cast<int>(std::ceil(seg.length() / h)) + 1, 8, 100000);
    smp.clear();
    seg.sample(n, smp);
    poly.insert(poly.end(), smp.point.begin(), smp.point.end());
  }
  std::vector<double> out(points.size(), INFINITY);
  if (poly.size() < 2) {
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = poly.empty() ? INFINITY : (points[i] - poly[0]).norm();
    return out;
  }
  const int edges = static_cast<int>(poly.size()) - 1;
  auto nearest = [&](const Vec2& p, int lo, int hi, double& best, int& best_e) {
    for (int e = std::max(0, lo); e <= std::min(edges - 1, hi); ++e) {
      const double d = distanceToSegment(p, poly[e], poly[e + 1]);
      if (d < best) best = d, best_e = e;
    }
  };
  // Points and curve run in the same order, so each foot is searched near the last
  // one, the window growing while the best edge sits on its border (for a closed curve
  // the seam is found by the check below). The first point gets the whole curve.
  // A window can lock onto a wrong passage where the curve comes back near itself:
  // a foot further than kLostFraction of the diagonal is checked against the whole curve.
  constexpr double kLostFraction = 0.01;
  int foot = -1;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = INFINITY;
    int best_e = -1;
    if (foot < 0) {
      nearest(points[i], 0, edges - 1, best, best_e);
    } else {
      int lo = foot - kSearchWindow, hi = foot + kSearchWindow;
      nearest(points[i], lo, hi, best, best_e);
      while ((best_e == std::max(0, lo) && lo > 0) || (best_e == std::min(edges - 1, hi) && hi < edges - 1)) {
        const int width = hi - lo;
        if (best_e <= lo) {
          nearest(points[i], lo - width, lo - 1, best, best_e);
          lo -= width;
        } else {
          nearest(points[i], hi + 1, hi + width, best, best_e);
          hi += width;
        }
      }
    }
    if (best > kLostFraction * diagonal) nearest(points[i], 0, edges - 1, best, best_e);
    out[i] = best;
    foot = best_e;
  }
  return out;
}

QualityFigures measureQuality(const Curve& curve, const std::vector<Vec2>& points) {
  QualityFigures q;
  q.diagonal = boundingBoxDiagonal(points);
  const double diag = q.diagonal > 0.0 ? q.diagonal : 1.0;
  q.segments = static_cast<int>(curve.pieces.size());
  const std::vector<double> d = distancesToCurve(curve, points, diag);
  double sum = 0.0;
  for (double v : d) {
    q.max_dev = std::max(q.max_dev, v);
    sum += v * v;
  }
  q.rms_dev = d.empty() ? 0.0 : std::sqrt(sum / d.size());

  const std::size_t n = curve.pieces.size();
  auto trend = [](const LaSegment& s) {
    const double a = s.kappaStart(), b = s.kappaEnd();
    if (std::abs(b - a) <= 1e-12 * std::max({std::abs(a), std::abs(b), 1e-300})) return 0;
    return b > a ? 1 : -1;
  };
  for (std::size_t j = 0; j < n; ++j) {
    if (curve.pieces[j].corner) ++q.corners;
    const bool has_joint_before = j > 0 || (curve.closed && n > 1);
    if (!has_joint_before || curve.pieces[j].corner) continue;
    const LaSegment& a = curve.pieces[(j + n - 1) % n].segment;
    const LaSegment& b = curve.pieces[j].segment;
    q.g1_gap = std::max(q.g1_gap, std::abs(wrapAngle(a.theta(a.length()) - b.theta0())));
    q.g2_gap = std::max(q.g2_gap, relativeGap(a.kappaEnd(), b.kappaStart(), diag));
    const int ta = trend(a), tb = trend(b);
    if (ta != 0 && tb != 0 && ta != tb) ++q.extrema;
  }
  // inflections: sign changes of curvature, also across corners (the shape inflects there too)
  auto sign = [](double k) { return k > 0 ? 1 : (k < 0 ? -1 : 0); };
  int last = 0;
  for (std::size_t j = 0; j < n; ++j) {
    for (double k : {curve.pieces[j].segment.kappaStart(), curve.pieces[j].segment.kappaEnd()}) {
      const int s = sign(k);
      if (s != 0 && last != 0 && s != last) ++q.inflections;
      if (s != 0) last = s;
    }
  }
  return q;
}

}  // namespace la
