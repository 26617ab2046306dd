#include "app/gui/comb.h"

#include <algorithm>
#include <cmath>

namespace la::gui {
namespace {

// The tooth at arc length `s` of a segment: away from the centre of curvature, which for
// a left turn (kappa > 0) lies on the left normal.
void addTooth(Comb& comb, double s_curve, const Vec2& point, const Vec2& left_normal, double kappa) {
  comb.s.push_back(s_curve);
  comb.base.push_back(point);
  comb.tip.push_back(point - comb.gain * kappa * left_normal);
}

Vec2 leftNormal(double theta) { return Vec2(-std::sin(theta), std::cos(theta)); }

// Arc length of tooth k of `teeth` along a curve of length `length`.
double toothAt(int k, int teeth, double length, bool closed) {
  return closed ? length * k / teeth : length * k / std::max(1, teeth - 1);
}

}  // namespace

double maxAbsCurvature(const Curve& curve) {
  double kmax = 0.0;
  for (const CurvePiece& piece : curve.pieces)
    kmax = std::max(kmax, piece.segment.maxAbsKappa());
  return kmax;
}

Comb curvatureComb(const Curve& curve, double gain, int teeth) {
  Comb comb;
  comb.gain = gain;
  teeth = std::max(2, teeth);
  double length = 0.0;
  for (const CurvePiece& piece : curve.pieces) length += piece.segment.length();
  if (curve.pieces.empty() || !(length > 0.0)) return comb;
  int k = 0;
  double s0 = 0.0;  // where the current segment starts along the curve
  for (std::size_t i = 0; i < curve.pieces.size(); ++i) {
    const LaSegment& seg = curve.pieces[i].segment;
    const bool last = i + 1 == curve.pieces.size();
    // the envelope through the joint: this segment's side of it (at a G2 joint the same
    // tip as the one before, at a corner the other side of the jump)
    comb.envelope.push_back(seg.start() - gain * seg.kappaStart() * leftNormal(seg.theta0()));
    for (; k < teeth; ++k) {
      const double s = toothAt(k, teeth, length, curve.closed);
      if (s > s0 + seg.length() && !last) break;
      const double local = std::clamp(s - s0, 0.0, seg.length());
      addTooth(comb, s, seg.position(local), leftNormal(seg.theta(local)), seg.kappa(local));
      comb.envelope.push_back(comb.tip.back());
    }
    comb.envelope.push_back(seg.end() - gain * seg.kappaEnd() * leftNormal(seg.theta(seg.length())));
    s0 += seg.length();
  }
  if (curve.closed && !comb.envelope.empty()) comb.envelope.push_back(comb.envelope.front());
  return comb;
}

Comb curvatureComb(const std::vector<double>& s, const std::vector<Vec2>& points, const std::vector<Vec2>& normals,
                   const std::vector<double>& kappa, double gain, int teeth) {
  Comb comb;
  comb.gain = gain;
  const std::size_t n = std::min({s.size(), points.size(), normals.size(), kappa.size()});
  if (n < 2 || !(s[n - 1] > s[0])) return comb;
  teeth = std::max(2, teeth);
  std::size_t j = 1;
  for (int k = 0; k < teeth; ++k) {
    const double at = s[0] + toothAt(k, teeth, s[n - 1] - s[0], false);
    while (j + 1 < n && s[j] < at) ++j;
    const double w = s[j] > s[j - 1] ? std::clamp((at - s[j - 1]) / (s[j] - s[j - 1]), 0.0, 1.0) : 1.0;
    const Vec2 normal = ((1 - w) * normals[j - 1] + w * normals[j]).normalized();
    addTooth(comb, at - s[0], (1 - w) * points[j - 1] + w * points[j], normal, (1 - w) * kappa[j - 1] + w * kappa[j]);
  }
  // the envelope through every sample's tip: the samples are dense, joints among them
  for (std::size_t i = 0; i < n; ++i) comb.envelope.push_back(points[i] - gain * kappa[i] * normals[i]);
  return comb;
}

}  // namespace la::gui
