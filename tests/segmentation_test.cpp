// Stage 3, splitting the smoothed B-spline at inflections and curvature extrema
// (fitting/segmentation.h, segmentSpline).
//
// The splines are built here, not by the smoothing stage: least-squares cubic B-splines
// (Eigen QR on the basis functions of CubicBSpline::basis) through dense samples of
// curves whose inflections and curvature extrema are known in closed form:
//  - the graph y = sin x: the x control points are the Greville abscissae, so x(t) = t
//    exactly and a split's parameter is its x. kappa(x) = -sin x / (1 + cos^2 x)^(3/2),
//    zero at k pi (inflections), and
//      dkappa/dx = -cos x (4 - 2 cos^2 x) / (1 + cos^2 x)^(5/2),
//    zero only where cos x = 0: the extrema are exactly at pi/2 + k pi, |kappa| = 1;
//  - the ellipse (a cos t, b sin t), a > b: kappa = ab / (a^2 sin^2 t + b^2 cos^2 t)^(3/2),
//    extrema exactly at the vertices t = k pi/2 (a/b^2 and b/a^2), no inflection;
//  - the circle: constant curvature, so every extremum of its spline is noise;
//  - the ellipse with a small wobble along its normal, whose curvature ripples make many
//    extrema of low persistence.
// Positions are compared in the parameter t (for the ellipse, the curve's own angle
// parameter: the spline is fitted at those t); turning is measured here from dense
// tangent angles of the spline.

#include "fitting/segmentation.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <string>
#include <vector>

#include "core/bspline.h"

