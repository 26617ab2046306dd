// fitting/subdivision.h: a resampler's points between the samples are told from drawn
// ones, and the clean-up and the fit see the stroke as drawn. Known truth: noisy strokes
// (std::mt19937, the seeds below) subdivided 2-, 3- and 4-fold here, or with their steps
// filled at a fixed spacing, whose samples are known, or resampled by arc length; the
// drawn strokes themselves, a pointer walking a pixel per sample and evenly sampled
// clean curves, which are not resampled.

#include "fitting/subdivision.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "fitting/pipeline.h"
#include "fitting/stroke.h"
#include "tests/shared_data_sets.h"

namespace la {
namespace {

// A spiral-like hooked stroke: a pen-down hook, then an arc of growing
// radius, sampled about every 3 units with Gaussian noise 0.5 (seed `seed`).
Stroke drawnStroke(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.5);
  Stroke s;
  s.samples.push_back({Vec2(14.0, 6.0)});
  s.samples.push_back({Vec2(7.0, 2.5)});
  for (int i = 0; i <= 60; ++i) {
    const double a = 0.05 * i, r = 60.0 + 10.0 * a;
    s.samples.push_back({Vec2(r * std::sin(a), 60.0 - r * std::cos(a)) + Vec2(noise(rng), noise(rng))});
  }
  return s;
}

TEST(SubdivisionSamples, ASubdividedStrokesSamplesAreFound) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    const Stroke drawn = drawnStroke(seed);
    EXPECT_TRUE(subdivisionSamples(test::pointsOf(drawn)).empty()) << "seed " << seed;
    for (int k : {2, 3}) {
      const std::vector<bool> sample = subdivisionSamples(test::pointsOf(test::subdivided(drawn, k)));
      ASSERT_EQ(sample.size(), (drawn.samples.size() - 1) * k + 1) << "seed " << seed << ", " << k << "-fold";
      for (std::size_t i = 0; i < sample.size(); ++i) EXPECT_EQ(sample[i], i % k == 0) << "point " << i;
    }
    // (4-fold: every second point found first; those are 2-fold again)
    const std::vector<bool> sample = subdivisionSamples(test::pointsOf(test::subdivided(drawn, 4)));
    ASSERT_FALSE(sample.empty());
    for (std::size_t i = 0; i < sample.size(); ++i) EXPECT_EQ(sample[i], i % 2 == 0) << "point " << i;
  }
}

TEST(SubdivisionSamples, MidpointsPrintedToFourDecimalsAreStillFound) {
  Stroke printed = test::subdivided(drawnStroke(5), 2);
  for (StrokeSample& q : printed.samples) q.p = (q.p * 1e4).array().round() / 1e4;
  const std::vector<bool> sample = subdivisionSamples(test::pointsOf(printed));
  ASSERT_FALSE(sample.empty());
  for (std::size_t i = 0; i < sample.size(); ++i) EXPECT_EQ(sample[i], i % 2 == 0) << "point " << i;
}

// Where every point or many points lie at their neighbours' midpoint by the way they were
// drawn or sampled, no class stands out: a pixel stroke walked a pixel per sample (a
// digital circle, and a digital line of slope 1/2), and a clean arc sampled evenly and
// densely (its midpoints off by the sagitta only, under the rounding allowance).
TEST(SubdivisionSamples, DrawnAndEvenlySampledStrokesAreNotSubdivided) {
  std::vector<Vec2> circle, line, arc;
  for (int i = 0; i < 400; ++i) {
    const double a = 2.0 * M_PI * i / 400;
    const Vec2 q(std::round(60.0 * std::cos(a)), std::round(60.0 * std::sin(a)));
    if (circle.empty() || q != circle.back()) circle.push_back(q);
  }
  for (int x = 0; x < 120; ++x) line.emplace_back(x, std::floor(0.5 * x));
  for (int i = 0; i <= 200; ++i) arc.emplace_back(1000.0 * std::cos(1e-3 * i), 1000.0 * std::sin(1e-3 * i));
  EXPECT_TRUE(subdivisionSamples(circle).empty());
  EXPECT_TRUE(subdivisionSamples(line).empty());
  EXPECT_TRUE(subdivisionSamples(arc).empty());
}

