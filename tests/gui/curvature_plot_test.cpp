// The curvature plot (issue 17, part 3, its plot half): it shows the selected stroke and
// shades the selected segment's arc-length range, its legend sits above the data, and it
// reads curvature, |curvature| on a log scale or radius. It follows the pen while a
// stroke is drawn and the handle while a joint is dragged, and shows every visible stroke
// on one axis; the LCG plot's legend sits above its data. Driven through the real window.

#include <gtest/gtest.h>

#include <QComboBox>
#include <QUndoStack>
#include <QWheelEvent>
#include <cmath>

#include "app/gui/curvature_plot.h"
#include "app/gui/lcg_plot.h"
#include "tests/gui/window_test_support.h"

namespace la::gui {
namespace {

double lengthOf(const Curve& c) {
  double s = 0.0;
  for (const CurvePiece& p : c.pieces) s += p.segment.length();
  return s;
}

void moveMouse(QWidget* canvas, QPoint to, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
  QMouseEvent move(QEvent::MouseMove, to, canvas->mapToGlobal(to), Qt::NoButton, Qt::LeftButton, modifiers);
  QApplication::sendEvent(canvas, &move);
}

double curvatureAt(const Curve& curve, double s) {
  for (std::size_t i = 0; i < curve.pieces.size(); ++i) {
    const LaSegment& seg = curve.pieces[i].segment;
    if (s <= seg.length() || i + 1 == curve.pieces.size()) return seg.kappa(std::min(s, seg.length()));
    s -= seg.length();
  }
  return NAN;
}

TEST_F(MainWindowTest, CurvaturePlotFollowsTheSelectionAndReadsThreeWays) {
  drawWithMouse(window->canvas(), wave());
  drawWithMouse(window->canvas(), wave(50));
  window->finishBackgroundFits();
  auto* plot = window->findChild<CurvaturePlot*>();
  ASSERT_NE(plot, nullptr);
  const Curve& first = window->document().strokes()[0].fit->curve;
  const Curve& second = window->document().strokes()[1].fit->curve;
  ASSERT_GE(first.pieces.size(), 2u);
  auto length = [](const Curve& c, std::size_t pieces) {
    double s = 0.0;
    for (std::size_t i = 0; i < pieces; ++i) s += c.pieces[i].segment.length();
    return s;
  };

  window->selectSegment(0, 1);
  EXPECT_NEAR(plot->totalLength(), length(first, first.pieces.size()), 1e-9) << "the plot shows another stroke";
  EXPECT_NEAR(plot->highlight().first, length(first, 1), 1e-9);
  EXPECT_NEAR(plot->highlight().second, length(first, 2), 1e-9);
  window->selectSegment(1, 0);
  EXPECT_NEAR(plot->totalLength(), length(second, second.pieces.size()), 1e-9) << "the plot did not follow";
  EXPECT_NEAR(plot->highlight().second, length(second, 1), 1e-9);
  window->selectSegment(-1, -1);
  EXPECT_EQ(plot->highlight().first, plot->highlight().second) << "nothing selected, nothing shaded";

  window->selectSegment(0, 0);
  EXPECT_FALSE(plot->legendRect().isEmpty());
  EXPECT_FALSE(plot->legendRect().intersects(plot->plotArea())) << "the legend is on the data";

  const double kmax = window->document().strokes()[0].fit->quality.max_abs_kappa;
  auto* mode = plot->findChild<QComboBox*>("curvature-plot-mode");
  ASSERT_NE(mode, nullptr);
  ASSERT_EQ(mode->count(), 3);
  for (int m = 0; m < 3; ++m) {
    mode->setCurrentIndex(m);
    if (plot->mode() == CurvaturePlot::Mode::kLogAbsCurvature) saveScreenshot(*window, "curvature-plot-log");
    int checked = 0;
    for (const auto& [s, y] : plot->afterPoints()) {
      const double k = curvatureAt(first, s);
      // (at an inflection joint one side has curvature 0, the other 1e-20 or so: no value to compare)
      if (plot->mode() != CurvaturePlot::Mode::kCurvature && std::abs(k) < 1e-9 * kmax) continue;
      const double want = plot->mode() == CurvaturePlot::Mode::kCurvature        ? k
                          : plot->mode() == CurvaturePlot::Mode::kLogAbsCurvature ? (k != 0 ? std::log10(std::abs(k)) : NAN)
                                                                                  : (k != 0 ? 1 / std::abs(k) : NAN);
      if (!std::isfinite(want)) {
        EXPECT_FALSE(std::isfinite(y)) << "mode " << m << " s " << s;
        continue;
      }
      EXPECT_NEAR(y, want, 1e-7 * std::max(1.0, std::abs(want))) << "mode " << m << " s " << s;
      ++checked;
    }
    EXPECT_GT(checked, 50) << "mode " << m;
  }
  EXPECT_EQ(plot->mode(), CurvaturePlot::Mode::kRadius);
  EXPECT_FALSE(plot->grab().isNull());
}

// While the pen moves the plot shows the live fit of the stroke being drawn (the canvas'
// preview), updated as the stroke grows; at pen-up, the stroke's own fit.
TEST_F(MainWindowTest, CurvaturePlotFollowsThePenWhileDrawing) {
  Canvas* canvas = window->canvas();
  auto* plot = window->findChild<CurvaturePlot*>();
  ASSERT_NE(plot, nullptr);
  const auto pts = wave();
  QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, pts.front());
  for (std::size_t i = 1; i < 50; ++i) moveMouse(canvas, pts[i]);
  ASSERT_TRUE(canvas->hasPreview());
  const double first = lengthOf(canvas->preview()->curve);
  EXPECT_NEAR(plot->totalLength(), first, 1e-9 * first) << "the plot does not show the stroke being drawn";
  QTest::qWait(120);  // (the live fit runs at most every 30 ms)
  for (std::size_t i = 50; i + 1 < pts.size(); ++i) moveMouse(canvas, pts[i]);
  ASSERT_TRUE(canvas->hasPreview());
  const double second = lengthOf(canvas->preview()->curve);
  EXPECT_GT(second, 1.5 * first) << "the live fit did not follow the pen";
  EXPECT_NEAR(plot->totalLength(), second, 1e-9 * second) << "the plot did not follow the pen";
  ASSERT_EQ(plot->mode(), CurvaturePlot::Mode::kCurvature);
  for (const auto& [s, kappa] : plot->afterPoints())
    ASSERT_NEAR(kappa, curvatureAt(canvas->preview()->curve, s), 1e-9) << "at s = " << s;
  QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, pts.back());
  const double drawn = lengthOf(window->document().strokes().back().fit->curve);
  EXPECT_NEAR(plot->totalLength(), drawn, 1e-9 * drawn);
}

