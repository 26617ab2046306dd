// The tools (issue 17, part 1): a toolbar of exclusive, checkable tools with one-key
// shortcuts decides what a plain drag does; the Select tool picks strokes (click,
// shift+click, rubber band), moves them as one undo step without refitting, deletes them
// as one, and edits the selected stroke's joints without ctrl. All driven through the
// real window with synthesized input.

#include <gtest/gtest.h>

#include <QAction>
#include <QActionGroup>
#include <QKeySequence>
#include <QMenu>
#include <QToolBar>
#include <QToolButton>
#include <QUndoStack>
#include <cmath>

#include "app/gui/canvas.h"
#include "app/gui/tools.h"
#include "tests/gui/window_test_support.h"

namespace la::gui {
namespace {

// A wave of `n` points from x = 60, about height y0 (widget pixels).
std::vector<QPoint> waveAt(int y0, int n = 60, double amplitude = 35.0) {
  std::vector<QPoint> pts;
  for (int i = 0; i < n; ++i) {
    const double x = 60 + 5.0 * i;
    pts.emplace_back(static_cast<int>(x), static_cast<int>(y0 + amplitude * std::sin(x / 50.0)));
  }
  return pts;
}

// A point on stroke k's fitted curve (its first segment's middle), in widget pixels.
QPoint onStroke(MainWindow& w, std::size_t k) {
  const LaSegment& seg = w.document().strokes()[k].fit->curve.pieces.front().segment;
  return w.canvas()->toWidget(seg.position(0.5 * seg.length())).toPoint();
}

class SelectToolTest : public MainWindowTest {
 protected:
  void SetUp() override {
    MainWindowTest::SetUp();
    QApplication::setActiveWindow(window.get());  // one-key shortcuts reach the active window only
    ASSERT_TRUE(QTest::qWaitForWindowActive(window.get()));
  }
  // Two strokes, one above the other, fitted in full.
  void drawTwo() {
    drawWithMouse(window->canvas(), waveAt(110));
    drawWithMouse(window->canvas(), waveAt(290));
    window->finishBackgroundFits();
    ASSERT_EQ(window->document().strokes().size(), 2u);
    ASSERT_TRUE(window->document().strokes()[0].fit && window->document().strokes()[1].fit);
  }
  void key(int key, Qt::KeyboardModifiers modifiers = Qt::NoModifier) {
    QTest::keyClick(window->canvas(), static_cast<Qt::Key>(key), modifiers);
  }
  using Indices = std::vector<std::size_t>;
};

// The toolbar: Draw, Select / Edit and Pan, checkable, exclusive, each with its key in its
// tool tip; the keys switch the canvas' tool; the Construct tools are there too; the empty
// canvas says how to start until something is drawn.
TEST_F(SelectToolTest, ToolbarHasExclusiveToolsWithShortcutsAndTips) {
  auto* bar = window->findChild<QToolBar*>("tools");
  ASSERT_NE(bar, nullptr);
  EXPECT_TRUE(bar->isVisible());
  const std::vector<std::pair<Tool, QString>> keys{{Tool::kDraw, "B"}, {Tool::kSelect, "V"}, {Tool::kPan, "H"}};
  for (const auto& [tool, k] : keys) {
    QAction* a = window->toolAction(tool);
    ASSERT_NE(a, nullptr);
    EXPECT_TRUE(a->isCheckable());
    EXPECT_TRUE(bar->actions().contains(a)) << a->text().toStdString();
    ASSERT_NE(a->actionGroup(), nullptr);
    EXPECT_TRUE(a->actionGroup()->isExclusive());
    EXPECT_TRUE(a->shortcuts().contains(QKeySequence(k))) << a->text().toStdString();
    EXPECT_TRUE(a->toolTip().contains("(" + k)) << a->toolTip().toStdString();
  }
  EXPECT_TRUE(window->toolAction(Tool::kDraw)->shortcuts().contains(QKeySequence("P")));
  EXPECT_EQ(window->tool(), Tool::kDraw);
  EXPECT_TRUE(window->toolAction(Tool::kDraw)->isChecked());
  bool construct = false;
  for (QWidget* w : bar->findChildren<QWidget*>())
    if (auto* b = qobject_cast<QToolButton*>(w); b && b->text() == "Construct" && b->menu()) construct = b->menu()->actions().size() == 4;
  EXPECT_TRUE(construct) << "a Construct button with the four constructions";

  key(Qt::Key_V);
  EXPECT_EQ(window->tool(), Tool::kSelect);
  EXPECT_TRUE(window->toolAction(Tool::kSelect)->isChecked());
  EXPECT_FALSE(window->toolAction(Tool::kDraw)->isChecked()) << "exclusive";
  key(Qt::Key_H);
  EXPECT_EQ(window->tool(), Tool::kPan);
  key(Qt::Key_P);
  EXPECT_EQ(window->tool(), Tool::kDraw);

  EXPECT_TRUE(window->canvas()->showsHint());
  EXPECT_TRUE(emptyCanvasHint().contains("B draw")) << emptyCanvasHint().toStdString();
  EXPECT_TRUE(emptyCanvasHint().contains("Import points")) << emptyCanvasHint().toStdString();
  const QImage empty = window->canvas()->grab().toImage();
  int ink = 0;  // the hint's text, in the middle of the white canvas
  for (int y = empty.height() / 3; y < 2 * empty.height() / 3; ++y)
    for (int x = 0; x < empty.width(); ++x) ink += qGray(empty.pixel(x, y)) < 200;
  EXPECT_GT(ink, 50) << "no hint drawn";
  drawWithMouse(window->canvas(), waveAt(200));
  EXPECT_FALSE(window->canvas()->showsHint());
}

// What a plain drag does is the tool's: Draw draws, Select drags a (here empty) rubber
// band, Pan moves the view; Space held pans in any tool; the old shortcuts stay in Draw
// (shift+drag pans).
TEST_F(SelectToolTest, PlainDragFollowsTheTool) {
  Canvas* canvas = window->canvas();
  const QPoint a(200, 150), b(260, 190);
  auto viewShift = [&] { return canvas->view().map(QPointF(0, 0)); };

  key(Qt::Key_V);
  dragOnCanvas(canvas, a, b);
  EXPECT_TRUE(window->document().strokes().empty()) << "Select drew";
  EXPECT_EQ(viewShift(), QPointF(0, 0)) << "Select panned";

  key(Qt::Key_H);
  dragOnCanvas(canvas, a, b);
  EXPECT_TRUE(window->document().strokes().empty()) << "Pan drew";
  EXPECT_EQ(viewShift(), QPointF(b - a)) << "Pan did not move the view by the drag";

  key(Qt::Key_B);
  QTest::keyPress(canvas, Qt::Key_Space);
  dragOnCanvas(canvas, b, a);
  QTest::keyRelease(canvas, Qt::Key_Space);
  EXPECT_TRUE(window->document().strokes().empty()) << "Space+drag drew";
  EXPECT_EQ(viewShift(), QPointF(0, 0)) << "Space+drag did not pan back";

  dragOnCanvas(canvas, a, b, Qt::ShiftModifier);
  EXPECT_TRUE(window->document().strokes().empty()) << "shift+drag drew";
  EXPECT_EQ(viewShift(), QPointF(b - a)) << "shift+drag no longer pans in Draw";

  drawWithMouse(canvas, waveAt(250));
  EXPECT_EQ(window->document().strokes().size(), 1u) << "Draw did not draw";
}

// Click selects the stroke under the cursor (within a few pixels of its curve), shift+click
// adds or removes one, a click on empty canvas clears, a rubber band selects the strokes
// inside it; Edit > Select all (Ctrl+A) and Clear selection (Esc, Ctrl+Shift+A).
TEST_F(SelectToolTest, ClickShiftClickRubberBandSelectAllAndClear) {
  drawTwo();
  Canvas* canvas = window->canvas();
  key(Qt::Key_V);
  QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, onStroke(*window, 0) + QPoint(0, 3));
  EXPECT_EQ(window->selectedStrokes(), Indices({0})) << "a click 3 pixels off the curve";
  EXPECT_EQ(window->selectedStroke(), 0) << "the segment panels follow the click";
  QTest::mouseClick(canvas, Qt::LeftButton, Qt::ShiftModifier, onStroke(*window, 1));
  EXPECT_EQ(window->selectedStrokes(), Indices({0, 1}));
  QTest::mouseClick(canvas, Qt::LeftButton, Qt::ShiftModifier, onStroke(*window, 0));
  EXPECT_EQ(window->selectedStrokes(), Indices({1})) << "shift+click removes a selected stroke";
  QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, onStroke(*window, 0));
  EXPECT_EQ(window->selectedStrokes(), Indices({0})) << "a plain click replaces the selection";
  QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, QPoint(canvas->width() - 10, canvas->height() - 10));
  EXPECT_TRUE(window->selectedStrokes().empty()) << "a click on empty canvas clears";
  QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, onStroke(*window, 1) + QPoint(0, 20));
  EXPECT_TRUE(window->selectedStrokes().empty()) << "20 pixels off is not a few";

  // rubber bands: round the upper stroke only, then round both
  QRectF upper;
  for (const StrokeSample& q : window->document().strokes()[0].raw.samples) upper |= QRectF(canvas->toWidget(q.p), QSizeF(1, 1));
  dragOnCanvas(canvas, upper.topLeft().toPoint() - QPoint(15, 15), upper.bottomRight().toPoint() + QPoint(15, 15));
  EXPECT_EQ(window->selectedStrokes(), Indices({0}));
  dragOnCanvas(canvas, QPoint(5, 5), QPoint(canvas->width() - 5, canvas->height() - 5));
  EXPECT_EQ(window->selectedStrokes(), Indices({0, 1}));
  saveScreenshot(*window, "select-two-strokes");
  const int steps = window->undoStack()->count();

  key(Qt::Key_Escape);
  EXPECT_TRUE(window->selectedStrokes().empty()) << "Esc";
  key(Qt::Key_A, Qt::ControlModifier);
  EXPECT_EQ(window->selectedStrokes(), Indices({0, 1})) << "Ctrl+A";
  key(Qt::Key_A, Qt::ControlModifier | Qt::ShiftModifier);
  EXPECT_TRUE(window->selectedStrokes().empty()) << "Ctrl+Shift+A";
  EXPECT_EQ(window->undoStack()->count(), steps) << "selecting changes no document";
}

