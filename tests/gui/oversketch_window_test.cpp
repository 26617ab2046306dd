// Oversketch through the real window (issue 17, part 2): a stroke drawn from and to an
// existing stroke replaces that part of it as one undo step, is refitted G2 and follows
// the new stroke; off, it is a stroke of its own; from an end it extends; on a closed
// stroke it replaces the shorter arc. The splice itself is tested in oversketch_test.cpp.

#include <gtest/gtest.h>

#include <QSettings>
#include <QSpinBox>
#include <QUndoStack>
#include <cmath>
#include <numbers>

#include "app/gui/oversketch.h"
#include "app/gui/selection.h"
#include "tests/gui/window_test_support.h"

namespace la::gui {
namespace {

// The old stroke: wave() (y = 300 + 90 sin(x / 110), x from 60 to 655 pixels).
double waveY(double x) { return 300 + 90 * std::sin(x / 110.0); }

// From x0 to x1 along the wave, `offset` pixels below it at the ends and `bump` above it
// in the middle.
std::vector<QPoint> overWave(double x0, double x1, double offset, double bump) {
  std::vector<QPoint> pts;
  const int n = static_cast<int>(std::abs(x1 - x0) / 5.0);
  for (int i = 0; i <= n; ++i) {
    const double x = x0 + (x1 - x0) * i / n;
    pts.emplace_back(static_cast<int>(std::lround(x)),
                     static_cast<int>(std::lround(waveY(x) + offset - bump * std::sin(std::numbers::pi * i / n))));
  }
  return pts;
}

double distanceToOutline(const std::vector<Vec2>& outline, const Vec2& p) {
  double best = INFINITY;
  for (std::size_t i = 1; i < outline.size(); ++i) {
    const Vec2 a = outline[i - 1], ab = outline[i] - a;
    const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
    best = std::min(best, (a + t * ab - p).norm());
  }
  return best;
}

bool sameSamples(const std::vector<StrokeSample>& a, const std::vector<StrokeSample>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].p != b[i].p) return false;
  return true;
}

class OversketchWindowTest : public MainWindowTest {
 protected:
  void SetUp() override {
    MainWindowTest::SetUp();
    window->setOversketch(true);
    window->setOversketchReach(kDefaultOversketchReachPixels);
  }
  // The stroke's drawn samples, as the canvas recorded them (world = widget at zoom 1).
  static std::vector<Vec2> worldOf(const std::vector<QPoint>& pts) {
    std::vector<Vec2> out;
    for (const QPoint& p : pts) out.emplace_back(p.x(), p.y());
    return out;
  }
  // Whether `inner` appears in `outer` as one run, forwards or backwards.
  static bool containsRun(const std::vector<StrokeSample>& outer, const std::vector<Vec2>& inner) {
    for (const bool backwards : {false, true})
      for (std::size_t start = 0; start + inner.size() <= outer.size(); ++start) {
        bool all = true;
        for (std::size_t i = 0; i < inner.size() && all; ++i)
          all = outer[start + i].p == inner[backwards ? inner.size() - 1 - i : i];
        if (all) return true;
      }
    return false;
  }
};

