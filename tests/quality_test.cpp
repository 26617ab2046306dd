// fitting/quality.h: distancesToCurve against a brute-force oracle (every point against
// every edge of a dense polyline of the curve), on the shapes where following the
// previous foot along the curve goes wrong: a closed curve whose points start at its
// seam, a curve that crosses itself, two passages closer than 1% of the diagonal (a thin
// trailing edge), and points far outside the curve's bounding box.
//
// The oracle's polyline has 20,000 samples per segment, so its own error (the sagitta
// kappa h^2 / 8) is far below the 1e-6 relative resolution asked of distancesToCurve;
// the two must agree within 2e-6 of the diagonal.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/curve.h"
#include "fitting/quality.h"

namespace la {
namespace {

constexpr double kResolution = 1e-6;
constexpr double kAgreement = 2e-6;  // relative to the diagonal: resolution with a factor 2
constexpr int kOracleSamples = 20000;

std::vector<double> bruteForce(const Curve& curve, const std::vector<Vec2>& points) {
  std::vector<Vec2> poly;
  for (const CurvePiece& p : curve.pieces) {
    const CurveSamples smp = p.segment.sample(kOracleSamples);
    poly.insert(poly.end(), smp.point.begin(), smp.point.end());
  }
  std::vector<double> out;
  for (const Vec2& q : points) {
    double best = INFINITY;
    for (std::size_t e = 0; e + 1 < poly.size(); ++e) best = std::min(best, distanceToSegment(q, poly[e], poly[e + 1]));
    out.push_back(best);
  }
  return out;
}

void expectAgrees(const Curve& curve, const std::vector<Vec2>& points, double diagonal) {
  const std::vector<double> fast = distancesToCurve(curve, points, diagonal, kResolution);
  const std::vector<double> slow = bruteForce(curve, points);
  ASSERT_EQ(fast.size(), points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    EXPECT_NEAR(fast[i], slow[i], kAgreement * diagonal) << "point " << i << " (" << points[i].transpose() << ")";
}

// Points near the curve, in curve order: samples of it moved along the normal by a
// uniform offset in [-amplitude, amplitude] (std::mt19937, seed 11).
std::vector<Vec2> pointsNear(const Curve& curve, int per_segment, double amplitude) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> offset(-amplitude, amplitude);
  std::vector<Vec2> out;
  for (const CurvePiece& p : curve.pieces) {
    for (int k = 0; k < per_segment; ++k) {
      const double s = p.segment.length() * (k + 0.5) / per_segment;
      const Vec2 t = p.segment.tangent(s);
      out.push_back(p.segment.position(s) + offset(rng) * Vec2(-t.y(), t.x()));
    }
  }
  return out;
}

TEST(DistancesToCurve, ClosedCircleFromTheSeam) {
  // A unit circle as four quarter arcs, points starting just before the seam (angle 0)
  // so that the first point's foot is on the last arc and the next on the first.
  Curve c;
  c.closed = true;
  for (int k = 0; k < 4; ++k) {
    const double a = k * std::numbers::pi / 2;
    c.pieces.push_back({LaSegment::arc(std::numbers::pi / 2, Vec2(std::cos(a), std::sin(a)), a + std::numbers::pi / 2, 1.0)});
  }
  std::vector<Vec2> pts;
  for (int k = -5; k < 60; ++k) {
    const double a = k * 0.1;
    pts.push_back((1.0 + 0.01 * std::sin(7.0 * k)) * Vec2(std::cos(a), std::sin(a)));
  }
  expectAgrees(c, pts, 2.0 * std::sqrt(2.0));
}

TEST(DistancesToCurve, ThinLensFromItsSharpEnd) {
  // A closed lens like an airfoil's trailing edge: two circular arcs of sagitta 0.006
  // between (1, 0) and (0, 0), corners at both ends. The points start at the sharp end,
  // just past the seam (nearest the bottom arc's end), then run along the top arc, which
  // near the tip is less than 1% of the diagonal from the bottom one.
  constexpr double kSagitta = 0.006;
  const double radius = (0.25 + kSagitta * kSagitta) / (2.0 * kSagitta);
  const double half = std::asin(0.5 / radius);
  Curve c;
  c.closed = true;
  c.pieces.push_back({LaSegment::arc(2.0 * half * radius, Vec2(1.0, 0.0), std::numbers::pi - half, 1.0 / radius), true});
  c.pieces.push_back({LaSegment::arc(2.0 * half * radius, Vec2(0.0, 0.0), -half, 1.0 / radius), true});
  std::vector<Vec2> pts{Vec2(1.0002, -0.0001)};
  for (int k = 1; k <= 30; ++k) {
    const double x = 1.0 - 0.01 * k;
    pts.push_back(Vec2(x, 4.0 * kSagitta * x * (1.0 - x) + 0.0002 * std::sin(3.0 * k)));
  }
  expectAgrees(c, pts, 1.0);
}

TEST(DistancesToCurve, ThinTrailingEdgeAndSelfCrossing) {
  // A long thin loop: out along y = +0.004 bending down, back along y = -0.004 (the two
  // passages 0.8% of the diagonal apart), then a figure-eight-like crossing arc.
  Curve c;
  c.pieces.push_back({LaSegment::arc(1.0, Vec2(0.0, 0.004), 0.0, 0.0)});
  c.pieces.push_back({LaSegment::arc(std::numbers::pi * 0.004, Vec2(1.0, 0.004), 0.0, -1.0 / 0.004)});
  c.pieces.push_back({LaSegment::arc(1.0, Vec2(1.0, -0.004), std::numbers::pi, 0.0)});
  c.pieces.push_back({LaSegment::arc(std::numbers::pi, Vec2(0.0, -0.004), std::numbers::pi, -1.0 / 0.5)});
  const std::vector<Vec2> pts = pointsNear(c, 40, 0.003);
  expectAgrees(c, pts, 1.5);
}

TEST(DistancesToCurve, PointsFarOutsideAndNearAClothoid) {
  Curve c;
  c.pieces.push_back({LaSegment(-1.0, 3.0, Vec2(0, 0), 0.3, 0.1, 2.0)});
  std::vector<Vec2> pts = pointsNear(c, 50, 0.05);
  pts.push_back(Vec2(100.0, -50.0));
  pts.push_back(Vec2(-3.0, 0.5));
  pts.push_back(Vec2(0.5, 40.0));
  expectAgrees(c, pts, 3.0);
}

// strayFromPoints against closed forms: a half circle of radius 5 over points along its
// diameter strays by 5 (its top; the polyline of the points is the diameter), the same
// half circle over points on it by at most the sagitta of their chords; a segment's
// gaps and corners of the polyline do not matter, only where the curve goes.
TEST(StrayFromPoints, HalfCircleOverItsDiameterAndOverItsOwnPoints) {
  constexpr double kPi = std::numbers::pi;
  Curve half;
  half.pieces.push_back({LaSegment::arc(5.0 * kPi, Vec2(0, 0), kPi / 2, -0.2), false});  // (0,0) over (5,5) to (10,0)
  std::vector<Vec2> diameter;
  for (int i = 0; i <= 20; ++i) diameter.emplace_back(0.5 * i, 0.0);
  EXPECT_NEAR(strayFromPoints(half, diameter, 10.0), 5.0, 1e-3);
  std::vector<Vec2> on;
  constexpr int kChords = 16;
  for (int i = 0; i <= kChords; ++i) {
    const double a = kPi * (1.0 - static_cast<double>(i) / kChords);
    on.emplace_back(5.0 + 5.0 * std::cos(a), 5.0 * std::sin(a));
  }
  const double sagitta = 5.0 * (1.0 - std::cos(kPi / kChords / 2));
  const double stray = strayFromPoints(half, on, 10.0);
  EXPECT_LE(stray, sagitta * (1 + 1e-6));
  EXPECT_GE(stray, 0.9 * sagitta);  // a sample near the middle of some chord
}

}  // namespace
}  // namespace la