// Dragging a selected stroke moves every selected stroke: points, curve, splines and the
// user's joint edits translate by the drag, the fit is not redone (same alphas, lengths,
// quality figures), and the whole drag is one undo step.
TEST_F(SelectToolTest, DraggingTheSelectionMovesItAsOneUndoStep) {
  drawTwo();
  Canvas* canvas = window->canvas();
  const std::vector<DocumentStroke> before = window->document().strokes();
  key(Qt::Key_A, Qt::ControlModifier);
  key(Qt::Key_V);
  const int steps = window->undoStack()->count();
  const QPoint from = onStroke(*window, 1), to = from + QPoint(37, -21);
  dragOnCanvas(canvas, from, to, Qt::NoModifier, 9);
  EXPECT_EQ(window->undoStack()->count(), steps + 1) << "one drag, one undo step";
  const QPointF dw = canvas->toWorld(to) - canvas->toWorld(from);
  const Vec2 d(dw.x(), dw.y());
  auto expectMovedBy = [&](const Vec2& by) {
    for (std::size_t k = 0; k < before.size(); ++k) {
      const DocumentStroke& now = window->document().strokes()[k];
      ASSERT_EQ(now.raw.samples.size(), before[k].raw.samples.size());
      for (std::size_t i = 0; i < now.raw.samples.size(); ++i)
        EXPECT_LT((now.raw.samples[i].p - before[k].raw.samples[i].p - by).norm(), 1e-9) << "stroke " << k << " sample " << i;
      const FitResult &a = *before[k].fit, &b = *now.fit;
      ASSERT_EQ(b.curve.pieces.size(), a.curve.pieces.size()) << "refitted";
      for (std::size_t i = 0; i < a.curve.pieces.size(); ++i) {
        const LaSegment &sa = a.curve.pieces[i].segment, &sb = b.curve.pieces[i].segment;
        EXPECT_LT((sb.start() - sa.start() - by).norm(), 1e-9);
        EXPECT_LT((sb.end() - sa.end() - by).norm(), 1e-9);
        EXPECT_EQ(sb.alpha(), sa.alpha());
        EXPECT_EQ(sb.length(), sa.length());
        EXPECT_EQ(sb.kappaStart(), sa.kappaStart());
      }
      EXPECT_EQ(b.quality.max_dev, a.quality.max_dev) << "refitted";
      for (std::size_t s = 0; s < a.splines.size(); ++s) {
        const CubicBSpline& spline = a.splines[s];
        const double t = 0.5 * (spline.tMin() + spline.tMax());
        EXPECT_LT((b.splines[s].point(t) - spline.point(t) - by).norm(), 1e-9) << "spline " << s;
      }
      EXPECT_LT((b.cleaned.points.front() - a.cleaned.points.front() - by).norm(), 1e-9);
    }
  };
  expectMovedBy(d);
  EXPECT_EQ(window->selectedStrokes(), Indices({0, 1})) << "still selected after the move";
  window->undoStack()->undo();
  expectMovedBy(Vec2::Zero());
  window->undoStack()->redo();
  expectMovedBy(d);

  // a second drag is a second step; a click that does not move is none
  const int moved = window->undoStack()->count();
  QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, onStroke(*window, 0));
  EXPECT_EQ(window->undoStack()->count(), moved);
  dragOnCanvas(canvas, onStroke(*window, 0), onStroke(*window, 0) + QPoint(5, 5));
  EXPECT_EQ(window->undoStack()->count(), moved + 1);
}

