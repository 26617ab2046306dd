// Stage 7's start read off the smoothing spline (fitting/spline_chain.h, chainFromSpline),
// on a part sampled from a chain built with known parameters; distances measured here,
// independently of the chain fit (tests/test_support.h).

#include "fitting/spline_chain.h"

#include "fitting/paper_stages.h"
#include "fitting/segmentation.h"

#include "tests/test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace la {
namespace {

using test::buildChain;
using test::maxDistance;
using test::sampleChain;

// A chain shot on from a held start (stage 7 in pieces: where the piece before ends)
// whose tangent is a twentieth of a radian off the spline's: its first segment takes up
// the turn, and the chain follows the spline about as closely as one shot from the
// spline's own start. (Before, every segment kept the spline's own turning, so the whole
// chain came out turned by the offset and its shots curled back towards the split points:
// 3.5 times as far from the points here; pieces of walked strokes looped hundreds of
// pixels off.)
TEST(ChainFromSpline, AHeldStartOffTheSplinesTangentTurnsOntoItInTheFirstSegment) {
  // (one turning direction, curvature 0.004 -> 0.02 -> 0.006 -> 0.015 -> 0.005)
  const std::vector<LaSegment> truth =
      buildChain({0, 0}, 0.0, 0.004, {{1.0, 120.0, 0.02}, {-1.0, 120.0, 0.006}, {0.5, 120.0, 0.015}, {1.5, 120.0, 0.005}});
  Part part;
  part.points = sampleChain(truth, 60, 0.02, 3);
  FitOptions options;
  StageTimings timings;
  const double diagonal = boundingBoxDiagonal(part.points), tolerance = 0.005 * diagonal;
  const FitContext context{options, tolerance, Noise{}, diagonal, timings};
  const PartFit fit = fitPart(part, context, true);
  ASSERT_TRUE(fit.spline.has_value());
  ASSERT_GE(fit.spans.size(), 3u);
  const CubicBSpline& spline = *fit.spline;
  const double t0 = fit.spans.front().t0, t1 = fit.spans.back().t1;
  auto shotFrom = [&](double off) {
    std::vector<PieceReport> spans = fit.spans;
    const ChainStart from{spline.point(t0), splineTangentAngle(spline, t0) + off, spline.curvature(t0)};
    return chainFromSpline(spline, spans, false, -3.0, 3.0, true, {}, from);
  };
  const std::vector<LaSegment> own = shotFrom(0.0);
  ASSERT_FALSE(own.empty());
  const double own_distance = maxDistance(own, part.points);
  for (double off : {0.05, -0.05}) {
    const std::vector<LaSegment> chain = shotFrom(off);
    ASSERT_FALSE(chain.empty()) << off;
    EXPECT_EQ(chain.front().theta0(), splineTangentAngle(spline, t0) + off);
    EXPECT_EQ(chain.front().kappaStart(), spline.curvature(t0));
    EXPECT_NEAR(std::remainder(chain.back().theta(chain.back().length()) - splineTangentAngle(spline, t1), 2.0 * M_PI), 0.0, 0.05)
        << off;
    EXPECT_LT(maxDistance(chain, part.points), 1.5 * own_distance) << off;
  }
}

}  // namespace
}  // namespace la