// The clean-up of a subdivided stroke keeps exactly the drawn stroke's points (the hook
// cut as there: its reach is counted in the samples' steps), and lists the resampler's
// points as left out, on the kept polyline.
TEST(SubdivisionCleanup, ASubdividedStrokeIsCleanedAsDrawn) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Stroke drawn = drawnStroke(seed);
    const CleanStroke as_drawn = cleanStroke(drawn);
    ASSERT_GT(as_drawn.trimmed_start, 0u) << "seed " << seed;
    for (int k : {2, 3, 4}) {
      const Stroke sub = test::subdivided(drawn, k);
      const CleanStroke c = cleanStroke(sub);
      EXPECT_EQ(c.points, as_drawn.points) << "seed " << seed << ", " << k << "-fold";
      EXPECT_EQ(c.corners.size(), as_drawn.corners.size());
      EXPECT_EQ(c.removed_resampled, (drawn.samples.size() - 1) * (k - 1));
      EXPECT_EQ(sub.samples.size(), c.points.size() + c.trimmed_start + c.trimmed_end + c.removed_overlap +
                                        c.removed_invalid + c.removed_duplicates + c.removed_resampled);
      EXPECT_NEAR(c.left_out_fraction, as_drawn.left_out_fraction, 1e-12);
      for (const LeftOutPoint& l : c.left_out) {
        if (l.why == LeftOutReason::kResampled) {
          EXPECT_NE(l.sample % k, 0u);
        }
      }
    }
  }
}

// Fitted, a subdivided stroke is the drawn one: the same tolerance, the same curve.
TEST(SubdivisionFit, ASubdividedStrokeFitsAsDrawn) {
  const Stroke drawn = drawnStroke(6);
  const FitResult as_drawn = fitStroke(drawn);
  for (int k : {2, 3}) {
    const FitResult r = fitStroke(test::subdivided(drawn, k));
    EXPECT_EQ(r.tolerance, as_drawn.tolerance) << k << "-fold";
    ASSERT_EQ(r.curve.pieces.size(), as_drawn.curve.pieces.size()) << k << "-fold";
    for (std::size_t i = 0; i < r.curve.pieces.size(); ++i) {
      EXPECT_EQ(r.curve.pieces[i].segment.length(), as_drawn.curve.pieces[i].segment.length());
      EXPECT_EQ(r.curve.pieces[i].segment.kappaStart(), as_drawn.curve.pieces[i].segment.kappaStart());
    }
    // (measured on the same points; over all of them, the resampler's too)
    EXPECT_EQ(r.quality.max_dev, as_drawn.quality.max_dev);
    EXPECT_GE(r.max_dev_all_points, as_drawn.max_dev_all_points);
  }
}

// Steps filled at a fixed spacing (as an importer flattens a polyline): the samples are
// exactly the points kept, also printed to 4 decimals; the drawn strokes are not taken.
TEST(FilledStepSamples, TheSamplesOfFilledStepsAreFound) {
  for (unsigned seed : {1u, 2u, 3u, 4u}) {
    const Stroke drawn = drawnStroke(seed);
    EXPECT_TRUE(filledStepSamples(test::pointsOf(drawn)).empty()) << "seed " << seed;
    for (double step : {0.3, 1.0}) {
      Stroke filled = test::filledSteps(drawn, step);
      for (bool printed : {false, true}) {
        if (printed)
          for (StrokeSample& q : filled.samples) q.p = (q.p * 1e4).array().round() / 1e4;
        const std::vector<Vec2> p = test::pointsOf(filled);
        const std::vector<bool> sample = filledStepSamples(p);
        ASSERT_EQ(sample.size(), p.size()) << "seed " << seed << ", step " << step;
        std::size_t next = 0;  // (the drawn samples, in order, are the points kept)
        for (std::size_t i = 0; i < p.size(); ++i) {
          const bool is_sample = next < drawn.samples.size() && (p[i] - drawn.samples[next].p).norm() < 1e-3;
          EXPECT_EQ(sample[i], is_sample) << "seed " << seed << ", step " << step << ", point " << i;
          next += is_sample;
        }
        EXPECT_EQ(next, drawn.samples.size());
      }
    }
  }
}

// Resampled by arc length, the samples are gone: the points kept are those beside them
// (at most two per sample, each within a step of one), the resampler's others left out.
TEST(FilledStepSamples, ResampledByArcLengthKeepsThePointsBesideTheSamples) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const Stroke drawn = drawnStroke(seed);
    const double step = 0.4;
    const std::vector<Vec2> p = test::pointsOf(test::resampledEvenly(drawn, step));
    const std::vector<bool> sample = filledStepSamples(p);
    ASSERT_EQ(sample.size(), p.size()) << "seed " << seed;
    std::size_t kept = 0;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!sample[i]) continue;
      ++kept;
      double nearest = INFINITY;
      for (const StrokeSample& q : drawn.samples) nearest = std::min(nearest, (q.p - p[i]).norm());
      EXPECT_LE(nearest, step + 1e-9) << "seed " << seed << ", point " << i;
    }
    EXPECT_LE(kept, 2 * drawn.samples.size());
    EXPECT_GE(kept, drawn.samples.size() / 2);
  }
}

