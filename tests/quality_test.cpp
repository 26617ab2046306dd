// fitting/quality.h: distancesToCurve against a brute-force oracle (every point against
// every edge of a dense polyline of the curve), on the shapes where following the
// previous foot along the curve goes wrong: a closed curve whose points start at its
// seam, a curve that crosses itself, two passages closer than 1% of the diagonal (a thin
// trailing edge), and points far outside the curve's bounding box.
//
// The oracle's polyline has 20,000 samples per segment, so its own error (the sagitta
// kappa h^2 / 8) is far below the 1e-6 relative resolution asked of distancesToCurve;
// the two must agree within 2e-6 of the diagonal.
//
// The curvature counts and the tightest radius (measureQuality) against curves built
// with known curvature: G2 chains of clothoids (alpha = -1, curvature linear in arc
// length) and arcs whose rises, falls, corner jumps and seams are counted by hand, as
// ../shared/tools/lacheck.py counts them (extrema_dense: reversals of the curvature along
// the whole curve, a jump at a corner included; extrema_per_part: reversals of the trend
// at the joints of each part between corners, arcs skipped).

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/curve.h"
#include "fitting/quality.h"
#include "test_support.h"

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

// A fit gone astray: the curve runs 10,000 diagonals away and back (its long edges must
// not make one coarse cell of the points' region), over points near its first segment.
TEST(DistancesToCurve, ACurveRunAwayFarFromThePoints) {
  Curve c;
  const LaSegment near(-1.0, 3.0, Vec2(0, 0), 0.3, 0.1, 2.0);
  c.pieces.push_back({near});
  const LaSegment out = LaSegment::arc(3.0e4, near.end(), near.theta(near.length()), 0.0);
  c.pieces.push_back({out, true});
  c.pieces.push_back({LaSegment::arc(3.0e4, out.end(), out.theta0() + 3.0, 0.0), true});
  Curve first;
  first.pieces.push_back({near});
  std::vector<Vec2> pts = pointsNear(first, 400, 0.05);
  expectAgrees(c, pts, 3.0);
  // Samples of the curve beyond a diagonal from the points' box count by their distance
  // to the box: at least the run's far end less the box.
  const double stray = strayFromPoints(c, pts, 3.0);
  EXPECT_GT(stray, 2.0e4);
  EXPECT_LT(stray, 3.1e4);
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

// strayWithin tells a limit the stray keeps from coarse samples, and never one it
// breaks: the half circle strays by 5 from its diameter (above), by the sagitta from
// its own points; a quarter circle's top is as far from the diameter's polyline as from
// its own end.
TEST(StrayWithin, NeverSaysWithinWhereTheStrayIsBeyond) {
  constexpr double kPi = std::numbers::pi;
  Curve half;
  half.pieces.push_back({LaSegment::arc(5.0 * kPi, Vec2(0, 0), kPi / 2, -0.2), false});
  std::vector<Vec2> diameter;
  for (int i = 0; i <= 20; ++i) diameter.emplace_back(0.5 * i, 0.0);
  for (double limit : {0.5, 2.0, 4.9, 5.0}) EXPECT_FALSE(strayWithin(half, diameter, 10.0, limit)) << limit;
  EXPECT_TRUE(strayWithin(half, diameter, 10.0, 10.0));  // its samples 10 apart: the ends and (5, 5)
  std::vector<Vec2> on;
  for (int i = 0; i <= 16; ++i) {
    const double a = kPi * (1.0 - i / 16.0);
    on.emplace_back(5.0 + 5.0 * std::cos(a), 5.0 * std::sin(a));
  }
  EXPECT_TRUE(strayWithin(half, on, 10.0, 0.5));    // the sagitta is 0.024
  EXPECT_FALSE(strayWithin(half, on, 10.0, 0.02));  // below it
  EXPECT_FALSE(strayWithin(half, on, 10.0, 0.0));
  EXPECT_FALSE(strayWithin(half, on, 10.0, NAN));
  // Wherever it says within, the dense measure agrees (limits from 0.01 to 6 over both).
  for (const auto* points : {&diameter, &on})
    for (double limit = 0.01; limit < 6.0; limit *= 1.1)
      if (strayWithin(half, *points, 10.0, limit)) {
        EXPECT_LE(strayFromPoints(half, *points, 10.0), limit) << limit;
      }
}

// strayBeyond is the dense measure where that exceeds the limit, else 0, whichever
// pass decides: the half circle's stray of 5 from its diameter, and of the sagitta from
// its own points.
TEST(StrayBeyond, TheDenseStrayWhereItExceedsTheLimitElseZero) {
  constexpr double kPi = std::numbers::pi;
  Curve half;
  half.pieces.push_back({LaSegment::arc(5.0 * kPi, Vec2(0, 0), kPi / 2, -0.2), false});
  std::vector<Vec2> diameter, on;
  for (int i = 0; i <= 20; ++i) diameter.emplace_back(0.5 * i, 0.0);
  for (int i = 0; i <= 16; ++i) {
    const double a = kPi * (1.0 - i / 16.0);
    on.emplace_back(5.0 + 5.0 * std::cos(a), 5.0 * std::sin(a));
  }
  for (const auto* points : {&diameter, &on}) {
    const double dense = strayFromPoints(half, *points, 10.0);
    for (double limit = 0.01; limit < 12.0; limit *= 1.3)
      EXPECT_EQ(strayBeyond(half, *points, 10.0, limit), dense > limit ? dense : 0.0) << limit;
  }
}


// --- Curvature extrema and the tightest radius.

constexpr double kClothoid = -1.0;  // alpha: curvature linear in arc length
constexpr double kPi = std::numbers::pi;

// The chain's own points (its diagonal is the curve's).
QualityFigures measure(const Curve& curve) {
  std::vector<LaSegment> chain;
  for (const CurvePiece& p : curve.pieces) chain.push_back(p.segment);
  return measureQuality(curve, test::sampleChain(chain, 50, 0.0, 1, curve.closed));
}

// Appends a clothoid from kappa_start to kappa_end after the curve's last segment,
// G1 there, or turned by `corner` radians and marked as a corner.
void appendClothoid(Curve& c, double length, double kappa_start, double kappa_end, double corner = 0.0) {
  const LaSegment& last = c.pieces.back().segment;
  c.pieces.push_back({LaSegment(kClothoid, length, last.end(), last.theta(last.length()) + corner, kappa_start, kappa_end),
                      corner != 0.0});
}

TEST(CurvatureExtrema, RiseFallRiseHasTwoReversals) {
  const Curve c = curveOf(test::buildChain(Vec2(0, 0), 0.0, 0.5, {{kClothoid, 1.0, 2.0}, {kClothoid, 1.0, 0.8},
                                                                  {kClothoid, 1.0, 1.5}}));
  const QualityFigures q = measure(c);
  EXPECT_EQ(q.extrema_dense, 2);  // a maximum at the first joint, a minimum at the second
  EXPECT_EQ(q.extrema_per_part, std::vector<int>{2});
  EXPECT_EQ(q.max_extrema_per_part, 2);
  EXPECT_DOUBLE_EQ(q.max_abs_kappa, 2.0);
  EXPECT_DOUBLE_EQ(q.min_radius, 0.5);
}

TEST(CurvatureExtrema, TheCountsAndTheRadiusScaleAsTheCurve) {
  // The rise-fall-rise chain 1000 times larger: the same counts, radii 1000 times larger.
  constexpr double kScale = 1000.0;
  const Curve c = curveOf(test::buildChain(Vec2(0, 0), 0.0, 0.5 / kScale,
                                           {{kClothoid, kScale, 2.0 / kScale}, {kClothoid, kScale, 0.8 / kScale},
                                            {kClothoid, kScale, 1.5 / kScale}}));
  const QualityFigures q = measure(c);
  EXPECT_EQ(q.extrema_dense, 2);
  EXPECT_EQ(q.extrema_per_part, std::vector<int>{2});
  EXPECT_NEAR(q.min_radius, 0.5 * kScale, 1e-12 * kScale);
}

TEST(CurvatureExtrema, ArcsAreSkippedAndInflectionsAreNoExtrema) {
  // rise 0.5 -> 2, an arc of curvature 2, fall 2 -> 0 (an inflection end), fall 0 -> -1:
  // one maximum (the plateau, counted once) and one inflection.
  Curve c = curveOf(test::buildChain(Vec2(0, 0), 0.0, 0.5, {{kClothoid, 1.0, 2.0}}));
  const LaSegment& rise = c.pieces.back().segment;
  c.pieces.push_back({LaSegment::arc(0.5, rise.end(), rise.theta(1.0), 2.0)});
  appendClothoid(c, 1.0, 2.0, 0.0);
  appendClothoid(c, 1.0, 0.0, -1.0);
  const QualityFigures q = measure(c);
  EXPECT_EQ(q.extrema_dense, 1);
  EXPECT_EQ(q.extrema_per_part, std::vector<int>{1});
  EXPECT_EQ(q.inflections, 1);
  EXPECT_DOUBLE_EQ(q.min_radius, 0.5);
}

TEST(CurvatureExtrema, ACornerJumpAgainstTheTrendIsOneReversalAlongTheCurve) {
  // rise 0.5 -> 2, a corner, then 1 -> 0.5: the jump down at the corner reverses the rise
  // (the side curls into the corner), and the fall goes on the same way: one reversal
  // along the curve, none inside either part.
  Curve against = curveOf(test::buildChain(Vec2(0, 0), 0.0, 0.5, {{kClothoid, 1.0, 2.0}}));
  appendClothoid(against, 1.0, 1.0, 0.5, 1.0);
  QualityFigures q = measure(against);
  EXPECT_EQ(q.extrema_dense, 1);
  EXPECT_EQ(q.extrema_per_part, (std::vector<int>{0, 0}));
  EXPECT_EQ(q.corners, 1);

  // ... and rising again after the corner: the jump is a minimum between two rises.
  Curve back = curveOf(test::buildChain(Vec2(0, 0), 0.0, 0.5, {{kClothoid, 1.0, 2.0}}));
  appendClothoid(back, 1.0, 1.0, 3.0, 1.0);
  q = measure(back);
  EXPECT_EQ(q.extrema_dense, 2);
  EXPECT_EQ(q.extrema_per_part, (std::vector<int>{0, 0}));
  EXPECT_DOUBLE_EQ(q.min_radius, 1.0 / 3.0);

  // A jump with the trend (up, then on rising) is no reversal.
  Curve with = curveOf(test::buildChain(Vec2(0, 0), 0.0, 0.5, {{kClothoid, 1.0, 2.0}}));
  appendClothoid(with, 1.0, 3.0, 4.0, 1.0);
  q = measure(with);
  EXPECT_EQ(q.extrema_dense, 0);
  EXPECT_EQ(q.extrema_per_part, (std::vector<int>{0, 0}));
}

TEST(CurvatureExtrema, ACircleOfArcsHasNoneAndItsRadius) {
  constexpr double kRadius = 2.5;
  Curve c;
  c.closed = true;
  for (int k = 0; k < 4; ++k) {
    const double a = k * kPi / 2;
    c.pieces.push_back({LaSegment::arc(kRadius * kPi / 2, kRadius * Vec2(std::cos(a), std::sin(a)), a + kPi / 2,
                                       1.0 / kRadius)});
  }
  const QualityFigures q = measure(c);
  EXPECT_EQ(q.extrema_dense, 0);
  EXPECT_EQ(q.extrema_per_part, std::vector<int>{0});
  EXPECT_DOUBLE_EQ(q.max_abs_kappa, 1.0 / kRadius);
  EXPECT_DOUBLE_EQ(q.min_radius, kRadius);
}

// lacheck.py's extrema_dense as it reads: every segment rebuilt at 2,001 samples, one walk
// over all of them with an anchor, a change beyond 1e-6 / diagonal its direction.
int lacheckReversals(const Curve& c, double diagonal) {
  std::vector<double> kappa;
  for (const CurvePiece& p : c.pieces)
    for (int i = 0; i <= 2000; ++i) kappa.push_back(p.segment.kappa(p.segment.length() * i / 2000));
  if (c.closed) kappa.push_back(kappa.front());
  const double eps = 1e-6 / diagonal;
  std::vector<int> signs;
  double anchor = kappa.front();
  for (double v : kappa)
    if (std::abs(v - anchor) > eps) signs.push_back(v > anchor ? 1 : -1), anchor = v;
  int count = 0;
  for (std::size_t i = 1; i < signs.size(); ++i) count += signs[i] != signs[i - 1];
  if (c.closed && signs.size() > 1 && signs.back() != signs.front()) ++count;
  return count;
}

// Nearly flat segments (their curvature changes by a few or tens of the threshold, less
// than it per sample near an end) are where the count walks the samples: it agrees with
// lacheck's walk on chains of them, rising and falling, open and closed. (Changes of a
// few thresholds make the count depend on the sample each walk last changed at.)
TEST(CurvatureExtrema, NearlyFlatSegmentsCountAsLacheckWalksThem) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int total = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Curve c;
    c.closed = trial % 2 == 1;
    Vec2 p(0, 0);
    double theta = 0.0, kappa = 1.0;
    const int segments = 2 + trial % 4;
    for (int k = 0; k < segments; ++k) {
      const double alpha = (unit(rng) < 0.5 ? -1.0 : 1.0) * (0.2 + 2.8 * unit(rng));
      const double next = kappa + (trial < 20 ? 6e-5 : 6e-6) * (unit(rng) - 0.5);
      const LaSegment s(alpha, 0.5 + unit(rng), p, theta, kappa, next);
      c.pieces.push_back({s});
      p = s.end(), theta = s.theta(s.length()), kappa = next;
    }
    const int expected = lacheckReversals(c, 1.0);
    EXPECT_EQ(curvatureReversals(c, 1.0), expected) << "trial " << trial;
    total += expected;
  }
  EXPECT_GT(total, 40);  // (the chains do reverse)

  // Segments whose steps between samples pass the threshold part of the way: with a
  // logarithmic spiral's curvature (alpha 1) running 1 -> 1.6 -> 1.1 -> 1.5, the step
  // changes 2.6 times along each; the threshold (the diagonal) is set between the
  // smallest and the largest.
  Curve spirals;
  Vec2 p(0, 0);
  double theta = 0.0, kappa = 1.0;
  for (double next : {1.6, 1.1, 1.5}) {
    const LaSegment s(1.0, 1.0, p, theta, kappa, next);
    spirals.pieces.push_back({s});
    p = s.end(), theta = s.theta(s.length()), kappa = next;
  }
  for (double diagonal : {1.0 / 300, 1.0 / 400, 1.0 / 500, 1.0 / 700}) {  // (eps 1e-6 / diagonal: 3e-4 to 7e-4)
    const int expected = lacheckReversals(spirals, diagonal);
    EXPECT_EQ(curvatureReversals(spirals, diagonal), expected) << diagonal;
    EXPECT_GE(expected, 2) << diagonal;
  }

  // Chains that mix such segments with nearly flat ones reversing by a few thresholds
  // (where the count depends on the sample each run left the anchor at).
  for (int trial = 0; trial < 300; ++trial) {
    Curve c;
    p = Vec2(0, 0), theta = 0.0, kappa = 1.0;
    for (int k = 0; k < 5; ++k) {
      const double alpha = unit(rng) < 0.5 ? 1.0 : -0.5 - unit(rng);
      const double change = k % 2 == 0 ? 0.6 * (unit(rng) - 0.5) : 4e-3 * (unit(rng) - 0.5);
      const LaSegment s(alpha, 1.0, p, theta, kappa, kappa + change);
      c.pieces.push_back({s});
      p = s.end(), theta = s.theta(s.length()), kappa += change;
    }
    const double diagonal = 1.0 / (1000.0 + 2000.0 * unit(rng));  // (eps 1e-3 to 3e-3)
    EXPECT_EQ(curvatureReversals(c, diagonal), lacheckReversals(c, diagonal)) << "trial " << trial;
  }
}