TEST_F(OversketchWindowTest, AStrokeOverTheMiddleReplacesItAsOneUndoStep) {
  drawWithMouse(window->canvas(), wave());
  window->finishBackgroundFits();
  ASSERT_EQ(window->document().strokes().size(), 1u);
  const DocumentStroke before = window->document().strokes().front();
  ASSERT_TRUE(before.fit);
  const int steps = window->undoStack()->count();
  saveScreenshot(*window, "oversketch-before");

  const std::vector<QPoint> fresh = overWave(200, 450, 2.0, 40.0);
  drawWithMouse(window->canvas(), fresh);
  const FitResult& fit = lastFit();
  saveScreenshot(*window, "oversketch-after");
  ASSERT_EQ(window->document().strokes().size(), 1u) << "the stroke was oversketched, not added to";
  EXPECT_EQ(window->undoStack()->count(), steps + 1) << "one undo step";
  const std::vector<StrokeSample>& raw = window->document().strokes().front().raw.samples;

  // old before + new + old after
  const std::vector<Vec2> drawn = worldOf(fresh);
  ASSERT_TRUE(containsRun(raw, drawn)) << "the new samples are in the stroke, in one run";
  std::size_t head = 0;
  while (head < raw.size() && raw[head].p == before.raw.samples[head].p) ++head;
  EXPECT_GT(head, 10u) << "the old stroke's head stays";
  EXPECT_TRUE(raw[head].p == drawn.front()) << "the new samples follow the old head directly";
  EXPECT_LT(before.raw.samples[head - 1].p.x(), 200.0) << "no old sample of the replaced part before them";
  const std::size_t tail = raw.size() - head - drawn.size();
  EXPECT_GT(tail, 10u) << "the old stroke's tail stays";
  for (std::size_t i = 0; i < tail; ++i) {
    EXPECT_TRUE(raw[head + drawn.size() + i].p == before.raw.samples[before.raw.samples.size() - tail + i].p);
    EXPECT_GT(raw[head + drawn.size() + i].p.x(), 450.0);
  }

  // the refit is G2 and follows the new stroke (its bump 40 px above the old one)
  EXPECT_LT(fit.quality.g2_gap, 1e-6) << "curvature continuous at every joint";
  EXPECT_EQ(fit.quality.corners, 0) << "the new stroke runs on smoothly: no corner";
  const std::vector<Vec2> outline = strokeOutline(window->document().strokes().front());
  double worst = 0.0;
  for (const Vec2& p : drawn) worst = std::max(worst, distanceToOutline(outline, p));
  EXPECT_LT(worst, 2.0 * fit.tolerance + 1.0) << "every new sample near the curve (tolerance " << fit.tolerance << ")";
  const Vec2 peak = drawn[drawn.size() / 2];
  EXPECT_LT(distanceToOutline(outline, peak), 2.0 * fit.tolerance + 1.0);

  // undo puts the old stroke back exactly, fit and all
  window->undoStack()->undo();
  ASSERT_EQ(window->document().strokes().size(), 1u);
  const DocumentStroke& back = window->document().strokes().front();
  EXPECT_TRUE(sameSamples(back.raw.samples, before.raw.samples));
  ASSERT_TRUE(back.fit);
  EXPECT_EQ(back.fit->curve.pieces.size(), before.fit->curve.pieces.size());
  EXPECT_EQ(back.fit->quality.max_dev, before.fit->quality.max_dev);
  EXPECT_EQ(back.id, before.id);
  window->undoStack()->redo();
  EXPECT_TRUE(containsRun(window->document().strokes().front().raw.samples, drawn));
}

TEST_F(OversketchWindowTest, AStrokeDrawnBackwardsReplacesTheSameMiddle) {
  drawWithMouse(window->canvas(), wave());
  window->finishBackgroundFits();
  const DocumentStroke before = window->document().strokes().front();
  const std::vector<QPoint> fresh = overWave(450, 200, -2.0, -30.0);
  drawWithMouse(window->canvas(), fresh);
  const FitResult& fit = lastFit();
  ASSERT_EQ(window->document().strokes().size(), 1u);
  const auto& raw = window->document().strokes().front().raw.samples;
  EXPECT_TRUE(raw.front().p == before.raw.samples.front().p) << "the stroke keeps its direction";
  EXPECT_TRUE(raw.back().p == before.raw.samples.back().p);
  EXPECT_TRUE(containsRun(raw, worldOf(fresh)));
  EXPECT_LT(fit.quality.g2_gap, 1e-6);
}

TEST_F(OversketchWindowTest, OffASecondStrokeIsAdded) {
  window->setOversketch(false);
  EXPECT_FALSE(QSettings().value("oversketch/enabled").toBool()) << "remembered";
  drawWithMouse(window->canvas(), wave());
  drawWithMouse(window->canvas(), overWave(200, 450, 2.0, 40.0));
  window->finishBackgroundFits();
  EXPECT_EQ(window->document().strokes().size(), 2u);
  // a new window reads the setting back
  MainWindow other;
  EXPECT_FALSE(other.oversketchEnabled());
}

TEST_F(OversketchWindowTest, AStrokeFromTheEndExtendsIt) {
  drawWithMouse(window->canvas(), wave(80));  // x from 60 to 455
  window->finishBackgroundFits();
  const DocumentStroke before = window->document().strokes().front();
  const Vec2 end = before.raw.samples.back().p;
  std::vector<QPoint> ext;  // on from the end, bending down
  for (int i = 0; i < 40; ++i)
    ext.emplace_back(static_cast<int>(end.x() + 2 + 5 * i), static_cast<int>(end.y() + 1 + 0.02 * (5 * i) * (5 * i)));
  drawWithMouse(window->canvas(), ext);
  const FitResult& fit = lastFit();
  ASSERT_EQ(window->document().strokes().size(), 1u);
  const auto& raw = window->document().strokes().front().raw.samples;
  EXPECT_TRUE(raw.front().p == before.raw.samples.front().p);
  EXPECT_TRUE(raw.back().p == Vec2(ext.back().x(), ext.back().y())) << "the stroke now ends where the new one does";
  EXPECT_LT(fit.quality.g2_gap, 1e-6);
  EXPECT_NEAR(fit.curve.pieces.back().segment.end().x(), ext.back().x(), 2.0 * fit.tolerance + 1.0);
}

