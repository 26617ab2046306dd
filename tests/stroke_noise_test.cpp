// fitting/stroke_noise.h: the noise of a stroke's points against known noise. Gaussian
// jitter of a known sigma on a smooth curve is recovered (the fourth differences cancel
// the curve's bending); a clean curve has next to none; points on a pixel grid have at
// least the quantization; and a zigzag drawn at the sampling scale (every sample a
// vertex, amplitude 10) at 1-unit noise is read as 1-unit noise, not as noise of its
// own amplitude, so the tolerance's floor does not swallow it. Noise that neighbouring
// samples share (a device's smoothing filter) is read at its own size, where the
// differences of neighbours show a sixth of it; the bending of a sparse clean curve is
// not taken for it.

#include "fitting/stroke_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace la {
namespace {

// A circle of radius 200 sampled every 2 units over 1.5 radians (or every 2 / k units,
// k = points / 150), with Gaussian noise `sigma` on each coordinate (std::mt19937, seed 7).
std::vector<Vec2> noisyArc(double sigma, int points = 150) {
  std::mt19937 rng(7);
  std::normal_distribution<double> jitter(0.0, sigma);
  std::vector<Vec2> p;
  for (int i = 0; i <= points; ++i) {
    const double a = 1.5 * i / points;
    p.emplace_back(200.0 * std::cos(a) + (sigma > 0 ? jitter(rng) : 0.0), 200.0 * std::sin(a) + (sigma > 0 ? jitter(rng) : 0.0));
  }
  return p;
}

TEST(StrokeNoise, GaussianJitterOnAnArcIsRecovered) {
  for (double sigma : {0.2, 1.0, 3.0}) {
    const Noise n = noiseOf(noisyArc(sigma));
    EXPECT_NEAR(n.sigma, sigma, 0.25 * sigma) << "sigma " << sigma;
    EXPECT_NEAR(n.floor, 4.0 * n.sigma, 1e-12);
    EXPECT_FALSE(n.on_grid);
  }
}

// The floor is where the largest of the points' deviations across the curve (normal,
// sigma) goes beyond it with a chance of 1%, at least 4 sigma: 4 sigma up to about 160
// points; for 2,000, k with 2000 erfc(k / sqrt 2) = 0.01 (4.56), so that the true curve
// itself keeps the tolerance on them.
TEST(StrokeNoise, TheFloorGrowsWithThePointsSoThatTheTrueCurveKeepsIt) {
  const Noise few = noiseOf(noisyArc(0.5, 150));
  EXPECT_NEAR(few.floor, 4.0 * few.sigma, 1e-12);
  const Noise many = noiseOf(noisyArc(0.5, 2000));
  const double k = many.floor / many.sigma;
  EXPECT_NEAR(2001.0 * std::erfc(k / std::sqrt(2.0)), 0.01, 1e-6);
  EXPECT_NEAR(k, 4.56, 0.01);
  // and it is so: the largest normal deviation of 2,000 such points, over many draws,
  // is beyond it about 1% of the time
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  int beyond = 0;
  constexpr int kDraws = 5000;
  for (int draw = 0; draw < kDraws; ++draw) {
    double most = 0.0;
    for (int i = 0; i < 2001; ++i) most = std::max(most, std::abs(normal(rng)));
    beyond += most > k;
  }
  EXPECT_NEAR(static_cast<double>(beyond) / kDraws, 0.01, 0.005);
}

TEST(StrokeNoise, ACleanCurveHasNextToNone) {
  const Noise n = noiseOf(noisyArc(0.0));
  EXPECT_LT(n.sigma, 1e-6);
}

TEST(StrokeNoise, PointsOnAPixelGridHaveTheQuantization) {
  std::vector<Vec2> p = noisyArc(0.0);
  for (Vec2& q : p) q = Vec2(std::round(q.x()), std::round(q.y()));
  const Noise n = noiseOf(p);
  EXPECT_TRUE(n.on_grid);
  EXPECT_GE(n.floor, 1.0);  // (one step: kQuantizationFloor)
  EXPECT_GE(n.sigma, std::sqrt(1.0 / 12.0));
}

// Samples 2 or 3 pixels apart along x and 3 or 4 along y (a mouse's events at speed):
// no two neighbours one pixel apart, and the grid is one pixel all the same (read as
// the smallest step, 2 and 3, it was no grid, and the pixels' rounding set no floor).
TEST(StrokeNoise, PointsSeveralPixelsApartShowTheirGrid) {
  std::vector<Vec2> p;
  double x = 0.0, y = 0.0;
  for (int i = 0; i < 40; ++i) {
    p.emplace_back(x, y);
    x += i % 2 ? 3.0 : 2.0;
    y += i % 2 ? 4.0 : 3.0;
  }
  const std::optional<PixelGrid> grid = pixelGridOf(p);
  ASSERT_TRUE(grid.has_value());
  EXPECT_DOUBLE_EQ(grid->step.x(), 1.0);
  EXPECT_DOUBLE_EQ(grid->step.y(), 1.0);
  EXPECT_GE(noiseOf(p).floor, 1.0);
  EXPECT_FALSE(pixelGridOf(noisyArc(0.3)).has_value());  // (points off any grid)
}

// Every sample a vertex: x steps by 8, y alternates +-10, with Gaussian noise of 1 on
// each coordinate. The fourth differences are all about 16 * 10 = 160, alternating in
// sign: read as noise they gave sigma ~ 28 and a floor above the zigzag's own size.
TEST(StrokeNoise, AZigzagAtTheSamplingScaleIsNotNoise) {
  std::mt19937 rng(3);
  std::normal_distribution<double> jitter(0.0, 1.0);
  std::vector<Vec2> p;
  for (int i = 0; i <= 40; ++i) p.emplace_back(8.0 * i + jitter(rng), (i % 2 ? 10.0 : -10.0) + jitter(rng));
  const Noise n = noiseOf(p);
  EXPECT_GT(n.sigma, 0.5);
  EXPECT_LT(n.sigma, 2.0);
  EXPECT_LT(n.floor, 10.0);  // under the zigzag's amplitude
}

// Legs of three samples (a vertex and two between), x by 8 and y +-10 a leg, on the
// nearest pixel: every fourth difference spans a vertex, and read as noise they put the
// floor near the zigzag's own size; left out at the corners the clean-up finds (the
// vertices), they do not.
TEST(StrokeNoise, AZigzagOfShortLegsIsNotNoiseAcrossItsCorners) {
  std::vector<Vec2> p;
  std::vector<std::size_t> vertices;
  for (int leg = 0; leg < 12; ++leg)
    for (int k = 0; k < 3; ++k) {
      if (k == 0 && leg > 0) vertices.push_back(p.size());
      const double t = k / 3.0, y0 = leg % 2 ? 10.0 : -10.0;
      p.emplace_back(std::round(8.0 * (leg + t)), std::round(y0 - 2.0 * y0 * t));
    }
  p.emplace_back(96.0, 10.0);
  const Noise all = noiseOf(p);
  EXPECT_GT(all.floor, 5.0) << "the vertices read as noise (the case this guards against)";
  // (every five neighbours span a vertex: nothing is left that shows noise; the legs'
  // rounding is under a pixel)
  EXPECT_LT(noiseOf(p, vertices).floor, 1.5);
}

// A stroke's few corners do not lower its noise: a noisy arc with two corners marked
// reads as the arc alone does.
TEST(StrokeNoise, AFewCornersLeaveTheEstimateAsItWas) {
  const std::vector<Vec2> p = noisyArc(1.0);
  EXPECT_EQ(noiseOf(p, {50, 100}).sigma, noiseOf(p).sigma);
}

// White noise of sigma 2 through the filter [1 2 1] / 4, as a tablet driver smooths its
// samples: each point keeps sqrt(6) / 4 of it (1.22), and the fourth differences of
// neighbours see a sixth of that (the filter all but cancels them). Read from every
// second and third sample, it is recovered within a fifth; the neighbours alone read
// under a third of it.
TEST(StrokeNoise, NoiseThatNeighboursShareIsReadAtItsOwnSize) {
  for (int points : {150, 600}) {
    const std::vector<Vec2> clean = noisyArc(0.0, points);
    std::mt19937 rng(5);
    std::normal_distribution<double> white(0.0, 2.0);
    std::vector<Vec2> e(clean.size() + 2);
    for (Vec2& v : e) v = Vec2(white(rng), white(rng));
    std::vector<Vec2> p = clean;
    for (std::size_t i = 0; i < p.size(); ++i) p[i] += (e[i] + 2.0 * e[i + 1] + e[i + 2]) / 4.0;
    const double kept = 2.0 * std::sqrt(6.0) / 4.0;
    EXPECT_NEAR(noiseOf(p).sigma, kept, 0.2 * kept) << points << " points";
  }
}

// A logarithmic spiral of two turns sampled at 40 points, no noise: its bending fills
// the differences of every second and third sample (16 and 81 times the neighbours'),
// and no noise is read from them.
TEST(StrokeNoise, ASparseBendingCurveIsNotSharedNoise) {
  std::vector<Vec2> p;
  for (int i = 0; i < 40; ++i) {
    const double a = 4.0 * std::acos(-1.0) * i / 39.0, r = 10.0 * std::exp(0.15 * a);
    p.emplace_back(r * std::cos(a), r * std::sin(a));
  }
  const Noise n = noiseOf(p);
  EXPECT_LT(n.sigma, 0.05) << "the spiral's steps are 2 to 9 units";
}

}  // namespace
}  // namespace la