// While a joint is dragged the plot shows the edited curve's curvature (the canvas'
// preview), with the selected segment shaded; when it is dropped, the stroke's new fit.
TEST_F(MainWindowTest, CurvaturePlotFollowsAJointDrag) {
  drawWithMouse(window->canvas(), wave());
  const FitResult before = lastFit();
  Canvas* canvas = window->canvas();
  auto* plot = window->findChild<CurvaturePlot*>();
  for (std::size_t i = 1; i < before.curve.pieces.size(); ++i) {
    if (before.curve.pieces[i].corner) continue;
    window->selectSegment(0, static_cast<int>(i));
    const int steps = window->undoStack()->index();
    const QPoint from = canvas->toWidget(before.curve.pieces[i].segment.start()).toPoint();
    QTest::mousePress(canvas, Qt::LeftButton, Qt::ControlModifier, from);
    moveMouse(canvas, from + QPoint(4, -6), Qt::ControlModifier);
    moveMouse(canvas, from + QPoint(8, -12), Qt::ControlModifier);
    if (!canvas->hasPreview()) {  // no G2 curve through there: try another joint
      QTest::mouseRelease(canvas, Qt::LeftButton, Qt::ControlModifier, from + QPoint(8, -12));
      window->undoStack()->setIndex(steps);  // (the refused edit, if it was recorded)
      continue;
    }
    const Curve& live = canvas->preview()->curve;
    const double length = lengthOf(live);
    EXPECT_GT(std::abs(length - lengthOf(before.curve)), 1e-6 * length) << "the drag changed nothing";
    EXPECT_NEAR(plot->totalLength(), length, 1e-9 * length) << "the plot does not follow the handle";
    int compared = 0;
    for (const auto& [s, kappa] : plot->afterPoints()) {
      ASSERT_NEAR(kappa, curvatureAt(live, s), 1e-9) << "at s = " << s;
      ++compared;
    }
    EXPECT_GT(compared, 50);
    double joint = 0.0;
    for (std::size_t k = 0; k < i; ++k) joint += live.pieces[k].segment.length();
    EXPECT_NEAR(plot->highlight().first, joint, 1e-9 * length) << "the selected segment is not shaded";
    QTest::mouseRelease(canvas, Qt::LeftButton, Qt::ControlModifier, from + QPoint(8, -12));
    const double after = lengthOf(lastFit().curve);
    EXPECT_NEAR(plot->totalLength(), after, 1e-9 * after);
    return;
  }
  FAIL() << "no joint could be dragged";
}