// A stroke moved before its stage-7 fit comes back from the worker thread gets that fit
// where it is now, not where it was drawn.
TEST_F(SelectToolTest, AStrokeMovedBeforeItsBackgroundFitKeepsItsPlace) {
  drawWithMouse(window->canvas(), waveAt(200));
  ASSERT_TRUE(window->document().strokes()[0].provisional) << "stage 7 is on by default";
  window->moveStrokes({0}, Vec2(80, 40), 1);
  window->finishBackgroundFits();
  const DocumentStroke& s = window->document().strokes()[0];
  ASSERT_FALSE(s.provisional);
  ASSERT_TRUE(s.fit);
  const Vec2 first = s.fit->cleaned.points.front(), source = s.raw.samples[s.fit->cleaned.source.front()].p;
  EXPECT_LT((first - source).norm(), 1e-9) << "the fit's points are not the moved stroke's";
  EXPECT_LT((s.fit->curve.pieces.front().segment.start() - source).norm(), 2 * s.fit->tolerance + 1e-9);
}

// Delete removes every selected stroke as one undo step; undo brings them back where they
// were, in order, selected.
TEST_F(SelectToolTest, DeleteRemovesTheSelectionAsOneUndoStep) {
  drawTwo();
  drawWithMouse(window->canvas(), waveAt(200, 30));
  window->finishBackgroundFits();
  ASSERT_EQ(window->document().strokes().size(), 3u);
  std::vector<std::uint64_t> ids;
  for (const DocumentStroke& s : window->document().strokes()) ids.push_back(s.id);
  key(Qt::Key_V);
  QTest::mouseClick(window->canvas(), Qt::LeftButton, Qt::NoModifier, onStroke(*window, 0));
  QTest::mouseClick(window->canvas(), Qt::LeftButton, Qt::ShiftModifier, onStroke(*window, 1));
  ASSERT_EQ(window->selectedStrokes(), Indices({0, 1}));
  const int steps = window->undoStack()->count();
  key(Qt::Key_Delete);
  ASSERT_EQ(window->document().strokes().size(), 1u);
  EXPECT_EQ(window->document().strokes()[0].id, ids[2]);
  EXPECT_EQ(window->undoStack()->count(), steps + 1);
  EXPECT_TRUE(window->selectedStrokes().empty());
  window->undoStack()->undo();
  ASSERT_EQ(window->document().strokes().size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) EXPECT_EQ(window->document().strokes()[k].id, ids[k]);
  EXPECT_EQ(window->selectedStrokes(), Indices({0, 1}));
  window->undoStack()->redo();
  EXPECT_EQ(window->document().strokes().size(), 1u);
}

