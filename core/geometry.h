#pragma once
// Plane geometry shared by every layer: points are Eigen 2-vectors, angles radians.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace la {

using Vec2 = Eigen::Vector2d;

/// ceil(x) as an int in [lo, hi]; NaN gives lo. Clamped before the conversion, which is
/// undefined for a value an int cannot hold (a NaN turning, a curve turning 1e12 rad).
inline int ceilWithin(double x, int lo, int hi) {
  if (!(x > lo)) return lo;
  if (!(x < hi)) return hi;
  return static_cast<int>(std::ceil(x));
}

inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Direction angle of a vector in (-pi, pi].
inline double angleOf(const Vec2& v) { return std::atan2(v.y(), v.x()); }

/// Unit vector at angle theta.
inline Vec2 unitVector(double theta) { return {std::cos(theta), std::sin(theta)}; }

/// Angle wrapped into (-pi, pi].
inline double wrapAngle(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

/// Signed angle turning from direction a to direction b, in (-pi, pi]; left turn positive.
inline double signedAngle(const Vec2& a, const Vec2& b) {
  return std::atan2(cross(a, b), a.dot(b));
}

inline bool allFinite(const Vec2& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

/// Distance from p to the segment [a, b] (to a if the segment is a point).
inline double distanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

/// Axis-aligned bounding box (both corners at the origin for no points).
struct BoundingBox {
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();
  Vec2 centre() const { return 0.5 * (lo + hi); }
};

inline BoundingBox boundingBoxOf(const std::vector<Vec2>& points) {
  if (points.empty()) return {};
  BoundingBox box{points.front(), points.front()};
  for (const Vec2& p : points) {
    box.lo = box.lo.cwiseMin(p);
    box.hi = box.hi.cwiseMax(p);
  }
  return box;
}

/// Diagonal of the axis-aligned bounding box (0 for no points): the scale every
/// relative tolerance and figure in the project refers to.
inline double boundingBoxDiagonal(const std::vector<Vec2>& points) {
  const BoundingBox box = boundingBoxOf(points);
  return (box.hi - box.lo).norm();
}

/// Median distance between consecutive points (0 for fewer than two): the sampling step.
inline double medianStep(const std::vector<Vec2>& points) {
  std::vector<double> steps;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) steps.push_back((points[i + 1] - points[i]).norm());
  if (steps.empty()) return 0.0;
  std::nth_element(steps.begin(), steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2), steps.end());
  return steps[steps.size() / 2];
}

/// The points' least-squares line (orthogonal distances): a point on it (their
/// centroid), its unit direction, and the largest distance of the points from it.
struct FittedLine {
  Vec2 point = Vec2::Zero(), direction = Vec2::UnitX();
  double deviation = 0.0;
};
FittedLine leastSquaresLine(const std::vector<Vec2>& points);

/// Largest distance of the points from their least-squares line (0 for fewer than two).
double lineDeviation(const std::vector<Vec2>& points);

}  // namespace la