// Where points lie at their neighbours' midpoints by the way they were drawn or sampled,
// they stay: pixel strokes walked a pixel per sample (a digital circle, a digital line
// of slope 1/2, a pixel column and row with every seventh pixel skipped), evenly and densely
// sampled clean curves (each point nearly a midpoint, off by a sagitta under the
// rounding allowance: an arc, and a circle of 5,000 points) and a straight line.
TEST(FilledStepSamples, DrawnAndEvenlySampledStrokesAreNotResampled) {
  std::vector<Vec2> circle, line, column, arc, dense, straight;
  for (int i = 0; i < 400; ++i) {
    const double a = 2.0 * M_PI * i / 400;
    const Vec2 q(std::round(60.0 * std::cos(a)), std::round(60.0 * std::sin(a)));
    if (circle.empty() || q != circle.back()) circle.push_back(q);
  }
  for (int x = 0; x < 120; ++x) line.emplace_back(x, std::floor(0.5 * x));
  for (int y = 0; y < 120; ++y)
    if (y % 7 != 6) column.emplace_back(3.0, y);
  for (int x = 4; x < 60; ++x)
    if (x % 7 != 6) column.emplace_back(x, 119.0);
  for (int i = 0; i <= 200; ++i) arc.emplace_back(1000.0 * std::cos(1e-3 * i), 1000.0 * std::sin(1e-3 * i));
  for (int i = 0; i < 5000; ++i) dense.emplace_back(50.0 * std::cos(2e-3 * M_PI * i), 50.0 * std::sin(2e-3 * M_PI * i));
  for (int i = 0; i < 50; ++i) straight.emplace_back(0.5 * i, 0.25 * i);
  for (const auto* p : {&circle, &line, &column, &arc, &dense, &straight}) EXPECT_TRUE(filledStepSamples(*p).empty());
}

// A pixel stroke with its steps filled at a fraction of a pixel: the points kept are
// pixels, among them every pixel where the walk turns; the others left out lie on the
// steps between the points kept (a pixel along a row or column, where the walk goes on
// straight, is as much a midpoint as the points between).
TEST(FilledStepSamples, APixelStrokeFilledKeepsItsPixels) {
  Stroke walk;
  for (int i = 0; i < 300; ++i) {
    const double a = 1.5 * M_PI * i / 300;
    const Vec2 q(std::round(40.0 * std::cos(a) + 10.0 * std::cos(3.0 * a)), std::round(40.0 * std::sin(a)));
    if (walk.samples.empty() || q != walk.samples.back().p) walk.samples.push_back({q});
  }
  const std::vector<Vec2> pixels = test::pointsOf(walk);
  ASSERT_TRUE(filledStepSamples(pixels).empty());
  const std::vector<Vec2> p = test::pointsOf(test::filledSteps(walk, 0.25));
  const std::vector<bool> sample = filledStepSamples(p);
  ASSERT_EQ(sample.size(), p.size());
  std::vector<Vec2> kept;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!sample[i]) continue;
    EXPECT_EQ(p[i], p[i].array().round().matrix()) << "point " << i;
    kept.push_back(p[i]);
  }
  for (std::size_t i = 1; i + 1 < pixels.size(); ++i) {
    const bool turns = pixels[i - 1] + pixels[i + 1] != 2.0 * pixels[i];
    if (turns) {
      EXPECT_NE(std::find(kept.begin(), kept.end(), pixels[i]), kept.end()) << "pixel " << i;
    }
  }
  for (std::size_t i = 0; i < p.size(); ++i) {  // (left out: on the step between the kept points around it)
    if (sample[i]) continue;
    std::size_t before = i, after = i;
    while (!sample[before]) --before;
    while (!sample[after]) ++after;
    const Vec2 chord = p[after] - p[before];
    EXPECT_LE(std::abs(cross(chord.normalized(), p[i] - p[before])), 1e-9) << "point " << i;
  }
}

// Cleaned and fitted, a stroke with its steps filled is the drawn one: the same points,
// the same tolerance, the same curve; the resampler's points are left out as resampled.
TEST(FilledStepFit, AFilledStrokeFitsAsDrawn) {
  const Stroke drawn = drawnStroke(6);
  const FitResult as_drawn = fitStroke(drawn);
  const Stroke filled = test::filledSteps(drawn, 0.5);
  const CleanStroke c = cleanStroke(filled);
  EXPECT_EQ(c.points, cleanStroke(drawn).points);
  EXPECT_EQ(c.removed_resampled, filled.samples.size() - drawn.samples.size());
  const FitResult r = fitStroke(filled);
  EXPECT_EQ(r.tolerance, as_drawn.tolerance);
  ASSERT_EQ(r.curve.pieces.size(), as_drawn.curve.pieces.size());
  for (std::size_t i = 0; i < r.curve.pieces.size(); ++i)
    EXPECT_EQ(r.curve.pieces[i].segment.length(), as_drawn.curve.pieces[i].segment.length());
  EXPECT_EQ(r.quality.max_dev, as_drawn.quality.max_dev);
}

}  // namespace
}  // namespace la