// An oval: rise 0.5 -> 2, fall 2 -> 0.5, twice, each segment turning pi/2 (a turning of
// pi repeated closes the curve). Two maxima and two minima, one of them at the seam.
Curve oval() {
  Curve c;
  c.closed = true;
  Vec2 p(0, 0);
  double theta = 0.0;
  for (int k = 0; k < 4; ++k) {
    const bool rising = k % 2 == 0;
    c.pieces.push_back({LaSegment::withTurning(kClothoid, kPi / 2, p, theta, rising ? 0.5 : 2.0, rising ? 2.0 : 0.5)});
    p = c.pieces.back().segment.end();
    theta += kPi / 2;
  }
  return c;
}

TEST(CurvatureExtrema, AClosedCurveCountsItsSeam) {
  const Curve c = oval();
  ASSERT_LT((c.pieces.back().segment.end() - c.pieces.front().segment.start()).norm(), 1e-9) << "the oval closes";
  QualityFigures q = measure(c);
  EXPECT_EQ(q.extrema_dense, 4);
  EXPECT_EQ(q.extrema_per_part, std::vector<int>{4});
  EXPECT_DOUBLE_EQ(q.min_radius, 0.5);

  // Open, the seam's minimum is gone.
  Curve open = c;
  open.closed = false;
  q = measure(open);
  EXPECT_EQ(q.extrema_dense, 3);
  EXPECT_EQ(q.extrema_per_part, std::vector<int>{3});

  // A corner at the seam (where the curvature is continuous): the part from the corner
  // round to it has 3 reversals at its joints; along the curve the seam's minimum stays.
  Curve cornered = c;
  cornered.pieces[0].corner = true;
  q = measure(cornered);
  EXPECT_EQ(q.extrema_dense, 4);
  EXPECT_EQ(q.extrema_per_part, std::vector<int>{3});
}

