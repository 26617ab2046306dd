#include "fitting/quality.h"

#include <algorithm>
#include <cmath>

#include "fitting/g2_joints.h"

namespace la {
namespace {

// Samples per unit of diagonal: the polyline's sagitta kappa h^2 / 8 is then below
// 1e-6 of the diagonal for |kappa| up to ~100 / diagonal.
constexpr double kSamplesPerDiagonal = 2000.0;
constexpr int kSearchWindow = 48;  // polyline edges either side of the previous foot

double pointToEdge(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

double bboxDiagonal(const std::vector<Vec2>& points) {
  if (points.empty()) return 0.0;
  Vec2 lo = points.front(), hi = points.front();
  for (const Vec2& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

}  // namespace

std::vector<double> distancesToCurve(const Curve& curve, const std::vector<Vec2>& points, double diagonal) {
  std::vector<Vec2> poly;
  for (const CurvePiece& piece : curve.pieces) {
    const int n = std::clamp(static_cast<int>(std::ceil(piece.segment.length() / diagonal * kSamplesPerDiagonal)), 8, 200000);
    CurveSamples smp;
    piece.segment.sample(n, smp);
    poly.insert(poly.end(), smp.point.begin(), smp.point.end());
  }
  std::vector<double> out(points.size(), INFINITY);
  if (poly.size() < 2) {
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = poly.empty() ? INFINITY : (points[i] - poly[0]).norm();
    return out;
  }
  const int edges = static_cast<int>(poly.size()) - 1;
  int foot = -1;
  double prev = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    double best = INFINITY;
    int best_e = -1;
    if (foot >= 0) {
      for (int e = std::max(0, foot - kSearchWindow); e <= std::min(edges - 1, foot + kSearchWindow); ++e) {
        const double d = pointToEdge(points[i], poly[e], poly[e + 1]);
        if (d < best) best = d, best_e = e;
      }
    }
    // a jump of the foot (first point, or far from the window) gets the global search
    if (best_e < 0 || best > 2.0 * prev + 1e-3 * diagonal) {
      for (int e = 0; e < edges; ++e) {
        const double d = pointToEdge(points[i], poly[e], poly[e + 1]);
        if (d < best) best = d, best_e = e;
      }
    }
    out[i] = best;
    foot = best_e;
    prev = best;
  }
  return out;
}

QualityFigures measureQuality(const Curve& curve, const std::vector<Vec2>& points) {
  QualityFigures q;
  q.diagonal = bboxDiagonal(points);
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