TEST_F(OversketchWindowTest, OnAClosedStrokeTheShorterArcIsReplaced) {
  // (the shape is checked here, not the pen-up budget: a slow build, the sanitizers' one,
  // runs out of the app's 250 ms on this stroke and keeps the best chain found by then)
  FitOptions unbounded = window->document().options();
  unbounded.time_budget_ms = 0.0;
  window->document().setOptions(unbounded);
  std::vector<QPoint> circle;  // counter-clockwise on screen (y down: angle decreasing), closed
  const QPointF c(400, 330);
  for (int i = 0; i <= 100; ++i) {
    const double a = 2 * std::numbers::pi * i / 100.0;
    circle.emplace_back(static_cast<int>(std::lround(c.x() + 150 * std::cos(a))), static_cast<int>(std::lround(c.y() + 150 * std::sin(a))));
  }
  drawWithMouse(window->canvas(), circle);
  window->finishBackgroundFits();
  ASSERT_EQ(window->document().strokes().size(), 1u);
  ASSERT_TRUE(window->document().strokes().front().fit && window->document().strokes().front().fit->curve.closed);
  const DocumentStroke before = window->document().strokes().front();

  std::vector<QPoint> bump;  // outward between angles 0.5 and 1.3, 2 px off the circle at its ends
  for (int i = 0; i <= 30; ++i) {
    const double a = 0.5 + 0.8 * i / 30.0, r = 152 + 35 * std::sin(std::numbers::pi * i / 30.0);
    bump.emplace_back(static_cast<int>(std::lround(c.x() + r * std::cos(a))), static_cast<int>(std::lround(c.y() + r * std::sin(a))));
  }
  drawWithMouse(window->canvas(), bump);
  const FitResult& fit = lastFit();
  ASSERT_EQ(window->document().strokes().size(), 1u);
  EXPECT_TRUE(fit.curve.closed) << "still a closed curve";
  EXPECT_LT(fit.quality.g2_gap, 1e-6);
  const auto& raw = window->document().strokes().front().raw.samples;
  EXPECT_TRUE(containsRun(raw, worldOf(bump)));
  EXPECT_GT(raw.size(), 60u) << "the longer arc of the circle stays";
  const std::vector<Vec2> outline = strokeOutline(window->document().strokes().front());
  const Vec2 peak(c.x() + 187 * std::cos(0.9), c.y() + 187 * std::sin(0.9));
  EXPECT_LT(distanceToOutline(outline, peak), 2.0 * fit.tolerance + 2.0) << "the curve goes out over the bump";
  window->undoStack()->undo();
  EXPECT_TRUE(sameSamples(window->document().strokes().front().raw.samples, before.raw.samples));
}

TEST_F(OversketchWindowTest, TheReachIsASettingInTheEditMenu) {
  auto* box = window->findChild<QSpinBox*>("oversketch-reach");
  ASSERT_NE(box, nullptr);
  EXPECT_EQ(box->value(), static_cast<int>(kDefaultOversketchReachPixels));
  drawWithMouse(window->canvas(), wave());
  window->finishBackgroundFits();
  // 14 px beside the stroke: out of the default reach, a new stroke
  drawWithMouse(window->canvas(), overWave(200, 450, 14.0, 30.0));
  window->finishBackgroundFits();
  EXPECT_EQ(window->document().strokes().size(), 2u);
  window->undoStack()->undo();
  box->setValue(20);
  EXPECT_EQ(window->oversketchReach(), 20.0);
  EXPECT_EQ(QSettings().value("oversketch/reach_px").toDouble(), 20.0) << "remembered";
  drawWithMouse(window->canvas(), overWave(200, 450, 14.0, 30.0));
  window->finishBackgroundFits();
  EXPECT_EQ(window->document().strokes().size(), 1u) << "within 20 px it oversketches";
}

}  // namespace
}  // namespace la::gui