namespace la {
namespace {

constexpr double kPi = std::numbers::pi;

// ---------------------------------------------------------------------------------
// Splines fitted here.

// Least-squares control points of `shape`'s basis for samples (t_i, f(t_i)), `per_span`
// samples per span (uniform).
std::vector<Vec2> leastSquaresControl(const CubicBSpline& shape, const std::function<Vec2(double)>& f, int per_span) {
  const int free = shape.freeControlCount();
  const std::vector<double> breaks = shape.breaks();
  std::vector<double> ts;
  for (std::size_t j = 0; j + 1 < breaks.size(); ++j)
    for (int k = 0; k < per_span; ++k) ts.push_back(breaks[j] + (breaks[j + 1] - breaks[j]) * (k + 0.5) / per_span);
  if (!shape.isPeriodic()) ts.front() = breaks.front(), ts.back() = breaks.back();
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(ts.size()), free);
  Eigen::MatrixXd b(static_cast<Eigen::Index>(ts.size()), 2);
  for (std::size_t r = 0; r < ts.size(); ++r) {
    double ders[4][4];
    const int i = shape.span(ts[r]);
    shape.basis(i, ts[r], ders, 0);
    for (int j = 0; j < 4; ++j) a(static_cast<Eigen::Index>(r), shape.controlIndex(i - 3 + j)) += ders[0][j];
    const Vec2 p = f(ts[r]);
    b(static_cast<Eigen::Index>(r), 0) = p.x();
    b(static_cast<Eigen::Index>(r), 1) = p.y();
  }
  const Eigen::MatrixXd x = a.colPivHouseholderQr().solve(b);
  std::vector<Vec2> control;
  for (int j = 0; j < free; ++j) control.emplace_back(x(j, 0), x(j, 1));
  return control;
}

std::vector<double> uniformBreaks(double t0, double t1, int spans) {
  std::vector<double> breaks;
  for (int k = 0; k <= spans; ++k) breaks.push_back(t0 + (t1 - t0) * k / spans);
  return breaks;
}

// The graph (t, g(t)) over the breaks, open clamped; x(t) = t exactly (the x control
// points are the Greville abscissae), y by least squares.
CubicBSpline graphSpline(const std::function<double(double)>& g, const std::vector<double>& breaks) {
  const int spans = static_cast<int>(breaks.size()) - 1;
  const CubicBSpline shape = CubicBSpline::clamped(breaks, std::vector<Vec2>(spans + 3, Vec2::Zero()));
  std::vector<Vec2> control = leastSquaresControl(shape, [&](double t) { return Vec2(t, g(t)); }, 12);
  const auto& knots = shape.knots();
  for (int k = 0; k < spans + 3; ++k) control[k].x() = (knots[k + 1] + knots[k + 2] + knots[k + 3]) / 3.0;
  return CubicBSpline::clamped(breaks, control);
}

CubicBSpline graphSpline(const std::function<double(double)>& g, double x0, double x1, int spans) {
  return graphSpline(g, uniformBreaks(x0, x1, spans));
}

// A closed curve c(t), t in [0, 2 pi), as a periodic spline with uniform spans.
CubicBSpline closedSpline(const std::function<Vec2(double)>& c, int spans, int samples_per_span = 12) {
  const std::vector<double> breaks = uniformBreaks(0.0, 2.0 * kPi, spans);
  const CubicBSpline shape = CubicBSpline::periodic(breaks, std::vector<Vec2>(spans, Vec2::Zero()));
  return CubicBSpline::periodic(breaks, leastSquaresControl(shape, c, samples_per_span));
}

// The test curves.
constexpr double kSineX0 = 0.3, kSineX1 = 4.0 * kPi - 0.5;  // ends away from every feature
double sineKappa(double x) { return -std::sin(x) / std::pow(1.0 + std::cos(x) * std::cos(x), 1.5); }
CubicBSpline sineSpline() { return graphSpline([](double x) { return std::sin(x); }, kSineX0, kSineX1, 120); }

constexpr double kA = 2.0, kB = 1.0;  // ellipse semi-axes: kappa from 0.25 to 2
Vec2 ellipse(double t) { return {kA * std::cos(t), kB * std::sin(t)}; }
double ellipseKappa(double t) {
  return kA * kB / std::pow(kA * kA * std::sin(t) * std::sin(t) + kB * kB * std::cos(t) * std::cos(t), 1.5);
}

// ---------------------------------------------------------------------------------
// Measurements of our own.

std::vector<SplitPoint> splitsOfKind(const Segmentation& s, SplitKind kind) {
  std::vector<SplitPoint> out;
  for (const SplitPoint& p : s.splits)
    if (p.kind == kind) out.push_back(p);
  return out;
}

// Distance between parameters on a circle of period 2 pi.
double cyclicDistance(double a, double b) { return std::abs(std::remainder(a - b, 2.0 * kPi)); }

// Local extrema of the spline's curvature on a dense uniform grid (strict, cyclic for a
// periodic spline): how many extrema the segmentation has to deal with.
int denseCurvatureExtrema(const CubicBSpline& s, int n = 20000) {
  std::vector<double> k(n);
  for (int i = 0; i < n; ++i) k[i] = s.curvature(s.tMin() + (s.tMax() - s.tMin()) * i / n);
  int count = 0;
  const bool cyc = s.isPeriodic();
  for (int i = cyc ? 0 : 1; i < (cyc ? n : n - 1); ++i) {
    const double a = k[(i + n - 1) % n], b = k[i], c = k[(i + 1) % n];
    if ((b > a && b > c) || (b < a && b < c)) ++count;
  }
  return count;
}

// Turning of the spline from t0 to t1 > t0 (may pass the seam of a periodic spline),
// summed from dense tangent angles.
double turningBetween(const CubicBSpline& s, double t0, double t1) {
  constexpr int kSteps = 2000;
  double total = 0.0, prev = angleOf(s.evaluate(t0, 1));
  for (int i = 1; i <= kSteps; ++i) {
    const double a = angleOf(s.evaluate(t0 + (t1 - t0) * i / kSteps, 1));
    total += wrapAngle(a - prev);
    prev = a;
  }
  return total;
}

// ---------------------------------------------------------------------------------
// Open: the sine wave.

// Three periods' worth of y = sin x on [0.3, 4 pi - 0.5]: the ends, the four extrema at
// pi/2 + k pi with their curvature, and the three inflections at k pi between them,
// alternating, in parameter order; nothing else (every piece turns pi/4 < 2).
TEST(SegmentSpline, SineWaveSplitsAtItsInflectionsAndCurvatureExtrema) {
  const CubicBSpline s = sineSpline();
  for (double x : {1.0, 5.0, 11.0}) ASSERT_NEAR(s.point(x).x(), x, 1e-12);  // x(t) = t
  const Segmentation seg = segmentSpline(s);
  ASSERT_FALSE(seg.closed);
  ASSERT_EQ(seg.splits.size(), 9u);
  EXPECT_EQ(seg.pieceCount(), 8u);
  EXPECT_EQ(seg.splits.front().kind, SplitKind::kEnd);
  EXPECT_EQ(seg.splits.back().kind, SplitKind::kEnd);
  EXPECT_DOUBLE_EQ(seg.splits.front().t, kSineX0);
  EXPECT_DOUBLE_EQ(seg.splits.back().t, kSineX1);
  double worst_extremum = 0.0, worst_inflection = 0.0;
  for (int k = 0; k < 7; ++k) {
    const SplitPoint& p = seg.splits[1 + k];
    SCOPED_TRACE("split " + std::to_string(1 + k) + " at t " + std::to_string(p.t));
    if (k % 2 == 0) {  // extremum at pi/2 + (k/2) pi
      ASSERT_EQ(p.kind, SplitKind::kExtremum);
      const double truth = kPi / 2 + (k / 2) * kPi;
      worst_extremum = std::max(worst_extremum, std::abs(p.t - truth));
      EXPECT_NEAR(p.t, truth, 0.005);
      EXPECT_NEAR(p.kappa, sineKappa(truth), 2e-3) << "curvature at the extremum";
    } else {  // inflection at ((k + 1)/2) pi
      ASSERT_EQ(p.kind, SplitKind::kInflection);
      const double truth = (k + 1) / 2 * kPi;
      worst_inflection = std::max(worst_inflection, std::abs(p.t - truth));
      EXPECT_NEAR(p.t, truth, 1e-4);
      EXPECT_EQ(p.kappa, 0.0);
    }
  }
  for (std::size_t i = 1; i < seg.splits.size(); ++i) EXPECT_LT(seg.splits[i - 1].t, seg.splits[i].t);
  std::printf("sine: extrema within %.2g of pi/2 + k pi, inflections within %.2g of k pi\n", worst_extremum,
              worst_inflection);
}

// The same sine with few spans (3 per quarter wave) and knots exactly at the extrema
// pi/2 + k pi: the curvature of the spline peaks at the knots themselves (a kink: d kappa/dt
// jumps there and changes sign, checked here), found by the sign change across the knot
// rather than as a root of a span's quintic. The extrema are still found, at the knots.
TEST(SegmentSpline, ExtremaOnKnotsAreFound) {
  std::vector<double> breaks{kSineX0};
  for (int k = 0; k < 4; ++k) breaks.push_back(kPi / 2 + k * kPi);
  breaks.push_back(kSineX1);
  std::vector<double> fine;
  for (std::size_t j = 0; j + 1 < breaks.size(); ++j)
    for (int k = 0; k < 6; ++k) fine.push_back(breaks[j] + (breaks[j + 1] - breaks[j]) * k / 6);
  fine.push_back(kSineX1);
  const CubicBSpline s = graphSpline([](double x) { return std::sin(x); }, fine);
  int kinks = 0;
  for (int k = 0; k < 4; ++k) {
    const double knot = kPi / 2 + k * kPi, h = 1e-6;
    const double before = (s.curvature(knot - h) - s.curvature(knot - 2 * h)) / h;
    const double after = (s.curvature(knot + 2 * h) - s.curvature(knot + h)) / h;
    if (before * after < 0.0) ++kinks;
  }
  std::printf("sine with knots at its extrema: %d of 4 curvature extrema on knots\n", kinks);
  ASSERT_GE(kinks, 2) << "the test needs curvature extrema sitting on knots";
  const std::vector<SplitPoint> ext = splitsOfKind(segmentSpline(s), SplitKind::kExtremum);
  ASSERT_EQ(ext.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(ext[k].t, kPi / 2 + k * kPi, 0.01) << "extremum " << k;
}

// Left turn positive: the crest of y = sin x (a right turn) has kappa ~ -1, the trough ~ +1.
TEST(SegmentSpline, ExtremumCurvatureHasTheSignOfTheTurn) {
  const Segmentation seg = segmentSpline(sineSpline());
  const std::vector<SplitPoint> ext = splitsOfKind(seg, SplitKind::kExtremum);
  ASSERT_EQ(ext.size(), 4u);
  EXPECT_LT(ext[0].kappa, -0.9);
  EXPECT_GT(ext[1].kappa, 0.9);
  EXPECT_LT(ext[2].kappa, -0.9);
  EXPECT_GT(ext[3].kappa, 0.9);
}

// On part of the spline, [2, 9]: the ends are the given ones and only what lies
// strictly inside is split: the extrema at 3 pi/2 and 5 pi/2 (not pi/2 or 7 pi/2), the
// inflections at pi (between the end at 2, kappa < 0, and 3 pi/2, kappa > 0) and 2 pi
// (not 3 pi > 9; from 5 pi/2 to the end at 9 kappa stays negative).
TEST(SegmentSpline, PartOfAnOpenSplineSplitsOnlyInside) {
  const CubicBSpline s = sineSpline();
  const Segmentation seg = segmentSpline(s, 2.0, 9.0);
  ASSERT_EQ(seg.splits.size(), 6u);
  EXPECT_EQ(seg.splits.front().kind, SplitKind::kEnd);
  EXPECT_DOUBLE_EQ(seg.splits.front().t, 2.0);
  EXPECT_EQ(seg.splits.back().kind, SplitKind::kEnd);
  EXPECT_DOUBLE_EQ(seg.splits.back().t, 9.0);
  EXPECT_EQ(seg.splits[1].kind, SplitKind::kInflection);
  EXPECT_NEAR(seg.splits[1].t, kPi, 1e-4);
  EXPECT_EQ(seg.splits[2].kind, SplitKind::kExtremum);
  EXPECT_NEAR(seg.splits[2].t, 1.5 * kPi, 0.005);
  EXPECT_EQ(seg.splits[3].kind, SplitKind::kInflection);
  EXPECT_NEAR(seg.splits[3].t, 2.0 * kPi, 1e-4);
  EXPECT_EQ(seg.splits[4].kind, SplitKind::kExtremum);
  EXPECT_NEAR(seg.splits[4].t, 2.5 * kPi, 0.005);
}

// Checks what max_extrema and the inflection rule promise on the sine: at most `cap`
// extrema (at least cap - 1: removal goes by pairs or single end extrema), each still at
// a true extremum; between consecutive kept bounds (ends and extrema) exactly one
// inflection, at a true one, where their curvatures have opposite signs, none otherwise.
void expectCappedSine(int cap) {
  SCOPED_TRACE("max_extrema " + std::to_string(cap));
  const CubicBSpline s = sineSpline();
  SegmentationOptions o;
  o.max_extrema = cap;
  const Segmentation seg = segmentSpline(s, o);
  const int kept = static_cast<int>(splitsOfKind(seg, SplitKind::kExtremum).size());
  EXPECT_LE(kept, cap);
  EXPECT_GE(kept, std::max(0, cap - 1));
  std::vector<SplitPoint> bounds;  // ends and extrema
  int inflections_between = 0;
  for (const SplitPoint& p : seg.splits) {
    if (p.kind == SplitKind::kExtremum) {
      const double k = std::round((p.t - kPi / 2) / kPi);
      EXPECT_NEAR(p.t, kPi / 2 + k * kPi, 0.005) << "kept extremum off the true ones";
    }
    if (p.kind == SplitKind::kInflection) {
      EXPECT_NEAR(p.t, std::round(p.t / kPi) * kPi, 1e-4) << "inflection off the true ones";
      ++inflections_between;
      continue;
    }
    if (p.kind == SplitKind::kTurning) continue;
    if (!bounds.empty()) {
      const bool opposite = (bounds.back().kappa < 0.0) != (p.kappa < 0.0);
      EXPECT_EQ(inflections_between, opposite ? 1 : 0)
          << "between t " << bounds.back().t << " (kappa " << bounds.back().kappa << ") and t " << p.t << " (kappa "
          << p.kappa << ")";
    }
    bounds.push_back(p);
    inflections_between = 0;
  }
}

TEST(SegmentSpline, MaxExtremaCapsTheExtremaKept) {
  for (int cap : {0, 1, 2, 3}) expectCappedSine(cap);
  // A cap above the count changes nothing.
  SegmentationOptions o;
  o.max_extrema = 10;
  EXPECT_EQ(splitsOfKind(segmentSpline(sineSpline(), o), SplitKind::kExtremum).size(), 4u);
}

// ---------------------------------------------------------------------------------
// Closed: ellipse and circle.

// An ellipse 2:1: closed, four extrema at the vertices t = k pi/2 with curvature a/b^2
// and b/a^2, no inflection, no turning cut (each quarter turns pi/2 < 2).
TEST(SegmentSpline, EllipseHasFourExtremaAtItsVerticesAndNoInflection) {
  const CubicBSpline s = closedSpline(ellipse, 64);
  const Segmentation seg = segmentSpline(s);
  ASSERT_TRUE(seg.closed);
  EXPECT_EQ(splitsOfKind(seg, SplitKind::kInflection).size(), 0u);
  const std::vector<SplitPoint> ext = splitsOfKind(seg, SplitKind::kExtremum);
  ASSERT_EQ(ext.size(), 4u);
  EXPECT_EQ(seg.splits.size(), 4u);
  EXPECT_EQ(seg.pieceCount(), 4u);
  std::vector<bool> found(4, false);
  double worst = 0.0;
  for (const SplitPoint& p : ext) {
    const int k = static_cast<int>(std::lround(p.t / (kPi / 2))) % 4;
    const double truth = k * kPi / 2;
    worst = std::max(worst, cyclicDistance(p.t, truth));
    EXPECT_LT(cyclicDistance(p.t, truth), 0.005) << "extremum at t " << p.t;
    EXPECT_NEAR(p.kappa, ellipseKappa(truth), 0.01 * ellipseKappa(truth)) << "extremum at t " << p.t;
    EXPECT_FALSE(found[k]) << "vertex " << k << " twice";
    found[k] = true;
  }
  std::printf("ellipse: extrema within %.2g of the vertices\n", worst);
  for (std::size_t i = 1; i < seg.splits.size(); ++i) EXPECT_LT(seg.splits[i - 1].t, seg.splits[i].t);
}

// The same ellipse with max_piece_turning 0.5: every quarter is cut into ceil((pi/2)/0.5)
// = 4 parts of equal turning (measured here), 16 pieces in all.
TEST(SegmentSpline, PiecesTurningTooMuchAreCutIntoEqualTurns) {
  const CubicBSpline s = closedSpline(ellipse, 64);
  SegmentationOptions o;
  o.max_piece_turning = 0.5;
  const Segmentation seg = segmentSpline(s, o);
  ASSERT_EQ(seg.splits.size(), 16u);
  EXPECT_EQ(splitsOfKind(seg, SplitKind::kExtremum).size(), 4u);
  EXPECT_EQ(splitsOfKind(seg, SplitKind::kTurning).size(), 12u);
  const double period = s.tMax() - s.tMin();
  for (std::size_t i = 0; i < seg.splits.size(); ++i) {
    const double t0 = seg.splits[i].t, t1 = seg.splits[(i + 1) % seg.splits.size()].t;
    const double turn = turningBetween(s, t0, t1 > t0 ? t1 : t1 + period);
    EXPECT_NEAR(turn, kPi / 8, 0.01) << "piece " << i << " from t " << t0;
    EXPECT_LE(turn, 0.5) << "piece " << i;
  }
}

// A circle of radius 1 as a periodic spline of 12 spans: its curvature ripples around 1
// by ~2% with many local extrema (counted here), all noise. None is kept, there is no
// inflection, and the only splits are the turning cuts: ceil(2 pi / 2) = 4 pieces of
// equal turning pi/2.
TEST(SegmentSpline, CircleHasNoSignificantExtrema) {
  const CubicBSpline s = closedSpline([](double t) { return unitVector(t); }, 12);
  const int raw = denseCurvatureExtrema(s);
  std::printf("circle spline: %d local curvature extrema on a dense grid\n", raw);
  ASSERT_GE(raw, 12) << "the test needs a spline with curvature ripples";
  const Segmentation seg = segmentSpline(s);
  ASSERT_TRUE(seg.closed);
  EXPECT_EQ(splitsOfKind(seg, SplitKind::kExtremum).size(), 0u);
  EXPECT_EQ(splitsOfKind(seg, SplitKind::kInflection).size(), 0u);
  ASSERT_EQ(seg.splits.size(), 4u);
  const double period = s.tMax() - s.tMin();
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(seg.splits[i].kind, SplitKind::kTurning);
    const double t0 = seg.splits[i].t, t1 = seg.splits[(i + 1) % 4].t;
    EXPECT_NEAR(turningBetween(s, t0, t1 > t0 ? t1 : t1 + period), kPi / 2, 0.01) << "piece " << i;
  }
}

// The ellipse with a wobble along its normal, 7.5e-5 cos(40 t): it adds about
// 7.5e-5 * 40^2 / |c'(t)|^2 to the curvature, 0.12 at the sharp vertices (6% of the
// largest |kappa|, so ripple pairs differ by less than the default significance of 20%)
// and enough slope to make extrema all round (counted here). The segmentation keeps only
// the four vertices; with significance 0 it keeps the ripples.
TEST(SegmentSpline, SignificanceDropsNoiseLevelExtrema) {
  auto wobbly = [](double t) -> Vec2 {
    const Vec2 d(-kA * std::sin(t), kB * std::cos(t));
    const Vec2 normal = Vec2(d.y(), -d.x()).normalized();
    return ellipse(t) + 7.5e-5 * std::cos(40.0 * t) * normal;
  };
  const CubicBSpline s = closedSpline(wobbly, 320, 6);
  const int raw = denseCurvatureExtrema(s);
  std::printf("wobbly ellipse spline: %d local curvature extrema on a dense grid\n", raw);
  ASSERT_GE(raw, 40) << "the test needs a spline with noise-level curvature extrema";

  const Segmentation seg = segmentSpline(s);
  EXPECT_EQ(splitsOfKind(seg, SplitKind::kInflection).size(), 0u);
  const std::vector<SplitPoint> ext = splitsOfKind(seg, SplitKind::kExtremum);
  ASSERT_EQ(ext.size(), 4u);
  for (const SplitPoint& p : ext) {
    const double truth = std::round(p.t / (kPi / 2)) * kPi / 2;
    EXPECT_LT(cyclicDistance(p.t, truth), 0.05) << "extremum at t " << p.t;
    EXPECT_NEAR(p.kappa, ellipseKappa(truth), 0.1 * ellipseKappa(truth)) << "extremum at t " << p.t;
  }

  double worst = 0.0;
  for (const SplitPoint& p : ext) worst = std::max(worst, cyclicDistance(p.t, std::round(p.t / (kPi / 2)) * kPi / 2));
  SegmentationOptions all;
  all.significance = 0.0;
  const std::size_t unfiltered = splitsOfKind(segmentSpline(s, all), SplitKind::kExtremum).size();
  std::printf("wobbly ellipse: 4 extrema kept within %.2g of the vertices; %zu with significance 0\n", worst, unfiltered);
  EXPECT_GE(unfiltered, 40u);
}

// max_extrema on a closed curve: the ellipse capped at 2 keeps one maximum and one
// minimum of the curvature (extrema go in pairs), at vertices.
TEST(SegmentSpline, MaxExtremaCapsAClosedCurve) {
  const CubicBSpline s = closedSpline(ellipse, 64);
  for (int cap : {2, 3}) {
    SCOPED_TRACE("max_extrema " + std::to_string(cap));
    SegmentationOptions o;
    o.max_extrema = cap;
    const std::vector<SplitPoint> ext = splitsOfKind(segmentSpline(s, o), SplitKind::kExtremum);
    ASSERT_EQ(ext.size(), 2u);
    const auto [lo, hi] = std::minmax(ext[0].kappa, ext[1].kappa);
    EXPECT_NEAR(lo, kB / (kA * kA), 0.01);
    EXPECT_NEAR(hi, kA / (kB * kB), 0.02);
    for (const SplitPoint& p : ext) EXPECT_LT(cyclicDistance(p.t, std::round(p.t / (kPi / 2)) * kPi / 2), 0.01);
  }
  SegmentationOptions none;
  none.max_extrema = 0;
  EXPECT_EQ(splitsOfKind(segmentSpline(s, none), SplitKind::kExtremum).size(), 0u);
}

}  // namespace
}  // namespace la
