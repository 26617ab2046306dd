#pragma once
// Helpers shared by the tests of the segment constructions.

#include <Eigen/Dense>

#include "core/la_segment.h"

namespace la::test {

struct Triangle {
  Vec2 q0, q1, q2;
};

/// The control triangle of a segment: its end points and the intersection of its end
/// tangents (computed here by a 2x2 solve, independently of the constructions).
inline Triangle triangleOf(const LaSegment& seg) {
  const Vec2 p0 = seg.start(), p2 = seg.end(1e-15);
  const Vec2 t0 = seg.tangent(0.0), t1 = seg.tangent(seg.length());
  Eigen::Matrix2d m;  // p0 + a t0 = p2 - b t1
  m << t0.x(), t1.x(), t0.y(), t1.y();
  const Eigen::Vector2d ab = m.colPivHouseholderQr().solve(p2 - p0);
  return {p0, p0 + ab.x() * t0, p2};
}

inline double relDiff(double a, double b) {
  return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300});
}

}  // namespace la::test
