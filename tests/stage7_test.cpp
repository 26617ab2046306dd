// Stage 7's last word on the cap on curvature extrema (fitting/stage7.h, keepTheCap): a
// part whose chain still keeps more extrema than the cap is replaced by a curve that has
// none, one LA segment between its ends or, closed, the circle closest to its points.
// Parts sampled from chains built with known parameters; distances measured here,
// independently of the chain fit (tests/test_support.h).

#include "fitting/stage7.h"

#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace la {
namespace {

using test::buildChain;
using test::maxDistance;
using test::sampleChain;

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
}

}  // namespace
}  // namespace la