// In the Select tool the selected stroke's joints are handles without ctrl: dragging one
// moves that joint (a joint edit, G2 kept, one undo step), not the stroke.
TEST_F(SelectToolTest, SelectedStrokesJointsDragWithoutCtrl) {
  drawWithMouse(window->canvas(), wave());
  window->finishBackgroundFits();
  const FitResult before = *window->document().strokes()[0].fit;
  ASSERT_GE(before.curve.pieces.size(), 2u);
  Canvas* canvas = window->canvas();
  key(Qt::Key_V);
  for (std::size_t i = 1; i < before.curve.pieces.size(); ++i) {
    if (before.curve.pieces[i].corner) continue;
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, onStroke(*window, 0));  // select it
    ASSERT_EQ(window->selectedStrokes(), Indices({0}));
    const int steps = window->undoStack()->count();
    const QPoint from = canvas->toWidget(before.curve.pieces[i].segment.start()).toPoint();
    dragOnCanvas(canvas, from, from + QPoint(6, -8));
    const DocumentStroke& s = window->document().strokes()[0];
    if (s.joint_overrides.count(static_cast<int>(i)) == 0) continue;  // no G2 curve through there: refused
    EXPECT_EQ(window->undoStack()->count(), steps + 1);
    EXPECT_LT(s.fit->quality.g2_gap, 1e-6);
    EXPECT_LT((s.fit->curve.pieces[0].segment.start() - before.curve.pieces[0].segment.start()).norm(), 1e-9)
        << "the stroke moved instead of its joint";
    window->undoStack()->undo();
    EXPECT_TRUE(window->document().strokes()[0].joint_overrides.empty());
    return;
  }
  FAIL() << "no joint could be moved";
}

}  // namespace
}  // namespace la::gui