TEST(CurvatureExtrema, TightestRadiusOfAClothoidAndOfALine) {
  constexpr double kKappa = 4.0;
  Curve clothoid;
  clothoid.pieces.push_back({LaSegment(kClothoid, 1.0, Vec2(0, 0), 0.0, 0.0, kKappa)});
  QualityFigures q = measure(clothoid);
  EXPECT_DOUBLE_EQ(q.max_abs_kappa, kKappa);
  EXPECT_DOUBLE_EQ(q.min_radius, 1.0 / kKappa);
  EXPECT_EQ(q.extrema_dense, 0);

  Curve line;
  line.pieces.push_back({LaSegment::arc(3.0, Vec2(0, 0), 0.4, 0.0)});
  q = measure(line);
  EXPECT_EQ(q.max_abs_kappa, 0.0);
  EXPECT_EQ(q.min_radius, INFINITY);
  EXPECT_EQ(q.extrema_dense, 0);
}

TEST(CurvatureExtrema, ChangesBelowTheThresholdCountAsTheDenseWalkCountsThem) {
  // Diagonal 1, so a change counts when it exceeds 1e-6. A rise of 1.5e-6 then a fall of
  // 1.2e-6: walked along lacheck.py's 2001 samples per segment, the rise changes once,
  // at the first sample 1e-6 above the start, and leaves the anchor there; the fall ends
  // only 0.3e-6 above the start, 0.7e-6 below the anchor: no reversal. (Walked over the
  // segment ends alone, the anchor would be the top and the fall a reversal.)
  Curve c;
  c.pieces.push_back({LaSegment(kClothoid, 1.0, Vec2(0, 0), 0.0, 1.0, 1.0 + 1.5e-6)});
  appendClothoid(c, 1.0, 1.0 + 1.5e-6, 1.0 + 0.3e-6);
  const std::vector<Vec2> diagonal_one{Vec2(0, 0), Vec2(0.6, 0.8)};
  QualityFigures q = measureQuality(c, diagonal_one);
  EXPECT_EQ(q.extrema_dense, 0);
  // A fall of 2.6e-6 ends 1.1e-6 below the anchor: a reversal.
  c.pieces.back() = {LaSegment(kClothoid, 1.0, c.pieces.back().segment.start(), c.pieces.back().segment.theta0(),
                               1.0 + 1.5e-6, 1.0 - 1.1e-6)};
  q = measureQuality(c, diagonal_one);
  EXPECT_EQ(q.extrema_dense, 1);
  // The joints see the trends however small: a maximum.
  EXPECT_EQ(q.extrema_per_part, std::vector<int>{1});
}

}  // namespace
}  // namespace la