// "All visible strokes": every fitted stroke in view on one axis, each from its own start;
// the selected one highlighted; a zoom that leaves a stroke out of view leaves it off.
TEST_F(MainWindowTest, CurvaturePlotShowsAllVisibleStrokesOnOneAxis) {
  const auto all = wave();
  drawWithMouse(window->canvas(), std::vector<QPoint>(all.begin(), all.begin() + 50));   // x 60..305
  drawWithMouse(window->canvas(), std::vector<QPoint>(all.begin() + 80, all.end()));     // x 460..655
  window->finishBackgroundFits();
  auto* plot = window->findChild<CurvaturePlot*>();
  auto* scope = plot->findChild<QComboBox*>("curvature-plot-scope");
  ASSERT_NE(scope, nullptr);
  const double a = lengthOf(window->document().strokes()[0].fit->curve);
  const double b = lengthOf(window->document().strokes()[1].fit->curve);
  ASSERT_EQ(plot->curveLengths().size(), 1u) << "the selected (last) stroke alone";

  scope->setCurrentIndex(scope->findData(static_cast<int>(CurvaturePlot::Scope::kAllVisible)));
  EXPECT_EQ(plot->scope(), CurvaturePlot::Scope::kAllVisible);
  std::vector<double> lengths = plot->curveLengths();
  ASSERT_EQ(lengths.size(), 2u);
  EXPECT_NEAR(lengths[0], a, 1e-9 * a);
  EXPECT_NEAR(lengths[1], b, 1e-9 * b);
  window->selectSegment(0, 0);
  EXPECT_EQ(plot->curveLengths().size(), 2u) << "selecting one keeps the others";
  EXPECT_NEAR(plot->totalLength(), a, 1e-9 * a) << "the selected stroke is not the highlighted one";
  EXPECT_GT(plot->highlight().second, 0.0);
  EXPECT_FALSE(plot->grab().isNull());

  // zoom in about the first stroke's start until the view's right edge is at x = 300: the
  // second stroke (from x = 460) leaves the view, the first stays
  const QPoint at = all.front();
  const double factor = (window->canvas()->width() - at.x()) / (300.0 - at.x());
  ASSERT_GT(factor, 1.0);
  const int angle = static_cast<int>(std::lround(120.0 * std::log(factor) / std::log(1.15)));  // (1.15 per notch)
  QWheelEvent wheel(at, window->canvas()->mapToGlobal(at), QPoint(), QPoint(0, angle), Qt::NoButton, Qt::NoModifier,
                    Qt::NoScrollPhase, false);
  QApplication::sendEvent(window->canvas(), &wheel);
  const double right = window->canvas()->toWorld(QPointF(window->canvas()->width(), 0)).x();
  ASSERT_GT(right, 200.0) << "the first stroke left the view too";
  ASSERT_LT(right, 400.0) << "the zoom left both in view";
  for (int i = 0; i < 40 && plot->curveLengths().size() != 1u; ++i) QTest::qWait(10);
  lengths = plot->curveLengths();
  ASSERT_EQ(lengths.size(), 1u) << "a stroke out of view is still plotted";
  EXPECT_NEAR(lengths[0], a, 1e-9 * a);

  scope->setCurrentIndex(scope->findData(static_cast<int>(CurvaturePlot::Scope::kSelectedStroke)));
  EXPECT_NEAR(plot->totalLength(), a, 1e-9 * a) << "back to the selected stroke";
}

// The LCG plot's title and legend sit above the plotting area: never on the data.
TEST_F(MainWindowTest, LcgLegendDoesNotCoverItsData) {
  drawWithMouse(window->canvas(), wave());
  window->finishBackgroundFits();
  window->selectSegment(0, 0);
  auto* lcg = window->findChild<LcgPlot*>();
  ASSERT_NE(lcg, nullptr);
  ASSERT_TRUE(lcg->hasSegment());
  const QRectF legend = lcg->legendRect(), area = lcg->plotArea();
  EXPECT_FALSE(legend.intersects(area)) << "the legend is on the data";
  EXPECT_TRUE(QRectF(lcg->rect()).contains(legend)) << "the legend is cut off";
  EXPECT_GT(area.height(), 60.0) << "no room left for the data";
  // the legend is drawn where it says: dark text pixels in its box
  const QImage shot = lcg->grab().toImage();
  int dark = 0;
  for (int y = static_cast<int>(legend.top()); y < static_cast<int>(legend.bottom()); ++y)
    for (int x = static_cast<int>(legend.left()); x < static_cast<int>(legend.right()); ++x)
      if (qGray(shot.pixel(x, y)) < 100) ++dark;
  EXPECT_GT(dark, 50) << "nothing is drawn in the legend's box";
}

}  // namespace
}  // namespace la::gui
