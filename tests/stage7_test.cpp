// Stage 7 in pieces (polishInPieces), where a part's chain is past the room of its fit as
// a whole. Stage 7's last word on the cap on curvature extrema (fitting/stage7.h, keepTheCap): a
// part whose chain still keeps more extrema than the cap is replaced by a curve that has
// none, one LA segment between its ends or, closed, the circle closest to its points.
// And the circular arc between a part's ends closest to its points (closestArcPart).
// Parts sampled from chains built with known parameters; distances measured here,
// independently of the chain fit (tests/test_support.h).

#include "fitting/stage7.h"

#include "fitting/paper_stages.h"

#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <random>

namespace la {
namespace {

using test::buildChain;
using test::maxDistance;
using test::sampleChain;
using test::Spec;

// A wave between two corners: curvature 0.01 -> 0.03 -> 0.01 -> 0.03 (two extrema), its
// points noise-free.
struct CornerWave {
  std::vector<LaSegment> chain = buildChain({0, 0}, 0.0, 0.01, {{1.0, 60.0, 0.03}, {-1.0, 60.0, 0.01}, {1.0, 60.0, 0.03}});
  Part part;
  CornerWave() {
    part.points = sampleChain(chain, 30, 0.0, 1);
    part.starts_at_corner = part.ends_at_corner = true;
  }
};

struct Context {
  FitOptions options;
  StageTimings timings;
  FitContext of(double tolerance, double diagonal) { return FitContext{options, tolerance, Noise{}, diagonal, timings}; }
};

// A wave of 12 bumps (24 clothoid segments, curvature 0 -> +-0.03 -> 0, 1.8 rad each),
// 720 points with noise of 0.05: stages 2-6 prepare it, and stage 7 in pieces fits it
// piece after piece. Every joint meets G2 (measured here on the segments), and every
// point is within the tolerance of the chain.
TEST(PolishInPieces, ALongWaveComesBackG2AndWithinTheTolerance) {
  std::vector<Spec> specs;
  for (int bump = 0; bump < 12; ++bump) {
    const double sign = bump % 2 == 0 ? 1.0 : -1.0;
    specs.push_back({-1.0, 60.0, 0.03 * sign});
    specs.push_back({-1.0, 60.0, 0.0});
  }
  const std::vector<LaSegment> wave = buildChain({0, 0}, -0.9, 0.0, specs);
  Part part;
  part.points = sampleChain(wave, 30, 0.05, 7);
  Context c;
  const double tolerance = 0.3, diagonal = boundingBoxDiagonal(part.points);
  FitContext context = c.of(tolerance, diagonal);
  context.noise.sigma = 0.05;
  PartFit fit = fitPart(part, context, true);
  ASSERT_GE(fit.spans.size(), 24u) << "the wave is one piece: this test shows nothing";
  ASSERT_TRUE(polishInPieces(fit, part, context));
  for (std::size_t j = 1; j < fit.segments.size(); ++j) {
    const LaSegment &a = fit.segments[j - 1], &b = fit.segments[j];
    EXPECT_LT((a.end() - b.start()).norm(), 1e-9 * diagonal) << "joint " << j;
    EXPECT_LT(std::abs(std::remainder(a.theta(a.length()) - b.theta0(), 2.0 * std::numbers::pi)), 1e-9) << "joint " << j;
    EXPECT_LE(std::abs(a.kappaEnd() - b.kappaStart()), 1e-9 * std::max(std::abs(a.kappaEnd()), 1.0 / diagonal)) << "joint " << j;
  }
  const double deviation = maxDistance(fit.segments, part.points);
  EXPECT_LE(deviation, tolerance);
  EXPECT_NEAR(fit.max_dev, deviation, 1e-3 * diagonal);
  EXPECT_TRUE(fit.g2.usable());
  ASSERT_EQ(fit.reports.size(), fit.segments.size());
}

// Over the cap, the part becomes one LA segment from corner to corner (it keeps its ends:
// the parts beside it meet it there), its deviation the one measured here.
TEST(KeepTheCap, AnOpenPartOverItBecomesOneSegmentBetweenItsCorners) {
  const CornerWave wave;
  Context c;
  c.options.segmentation.max_extrema = 0;
  const double diagonal = boundingBoxDiagonal(wave.part.points);
  const FitContext context = c.of(1.0, diagonal);
  ASSERT_TRUE(overCap(wave.chain, false, context)) << "the wave keeps its extrema: this test shows nothing";
  PartFit fit;
  fit.segments = wave.chain;
  keepTheCap(fit, wave.part, context);
  ASSERT_EQ(fit.segments.size(), 1u);
  EXPECT_FALSE(overCap(fit.segments, false, context));
  EXPECT_LT((fit.segments.front().start() - wave.part.points.front()).norm(), 1e-9 * diagonal);
  EXPECT_LT((fit.segments.front().end() - wave.part.points.back()).norm(), 1e-9 * diagonal);
  EXPECT_NEAR(fit.max_dev, maxDistance(fit.segments, wave.part.points), 1e-3 * diagonal);
  ASSERT_EQ(fit.reports.size(), 1u);
  EXPECT_TRUE(fit.capped) << "its miss is the cap's: the pipeline tries no other fit to mend it";
}

// Without a cap, or within it, the part's chain stays as it is.
TEST(KeepTheCap, APartWithinItStaysAsItIs) {
  const CornerWave wave;
  for (int cap : {-1, 2}) {
    Context c;
    c.options.segmentation.max_extrema = cap;
    PartFit fit;
    fit.segments = wave.chain;
    keepTheCap(fit, wave.part, c.of(1.0, boundingBoxDiagonal(wave.part.points)));
    ASSERT_EQ(fit.segments.size(), wave.chain.size()) << "cap " << cap;
    EXPECT_EQ(fit.segments.back().end(), wave.chain.back().end()) << "cap " << cap;
    EXPECT_FALSE(fit.capped) << "cap " << cap;
  }
}

// A closed part (an ellipse, 4 extrema) under a cap below 4 becomes the circle closest to
// its points: a closed curve other than a circle has at least 4 extrema.
TEST(KeepTheCap, AClosedPartUnderACapBelowFourBecomesTheClosestCircle) {
  Part part;
  part.closed = true;
  std::mt19937 rng(2);
  std::normal_distribution<double> noise(0.0, 0.1);
  for (int i = 0; i < 100; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 100.0;
    part.points.push_back(Vec2(40.0 * std::cos(a), 34.0 * std::sin(a)) + Vec2(noise(rng), noise(rng)));
  }
  // (a chain whose curvature rises and falls twice round: over a cap of 2)
  const std::vector<LaSegment> over =
      buildChain({40, 0}, 0.5 * std::numbers::pi, 0.02, {{1.0, 40.0, 0.035}, {-1.0, 20.0, 0.02}, {1.0, 40.0, 0.035}, {-1.0, 20.0, 0.02}});
  Context c;
  c.options.segmentation.max_extrema = 2;
  const FitContext context = c.of(1.0, boundingBoxDiagonal(part.points));
  ASSERT_TRUE(overCap(over, true, context));
  PartFit fit;
  fit.segments = over;
  keepTheCap(fit, part, context);
  ASSERT_EQ(fit.segments.size(), 1u);
  EXPECT_TRUE(fit.segments.front().isCircular());
  EXPECT_NEAR(1.0 / std::abs(fit.segments.front().kappaStart()), 37.0, 1.5);  // between the half axes
  EXPECT_NEAR(fit.max_dev, maxDistance(fit.segments, part.points), 0.05);
  EXPECT_TRUE(fit.capped);
}

// Points on a circular arc of radius 80 turning 100 degrees: the closest arc between their
// ends is that arc, with its points on it.
TEST(ClosestArcPart, PointsOnAnArcGiveThatArc) {
  const double radius = 80.0, turning = 100.0 * std::numbers::pi / 180.0;
  Part part;
  for (int i = 0; i <= 300; ++i) {
    const double a = -0.5 * std::numbers::pi + turning * i / 300.0;
    part.points.push_back(Vec2(10.0 + radius * std::cos(a), 20.0 + radius * std::sin(a)));
  }
  Context c;
  const FitContext context = c.of(1.0, boundingBoxDiagonal(part.points));
  const std::optional<PartFit> arc = closestArcPart(part, context, "test");
  ASSERT_TRUE(arc.has_value());
  ASSERT_EQ(arc->segments.size(), 1u);
  EXPECT_NEAR(arc->segments.front().kappaStart(), 1.0 / radius, 1e-7);
  EXPECT_NEAR(arc->segments.front().length(), radius * turning, 1e-4);
  EXPECT_LT(arc->max_dev, 1e-5);
  EXPECT_LT(maxDistance(arc->segments, part.points), 1e-5);
}

// Points off any arc (a wave of two extrema, noisy, 400 points): the arc returned within a
// limit is the one returned without, its deviation the one measured here; below that
// deviation, none is.
TEST(ClosestArcPart, ALimitBelowTheClosestArcsDeviationGivesNone) {
  const std::vector<LaSegment> wave = buildChain({0, 0}, 0.0, 0.004, {{1.0, 150.0, 0.012}, {-1.0, 150.0, 0.004}, {1.0, 150.0, 0.012}});
  Part part;
  part.points = sampleChain(wave, 133, 0.2, 3);
  Context c;
  const FitContext context = c.of(1.0, boundingBoxDiagonal(part.points));
  const std::optional<PartFit> free = closestArcPart(part, context, "test");
  ASSERT_TRUE(free.has_value());
  const double deviation = maxDistance(free->segments, part.points);
  EXPECT_NEAR(free->max_dev, deviation, 1e-3 * deviation);
  ASSERT_GT(deviation, 2.0) << "the wave is nearly an arc: this test shows nothing";
  const std::optional<PartFit> within = closestArcPart(part, context, "test", 1.01 * free->max_dev);
  ASSERT_TRUE(within.has_value());
  EXPECT_EQ(within->segments.front().kappaStart(), free->segments.front().kappaStart());
  EXPECT_EQ(within->max_dev, free->max_dev);
  EXPECT_FALSE(closestArcPart(part, context, "test", 0.9 * free->max_dev).has_value());
}

}  // namespace
}  // namespace la
