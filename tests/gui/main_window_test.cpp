// GUI tests of the application window (app/gui), run offscreen: strokes drawn with
// synthesized mouse and tablet events are fitted; undo/redo; parameter changes refit;
// save and reopen; import and export of every file type; bad files give an error, not a
// crash. One test saves a screenshot of the window with a fitted stroke (the README's).

#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileInfo>
#include <QPointingDevice>
#include <QSemaphore>
#include <QThreadPool>
#include <QStandardPaths>
#include <QTabletEvent>
#include <QTemporaryDir>
#include <QSlider>
#include <QLabel>
#include <QMessageBox>
#include <QStatusBar>
#include <QTest>
#include <QUndoStack>
#include <cmath>

#include "app/gui/canvas.h"
#include "app/gui/chart.h"
#include "app/gui/curvature_plot.h"
#include "app/gui/main_window.h"
#include "app/gui/parameter_panel.h"
#include "tests/gui/window_test_support.h"

namespace la::gui {
namespace {

// The first segment whose alpha the user may steer (a 3-point piece, not a circle), or -1.
int firstSteerablePiece(const FitResult& fit) {
  for (std::size_t i = 0; i < fit.pieces.size(); ++i)
    if (fit.pieces[i].kind == PieceKind::kThreePoint && std::isfinite(fit.curve.pieces[i].segment.alpha()))
      return static_cast<int>(i);
  return -1;
}

// Fields that behave (issue 17, part 4): no field has the focus at start, the canvas has
// it; a tolerance typed into its field applies on Enter, not at every keystroke ("1.25"
// once passed through 1), as one undo step; Ctrl+Shift+Z and Ctrl+Y redo.
TEST_F(MainWindowTest, TypedToleranceAppliesOnEnterAsOneUndoStep) {
  EXPECT_EQ(window->focusWidget(), window->canvas());
  QDoubleSpinBox* tolerance = nullptr;
  for (QDoubleSpinBox* box : window->findChildren<QDoubleSpinBox*>())
    if (box->suffix() == " % of size") tolerance = box;
  ASSERT_NE(tolerance, nullptr);
  const double before = window->document().options().tolerance_fraction;
  const int steps = window->undoStack()->count();
  tolerance->setFocus();
  tolerance->selectAll();
  QTest::keyClicks(tolerance, "1.25");
  EXPECT_EQ(window->document().options().tolerance_fraction, before) << "applied while typing";
  QTest::keyClick(tolerance, Qt::Key_Return);
  EXPECT_NEAR(window->document().options().tolerance_fraction, 0.0125, 1e-12);
  EXPECT_EQ(window->undoStack()->count(), steps + 1);
  saveScreenshot(*window, "tolerance-typed-empty-canvas-hint");
  QAction* redo = nullptr;
  for (QAction* a : window->findChildren<QAction*>())
    if (a->text().contains("Redo")) redo = a;
  ASSERT_NE(redo, nullptr);
  EXPECT_TRUE(redo->shortcuts().contains(QKeySequence("Ctrl+Shift+Z")));
  EXPECT_TRUE(redo->shortcuts().contains(QKeySequence("Ctrl+Y")));
}

// Never lose work (issue 17, part 5): New and closing the window ask before unsaved
// changes go (Save / Discard / Cancel); Cancel keeps everything, Save writes the sketch
// first, Discard goes on. The crash-recovery marker goes only after a clean save or an
// explicit discard.
TEST_F(MainWindowTest, NewAndCloseAskBeforeUnsavedWorkIsLost) {
  QAction* new_sketch = actionNamed(*window, "&New");
  ASSERT_NE(new_sketch, nullptr);
  window->offerRecovery();  // (lays the crash-recovery marker, as at start)
  const QString marker = window->autosavePath() + ".running";
  ASSERT_TRUE(QFileInfo::exists(marker));

  drawWithMouse(window->canvas(), wave());
  window->answerUnsavedChanges(QMessageBox::Cancel);
  new_sketch->trigger();
  EXPECT_EQ(window->document().strokes().size(), 1u) << "Cancel lost the stroke";
  EXPECT_FALSE(window->close()) << "Cancel closed the window";

  const QString path = dir.filePath("kept.lafair.json");
  ASSERT_TRUE(window->saveFile(path));
  drawWithMouse(window->canvas(), wave(70));
  window->answerUnsavedChanges(QMessageBox::Save);
  new_sketch->trigger();
  EXPECT_TRUE(window->document().strokes().empty());
  MainWindow reopened;
  ASSERT_TRUE(reopened.openFile(path));
  EXPECT_EQ(reopened.document().strokes().size(), 2u) << "Save did not write the second stroke first";

  drawWithMouse(window->canvas(), wave());
  window.reset();  // unsaved and not discarded: the marker stays for the next start
  EXPECT_TRUE(QFileInfo::exists(marker));
  window = std::make_unique<MainWindow>();
  drawWithMouse(window->canvas(), wave());
  window->answerUnsavedChanges(QMessageBox::Discard);
  EXPECT_TRUE(window->close());
  window.reset();
  EXPECT_FALSE(QFileInfo::exists(marker)) << "an explicit discard ends the session cleanly";
  window = std::make_unique<MainWindow>();
}

// The charts' ticks sit at round values (issue 17, part 3: the LCG plot read 2.38, 2.6,
// 2.82): multiples of 1, 2 or 5 times a power of ten, about five over the range.
TEST(ChartTicks, AreRoundValuesInsideTheRange) {
  for (const auto& [lo, hi] : {std::pair{2.16, 3.04}, std::pair{-0.37, 12.9}, std::pair{-3e-5, 7e-5}, std::pair{100.0, 100.5}}) {
    const std::vector<double> ticks = roundTicks(lo, hi);
    ASSERT_GE(ticks.size(), 3u) << lo << " " << hi;
    EXPECT_LE(ticks.size(), 11u);
    const double step = tickStep(hi - lo);
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step)));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-9 || std::abs(mantissa - 2) < 1e-9 || std::abs(mantissa - 5) < 1e-9) << step;
    for (double t : ticks) {
      EXPECT_GE(t, lo - 1e-12);
      EXPECT_LE(t, hi + 1e-12);
      EXPECT_NEAR(t / step, std::round(t / step), 1e-9) << t;
    }
  }
}

// Delete removes the selected stroke (issue 17, part 1, its Delete key), undoably: undo
// puts it back as it was, fit and all, without a refit.
TEST_F(MainWindowTest, DeleteRemovesTheSelectedStrokeUndoably) {
  drawWithMouse(window->canvas(), wave());
  drawWithMouse(window->canvas(), wave(70));
  window->finishBackgroundFits();
  ASSERT_EQ(window->document().strokes().size(), 2u);
  const FitResult first = *window->document().strokes()[0].fit;
  const std::uint64_t second = window->document().strokes()[1].id;
  QAction* remove = actionNamed(*window, "&Delete");
  ASSERT_NE(remove, nullptr);
  EXPECT_TRUE(remove->shortcuts().contains(QKeySequence(QKeySequence::Delete)));
  remove->trigger();  // nothing selected: nothing goes
  EXPECT_EQ(window->document().strokes().size(), 2u);
  window->selectSegment(0, 0);
  remove->trigger();
  ASSERT_EQ(window->document().strokes().size(), 1u);
  EXPECT_EQ(window->document().strokes()[0].id, second);
  window->undoStack()->undo();
  ASSERT_EQ(window->document().strokes().size(), 2u);
  const FitResult& back = *window->document().strokes()[0].fit;
  ASSERT_EQ(back.curve.pieces.size(), first.curve.pieces.size());
  EXPECT_EQ(back.curve.pieces[0].segment.start(), first.curve.pieces[0].segment.start());
  window->undoStack()->redo();
  EXPECT_EQ(window->document().strokes().size(), 1u);
}

TEST_F(MainWindowTest, MouseStrokeIsFittedG2) {
  drawWithMouse(window->canvas(), wave());
  ASSERT_EQ(window->document().strokes().size(), 1u);
  const FitResult& r = lastFit();
  EXPECT_GE(r.quality.segments, 1);
  EXPECT_LT(r.quality.g2_gap, 1e-6) << "curvature continuous at every joint";
  EXPECT_LE(r.quality.max_dev, r.tolerance * (1 + 1e-9));
}

// Pen-up shows stages 1-6 at once; stage 7 runs on a worker thread and replaces that
// fit with exactly what fitStroke gives. A stroke undone, or edited by the user, before
// it comes back keeps what the user did.
TEST_F(MainWindowTest, PenUpFitsAtOnceAndStage7FollowsOffTheUiThread) {
  drawWithMouse(window->canvas(), wave());
  {
    const DocumentStroke& s = window->document().strokes().back();
    ASSERT_TRUE(s.fit.has_value()) << s.error;
    EXPECT_TRUE(s.provisional) << "stage 7 is on by default: it must not run on the UI thread";
  }
  auto statusText = [&] {
    QString text;
    for (const QLabel* label : window->statusBar()->findChildren<QLabel*>()) text += label->text();
    return text;
  };
  EXPECT_TRUE(statusText().contains("fitting the chain")) << statusText().toStdString();
  window->finishBackgroundFits();
  EXPECT_FALSE(statusText().contains("fitting the chain")) << statusText().toStdString();
  const DocumentStroke& done = window->document().strokes().back();
  EXPECT_FALSE(done.provisional);
  const FitResult direct = fitStroke(done.raw, window->document().options());
  ASSERT_TRUE(done.fit.has_value());
  EXPECT_EQ(done.fit->quality.segments, direct.quality.segments);
  EXPECT_DOUBLE_EQ(done.fit->quality.max_dev, direct.quality.max_dev);

  drawWithMouse(window->canvas(), wave(60));  // undone before its fit comes back
  window->undoStack()->undo();
  window->finishBackgroundFits();
  EXPECT_EQ(window->document().strokes().size(), 1u);

  drawWithMouse(window->canvas(), wave(70));  // edited before its fit comes back
  const std::size_t last = window->document().strokes().size() - 1;
  const FitResult& quick = *window->document().strokes()[last].fit;
  const int piece = firstSteerablePiece(quick);
  ASSERT_GE(piece, 0);
  const double steered = quick.curve.pieces[piece].segment.alpha() + 0.25;
  if (!window->document().steerSegment(last, piece, steered).empty()) FAIL() << "no G2 chain with that alpha";
  window->finishBackgroundFits();
  const DocumentStroke& edited = window->document().strokes()[last];
  EXPECT_FALSE(edited.provisional);
  EXPECT_NEAR(edited.fit->curve.pieces[piece].segment.alpha(), steered, 1e-12) << "the background fit undid the edit";
}

// A parameter change refits every stroke the same way: stages 1-6 at once, stage 7 in
// the background, ending as fitStroke with the new options. A stroke the user edited is
// refitted in full at once (its edits apply to the full fit).
TEST_F(MainWindowTest, ParameterChangeRefitsInTheBackgroundExceptEditedStrokes) {
  drawWithMouse(window->canvas(), wave());
  drawWithMouse(window->canvas(), wave(70));
  window->finishBackgroundFits();
  const FitResult& first = *window->document().strokes()[0].fit;
  const int piece = firstSteerablePiece(first);
  ASSERT_GE(piece, 0);
  const bool steered = window->document().steerSegment(0, piece, first.curve.pieces[piece].segment.alpha() + 0.2).empty();
  FitOptions o = window->document().options();
  o.tolerance_fraction = 0.004;
  window->parameters()->setOptions(o);
  emit window->parameters()->optionsChanged(o);
  const auto& strokes = window->document().strokes();
  EXPECT_EQ(strokes[0].provisional, !steered);
  EXPECT_TRUE(strokes[1].provisional);
  window->finishBackgroundFits();
  EXPECT_FALSE(strokes[1].provisional);
  const FitResult direct = fitStroke(strokes[1].raw, window->document().options());
  ASSERT_TRUE(strokes[1].fit.has_value());
  EXPECT_EQ(strokes[1].fit->quality.segments, direct.quality.segments);
  EXPECT_DOUBLE_EQ(strokes[1].fit->quality.max_dev, direct.quality.max_dev);
  EXPECT_DOUBLE_EQ(strokes[1].fit->tolerance, direct.tolerance);
}

// Parameter changes faster than stage 7 (here: every worker thread held while five
// changes come in) run only the newest background fit of each stroke; the others are
// dropped before they start, and every stroke ends as fitStroke with the last options.
TEST_F(MainWindowTest, RapidParameterChangesRunOnlyTheNewestBackgroundFit) {
  drawWithMouse(window->canvas(), wave());
  drawWithMouse(window->canvas(), wave(70));
  window->finishBackgroundFits();
  QThreadPool* pool = QThreadPool::globalInstance();
  // (every holder is running before the changes come in, and has returned before the
  // semaphores go: a holder still queued when the test ended once waited on a semaphore
  // gone, and the pool's exit waited on it for ever)
  QSemaphore started, held, returned;
  const int threads = pool->maxThreadCount();
  for (int i = 0; i < threads; ++i)
    pool->start([&] {
      started.release();
      held.acquire();
      returned.release();
    });
  started.acquire(threads);
  FitOptions o = window->document().options();
  constexpr int kChanges = 5;
  for (int k = 1; k <= kChanges; ++k) {
    o.tolerance_fraction = 0.004 + 0.0002 * k;
    window->parameters()->setOptions(o);
    emit window->parameters()->optionsChanged(o);
  }
  held.release(threads);
  returned.acquire(threads);
  window->finishBackgroundFits();
  EXPECT_EQ(window->supersededBackgroundFits(), (kChanges - 1) * 2);
  for (const DocumentStroke& s : window->document().strokes()) {
    EXPECT_FALSE(s.provisional);
    ASSERT_TRUE(s.fit.has_value()) << s.error;
    const FitResult direct = fitStroke(s.raw, o);
    EXPECT_EQ(s.fit->quality.segments, direct.quality.segments);
    EXPECT_DOUBLE_EQ(s.fit->quality.max_dev, direct.quality.max_dev);
    EXPECT_DOUBLE_EQ(s.fit->tolerance, direct.tolerance);
  }
}

TEST_F(MainWindowTest, PenStrokeKeepsPressureAndTime) {
  drawWithPen(window->canvas(), wave(80));
  ASSERT_EQ(window->document().strokes().size(), 1u);
  const Stroke& raw = window->document().strokes()[0].raw;
  ASSERT_GE(raw.samples.size(), 70u);
  EXPECT_NEAR(raw.samples.front().pressure, 0.3, 1e-6);
  EXPECT_GT(raw.samples[40].pressure, raw.samples.front().pressure);
  EXPECT_TRUE(lastFit().quality.g2_gap < 1e-6);
}

TEST_F(MainWindowTest, UndoRedoAndParameterChangeRefits) {
  drawWithMouse(window->canvas(), wave());
  drawWithMouse(window->canvas(), wave(60));
  EXPECT_EQ(window->document().strokes().size(), 2u);
  window->undoStack()->undo();
  EXPECT_EQ(window->document().strokes().size(), 1u);
  window->undoStack()->redo();
  EXPECT_EQ(window->document().strokes().size(), 2u);
  FitOptions o = window->document().options();
  o.g2 = G2Method::kOff;
  window->parameters()->setOptions(o);
  emit window->parameters()->optionsChanged(o);
  EXPECT_EQ(window->document().options().g2, G2Method::kOff);
  // (the stroke fitted again with the new options: stages 1-6's pieces, not G2)
  const FitResult refit = fitStroke(window->document().strokes().back().raw, window->document().options());
  EXPECT_EQ(lastFit().quality.segments, refit.quality.segments);
  EXPECT_DOUBLE_EQ(lastFit().quality.max_dev, refit.quality.max_dev);
  window->undoStack()->undo();
  EXPECT_EQ(window->document().options().g2, G2Method::kNewton);
  EXPECT_LT(lastFit().quality.g2_gap, 1e-6);
}

TEST_F(MainWindowTest, SaveAndReopenGivesTheSameCurves) {
  drawWithMouse(window->canvas(), wave());
  const QString path = dir.filePath("sketch.lafair.json");
  ASSERT_TRUE(window->saveFile(path));
  const Curve saved = lastFit().curve;
  MainWindow other;
  ASSERT_TRUE(other.openFile(path));
  other.finishBackgroundFits();  // (opening fits stages 1-6 at once, stage 7 in the background)
  ASSERT_EQ(other.document().strokes().size(), 1u);
  const Curve& reopened = other.document().strokes()[0].fit->curve;
  ASSERT_EQ(reopened.pieces.size(), saved.pieces.size());
  for (std::size_t i = 0; i < saved.pieces.size(); ++i) {
    EXPECT_DOUBLE_EQ(reopened.pieces[i].segment.length(), saved.pieces[i].segment.length());
    EXPECT_DOUBLE_EQ(reopened.pieces[i].segment.kappaEnd(), saved.pieces[i].segment.kappaEnd());
  }
}

// An airfoil .dat is a profile: its trailing edge is its one corner, its nose is round,
// also after the sketch is saved and opened again.
TEST_F(MainWindowTest, AnImportedProfileKeepsItsRoundNoseAcrossSaveAndReopen) {
  ASSERT_TRUE(window->importPoints(QString(LAFAIR_SHARED_DATA_DIR) + "/curves/airfoils/clark-y.dat"));
  EXPECT_EQ(lastFit().quality.corners, 1);
  const QString path = dir.filePath("foil.lafair.json");
  ASSERT_TRUE(window->saveFile(path));
  MainWindow other;
  ASSERT_TRUE(other.openFile(path));
  other.finishBackgroundFits();
  ASSERT_EQ(other.document().strokes().size(), 1u);
  EXPECT_TRUE(other.document().strokes()[0].raw.profile);
  EXPECT_EQ(other.document().strokes()[0].fit->quality.corners, 1);
}

// The status bar says what the clean-up left out of the last stroke: an MMG stroke whose
// first point lies far before the rest (a pen-down outlier).
TEST_F(MainWindowTest, TheStatusBarSaysWhatTheCleanUpLeftOut) {
  ASSERT_TRUE(window->importPoints(QString(LAFAIR_SHARED_DATA_DIR) + "/strokes/mmg_s10_stylus_medium/csv/10-stylus-medium-N-01.csv"));
  window->finishBackgroundFits();
  QString text;
  for (const QLabel* label : window->statusBar()->findChildren<QLabel*>()) text += label->text();
  const FitResult& fit = lastFit();
  ASSERT_FALSE(fit.cleaned.left_out.empty());
  EXPECT_TRUE(text.contains("samples left out")) << text.toStdString();
}

TEST_F(MainWindowTest, ImportEveryFileTypeAndExportEveryFormat) {
  const QString data = QString(LAFAIR_SHARED_DATA_DIR);
  for (const char* f : {"/strokes/dollar1_unistroke_s01_pilot/csv/medium/question_mark.csv", "/curves/airfoils/clark-y.dat",
                        "/curves/kanjivg/0306e.svg"})
    EXPECT_TRUE(window->importPoints(data + f)) << f;
  EXPECT_EQ(window->document().strokes().size(), 4u);  // 2 + 1 + 1
  for (const char* ext : {"svg", "dxf", "json", "csv"}) {
    const QString out = dir.filePath(QString("curves.") + ext);
    EXPECT_TRUE(window->exportFile(out)) << ext;
    EXPECT_GT(QFile(out).size(), 100) << ext;
  }
  // only the selected stroke: fewer curves in the JSON
  EXPECT_FALSE(window->exportFile(dir.filePath("none.json"), true)) << "nothing selected yet";
  window->selectSegment(3, 0);
  ASSERT_TRUE(window->exportFile(dir.filePath("one.json"), true));
  QFile all(dir.filePath("curves.json")), one(dir.filePath("one.json"));
  ASSERT_TRUE(all.open(QIODevice::ReadOnly) && one.open(QIODevice::ReadOnly));
  EXPECT_EQ(QString(one.readAll()).count("\"segments\""), 1);
  EXPECT_EQ(QString(all.readAll()).count("\"segments\""), 4);
}

TEST_F(MainWindowTest, BadFilesGiveAnErrorAndKeepTheSketch) {
  drawWithMouse(window->canvas(), wave());
  const QString bad = dir.filePath("bad.csv");
  QFile f(bad);
  ASSERT_TRUE(f.open(QIODevice::WriteOnly));
  f.write("1,2\n3,oops\n");
  f.close();
  EXPECT_FALSE(window->importPoints(bad));
  EXPECT_FALSE(window->openFile(bad));
  EXPECT_FALSE(window->openFile(dir.filePath("missing.json")));
  EXPECT_EQ(window->document().strokes().size(), 1u) << "the sketch is still there";
}

TEST_F(MainWindowTest, LivePreviewWhileThePenMoves) {
  Canvas* canvas = window->canvas();
  const auto pts = wave(60);
  QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, pts.front());
  for (std::size_t i = 1; i < pts.size(); ++i) {
    QMouseEvent move(QEvent::MouseMove, pts[i], canvas->mapToGlobal(pts[i]), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(canvas, &move);
  }
  EXPECT_TRUE(canvas->hasPreview()) << "no live fit while drawing";
  EXPECT_TRUE(window->document().strokes().empty()) << "nothing is added before pen-up";
  QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, pts.back());
  EXPECT_FALSE(canvas->hasPreview());
  EXPECT_EQ(window->document().strokes().size(), 1u);
}

TEST_F(MainWindowTest, RightClickSelectsASegmentAndPngExport) {
  drawWithMouse(window->canvas(), wave());
  const LaSegment& seg = lastFit().curve.pieces.front().segment;
  const QPointF on_curve = window->canvas()->toWidget(seg.position(0.5 * seg.length()));
  QTest::mouseClick(window->canvas(), Qt::RightButton, Qt::NoModifier, on_curve.toPoint());
  EXPECT_EQ(window->selectedStroke(), 0);
  EXPECT_EQ(window->selectedPiece(), 0) << "the click was on the first segment";
  const QString png = dir.filePath("picture.png");
  EXPECT_TRUE(window->exportPng(png));
  EXPECT_FALSE(QImage(png).isNull());
}

TEST_F(MainWindowTest, SteeringASegmentAlphaKeepsG2AndUndoes) {
  drawWithMouse(window->canvas(), wave());
  const FitResult before = lastFit();
  for (std::size_t i = 0; i < before.pieces.size(); ++i) {
    if (before.pieces[i].kind != PieceKind::kThreePoint) continue;
    window->selectSegment(0, static_cast<int>(i));
    const double wanted = std::clamp(before.curve.pieces[i].segment.alpha() + 0.3, -3.0, 3.0);
    emit window->parameters()->segmentAlphaChanged(wanted);
    const FitResult& after = lastFit();
    if (after.curve.pieces[i].segment.alpha() != wanted) continue;  // infeasible: reported in the status bar
    EXPECT_LT(after.quality.g2_gap, 1e-6);
    EXPECT_EQ(window->document().strokes()[0].alpha_overrides.count(static_cast<int>(i)), 1u);
    window->undoStack()->undo();
    EXPECT_DOUBLE_EQ(lastFit().curve.pieces[i].segment.alpha(), before.curve.pieces[i].segment.alpha());
    // kept in the saved sketch
    window->undoStack()->redo();
    const QString path = dir.filePath("steered.lafair.json");
    ASSERT_TRUE(window->saveFile(path));
    MainWindow other;
    ASSERT_TRUE(other.openFile(path));
    EXPECT_DOUBLE_EQ(other.document().strokes()[0].fit->curve.pieces[i].segment.alpha(), wanted);
    return;
  }
  FAIL() << "no steerable segment in this stroke";
}

// The alpha slider: dragging previews without editing, releasing makes one undoable edit.
TEST_F(MainWindowTest, AlphaSliderPreviewsWhileDraggedAndEditsOnRelease) {
  drawWithMouse(window->canvas(), wave());
  const FitResult before = lastFit();
  auto* slider = window->parameters()->findChild<QSlider*>();
  ASSERT_NE(slider, nullptr);
  for (std::size_t i = 0; i < before.pieces.size(); ++i) {
    if (before.pieces[i].kind != PieceKind::kThreePoint) continue;
    window->selectSegment(0, static_cast<int>(i));
    ASSERT_TRUE(slider->isEnabled());
    const int undo_steps = window->undoStack()->count();
    const double wanted = std::clamp(std::round((before.curve.pieces[i].segment.alpha() + 0.3) * 100.0) / 100.0, -3.0, 3.0);
    slider->setSliderDown(true);
    slider->setSliderPosition(static_cast<int>(std::lround(wanted * 100.0)));  // emits sliderMoved
    if (!window->canvas()->hasPreview()) continue;  // infeasible alpha for this piece: no preview, try another
    EXPECT_EQ(window->undoStack()->count(), undo_steps) << "dragging must not edit";
    EXPECT_DOUBLE_EQ(lastFit().curve.pieces[i].segment.alpha(), before.curve.pieces[i].segment.alpha());
    slider->setSliderDown(false);  // release: the value is committed
    EXPECT_FALSE(window->canvas()->hasPreview());
    EXPECT_EQ(window->undoStack()->count(), undo_steps + 1) << "one edit on release";
    EXPECT_NEAR(lastFit().curve.pieces[i].segment.alpha(), wanted, 1e-12);
    EXPECT_LT(lastFit().quality.g2_gap, 1e-6);
    return;
  }
  FAIL() << "no segment of this stroke takes that alpha";
}

TEST_F(MainWindowTest, CtrlDragAJointKeepsG2AndUndoes) {
  drawWithMouse(window->canvas(), wave());
  const FitResult before = lastFit();
  ASSERT_GE(before.curve.pieces.size(), 2u);
  Canvas* canvas = window->canvas();
  for (std::size_t i = 1; i < before.curve.pieces.size(); ++i) {
    if (before.curve.pieces[i].corner) continue;
    const QPoint from = canvas->toWidget(before.curve.pieces[i].segment.start()).toPoint();
    const QPoint to = from + QPoint(6, -8);
    QTest::mousePress(canvas, Qt::LeftButton, Qt::ControlModifier, from);
    QMouseEvent move(QEvent::MouseMove, to, canvas->mapToGlobal(to), Qt::NoButton, Qt::LeftButton, Qt::ControlModifier);
    QApplication::sendEvent(canvas, &move);
    QTest::mouseRelease(canvas, Qt::LeftButton, Qt::ControlModifier, to);
    EXPECT_EQ(window->document().strokes().size(), 1u) << "a joint drag draws no stroke";
    const FitResult& after = lastFit();
    const QPointF world = canvas->toWorld(to);
    if ((after.curve.pieces[i].segment.start() - Vec2(world.x(), world.y())).norm() > 1e-6 * after.quality.diagonal)
      continue;  // no G2 curve through that point: refused and reported
    EXPECT_LT(after.quality.g2_gap, 1e-6);
    window->undoStack()->undo();
    EXPECT_LT((lastFit().curve.pieces[i].segment.start() - before.curve.pieces[i].segment.start()).norm(),
              1e-9 * before.quality.diagonal);
    return;
  }
  FAIL() << "no joint could be moved";
}

// The selected segment shows its control triangle; ctrl+dragging its apex (Q1) turns
// both end tangents towards the new apex, the curve stays G2, and undo restores it.
TEST_F(MainWindowTest, CtrlDragTheApexKeepsG2AndUndoes) {
  drawWithMouse(window->canvas(), wave());
  const FitResult before = lastFit();
  Canvas* canvas = window->canvas();
  for (std::size_t i = 0; i < before.curve.pieces.size(); ++i) {
    const LaSegment& seg = before.curve.pieces[i].segment;
    const Vec2 a = seg.start(), b = seg.end(), u = seg.tangent(0.0), v = seg.tangent(seg.length());
    if (std::abs(seg.turning()) < 0.2 || std::abs(cross(u, v)) < 1e-3) continue;
    const Vec2 apex = a + (cross(b - a, v) / cross(u, v)) * u;
    window->selectSegment(0, static_cast<int>(i));  // shows its triangle and apex handle
    const QPoint from = canvas->toWidget(apex).toPoint();
    const QPoint to = from + QPoint(3, 4);
    QTest::mousePress(canvas, Qt::LeftButton, Qt::ControlModifier, from);
    QMouseEvent move(QEvent::MouseMove, to, canvas->mapToGlobal(to), Qt::NoButton, Qt::LeftButton, Qt::ControlModifier);
    QApplication::sendEvent(canvas, &move);
    QTest::mouseRelease(canvas, Qt::LeftButton, Qt::ControlModifier, to);
    EXPECT_EQ(window->document().strokes().size(), 1u) << "an apex drag draws no stroke";
    if (window->document().strokes()[0].apex_overrides.count(static_cast<int>(i)) == 0) continue;  // refused, reported
    const FitResult& after = lastFit();
    const LaSegment& moved = after.curve.pieces[i].segment;
    const QPointF w = canvas->toWorld(to);
    const Vec2 target(w.x(), w.y());
    EXPECT_LT((moved.tangent(0.0) - (target - moved.start()).normalized()).norm(), 1e-9);
    EXPECT_LT((moved.tangent(moved.length()) - (moved.end() - target).normalized()).norm(), 1e-9);
    EXPECT_LT(after.quality.g2_gap, 1e-6);
    window->undoStack()->undo();
    EXPECT_LT((lastFit().curve.pieces[i].segment.tangent(0.0) - u).norm(), 1e-12);
    return;
  }
  FAIL() << "no apex could be moved";
}

// Construct > LA segment: a curve from three handles. Dragging a handle re-solves it
// live and the curve ends on the handle; a parameter change, undo, save and reopen.
TEST_F(MainWindowTest, SegmentConstructionFollowsItsHandles) {
  window->addConstruction(ConstructionKind::kSegment);
  ASSERT_EQ(window->document().constructions().size(), 1u);
  EXPECT_EQ(window->selectedConstruction(), 0);
  const Construction& c = window->document().constructions()[0];
  ASSERT_TRUE(c.result.ok) << c.result.message;
  Canvas* canvas = window->canvas();
  const QPoint from = canvas->toWidget(c.handles[2]).toPoint();
  const QPoint to = from + QPoint(-10, 15);
  QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, from);
  QMouseEvent move(QEvent::MouseMove, to, canvas->mapToGlobal(to), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(canvas, &move);
  QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, to);
  EXPECT_TRUE(window->document().strokes().empty()) << "a handle drag draws no stroke";
  const Construction& moved = window->document().constructions()[0];
  const QPointF w = canvas->toWorld(to);
  ASSERT_TRUE(moved.result.ok) << moved.result.message;
  EXPECT_LT((moved.result.curve->pieces[0].segment.end() - Vec2(w.x(), w.y())).norm(), 1e-9 * (moved.handles[2] - moved.handles[0]).norm());

  Construction steeper = moved;
  steeper.parameters["alpha"] = 1.0;  // a logarithmic spiral through the same triangle
  window->editConstruction(0, moved, steeper, "alpha");
  EXPECT_DOUBLE_EQ(window->document().constructions()[0].result.curve->pieces[0].segment.alpha(), 1.0);
  window->undoStack()->undo();
  EXPECT_DOUBLE_EQ(window->document().constructions()[0].result.curve->pieces[0].segment.alpha(), -1.0);
  window->undoStack()->redo();

  const QString path = dir.filePath("constructed.lafair.json");
  ASSERT_TRUE(window->saveFile(path));
  MainWindow other;
  ASSERT_TRUE(other.openFile(path));
  ASSERT_EQ(other.document().constructions().size(), 1u);
  EXPECT_EQ(other.document().constructions()[0].handles, window->document().constructions()[0].handles);
  EXPECT_DOUBLE_EQ(other.document().constructions()[0].result.curve->pieces[0].segment.alpha(), 1.0);
  EXPECT_TRUE(window->exportFile(dir.filePath("constructed.svg")));
  window->undoStack()->undo();
  window->undoStack()->undo();
  window->undoStack()->undo();
  EXPECT_TRUE(window->document().constructions().empty());
}

// A finger on a touch screen draws like the mouse: the stroke is fitted on release.
TEST_F(MainWindowTest, TouchStrokeIsFitted) {
  QPointingDevice* screen = QTest::createTouchDevice(QInputDevice::DeviceType::TouchScreen);
  Canvas* canvas = window->canvas();
  const std::vector<QPoint> pts = wave();
  QTest::touchEvent(canvas, screen).press(0, pts.front());
  for (std::size_t i = 1; i < pts.size(); ++i) QTest::touchEvent(canvas, screen).move(0, pts[i]);
  QTest::touchEvent(canvas, screen).release(0, pts.back());
  ASSERT_EQ(window->document().strokes().size(), 1u);
  EXPECT_GE(window->document().strokes()[0].raw.samples.size(), pts.size() - 2);
  const FitResult& r = lastFit();
  EXPECT_GE(r.curve.pieces.size(), 1u);
  EXPECT_LT(r.quality.g2_gap, 1e-6);
  EXPECT_LE(r.quality.max_dev, r.tolerance * (1 + 1e-9));
}

TEST_F(MainWindowTest, BackgroundImageAndRecoveryMarker) {
  const QString png = dir.filePath("background.png");
  QImage image(200, 100, QImage::Format_RGB32);
  image.fill(Qt::yellow);
  ASSERT_TRUE(image.save(png));
  EXPECT_TRUE(window->loadBackground(png));
  EXPECT_TRUE(window->canvas()->hasBackground());
  EXPECT_FALSE(window->loadBackground(dir.filePath("missing.png")));
  // a session that did not end cleanly leaves its marker: the next start offers recovery
  drawWithMouse(window->canvas(), wave());
  ASSERT_TRUE(window->saveFile(window->autosavePath()));
  window->offerRecovery();  // this session's marker
  MainWindow next;          // as if the first had crashed: its marker is still there
  EXPECT_TRUE(next.offerRecovery());
}

// A stroke too long to fit within a frame (Document::kOffThreadFitSamples) is recorded at
// once, unfitted, and fitted entirely off the UI thread; undo and redo work meanwhile.
TEST_F(MainWindowTest, AHugeStrokeIsFittedOffTheUiThread) {
  Stroke huge;
  const std::size_t n = Document::kOffThreadFitSamples + 4000;
  for (std::size_t i = 0; i < n; ++i) {
    StrokeSample q;
    const double x = 600.0 * static_cast<double>(i) / (n - 1);
    q.p = Vec2(60 + x, 300 + 80 * std::sin(x / 100.0));
    huge.samples.push_back(q);
  }
  window->addStroke(huge);
  ASSERT_EQ(window->document().strokes().size(), 1u);
  const DocumentStroke& s = window->document().strokes().front();
  EXPECT_FALSE(s.fit.has_value()) << "no fit was made on the UI thread";
  EXPECT_TRUE(s.provisional);
  window->canvas()->grab();  // its points are drawn meanwhile
  const FitResult& fit = lastFit();
  EXPECT_LT(fit.quality.g2_gap, 1e-6);
  EXPECT_FALSE(window->document().strokes().front().provisional);
  saveScreenshot(*window, "huge-stroke-fitted");
  window->undoStack()->undo();
  EXPECT_TRUE(window->document().strokes().empty());
  window->undoStack()->redo();
  EXPECT_TRUE(lastFit().quality.max_dev < 0.05 * lastFit().quality.diagonal);
}

TEST_F(MainWindowTest, ScreenshotWithFittedCurveCombAndPlot) {
  window->importPoints(QString(LAFAIR_SHARED_DATA_DIR) + "/strokes/dollar1_unistroke_s01_pilot/csv/medium/question_mark.csv");
  window->finishBackgroundFits();  // the picture shows the fit as it ends up
  QApplication::processEvents();
  ASSERT_FALSE(window->document().strokes().empty()) << "the shared data's question mark did not import";
  ASSERT_TRUE(window->document().strokes().back().fit);
  ASSERT_GT(window->document().strokes().back().fit->curve.pieces.size(), 2u);
  {  // select a segment, so the LCG dock shows something
    const LaSegment& seg = window->document().strokes().back().fit->curve.pieces[2].segment;
    QTest::mouseClick(window->canvas(), Qt::RightButton, Qt::NoModifier,
                      window->canvas()->toWidget(seg.position(0.5 * seg.length())).toPoint());
  }
  // the curvature plot of both strokes on one axis (the README shows two curves compared)
  auto* plot = window->findChild<CurvaturePlot*>();
  ASSERT_NE(plot, nullptr);
  plot->setScope(CurvaturePlot::Scope::kAllVisible);
  QApplication::processEvents();
  EXPECT_EQ(plot->curveLengths().size(), 2u);
  const QImage shot = window->grab().toImage();
  ASSERT_FALSE(shot.isNull());
  const QString path = QString(LAFAIR_BINARY_DIR) + "/lafair-window.png";
  EXPECT_TRUE(shot.save(path)) << path.toStdString();
  // the curve is drawn: some pixels have the curve's blue
  int blue = 0;
  for (int y = 0; y < shot.height(); y += 2)
    for (int x = 0; x < shot.width(); x += 2) {
      const QColor c = shot.pixelColor(x, y);
      if (c.blue() > 150 && c.red() < 60 && c.green() < 140) ++blue;
    }
  EXPECT_GT(blue, 100) << "no curve pixels in the screenshot";
}

// Construct > compound rhythm, triple-LA Hermite, ALP: each gives a curve from its
// default handles; dragging the end handle re-solves it live and the curve still starts
// and ends on its handles, with continuous curvature at the joints of LA pieces; every
// parameter in reach of its slider solves or says why; the curve is saved, reopened and
// exported in every format.
class ConstructionKindTest : public MainWindowTest, public ::testing::WithParamInterface<ConstructionKind> {};

TEST_P(ConstructionKindTest, FollowsItsHandlesKeepsContinuityAndExports) {
  window->addConstruction(GetParam());
  ASSERT_EQ(window->document().constructions().size(), 1u);
  ASSERT_TRUE(window->document().constructions()[0].result.ok) << window->document().constructions()[0].result.message;
  Canvas* canvas = window->canvas();
  const Vec2 start_handle = window->document().constructions()[0].handles[3];
  const QPoint from = canvas->toWidget(start_handle).toPoint();
  const QPoint to = from + QPoint(-6, 9);
  QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, from);
  QMouseEvent move(QEvent::MouseMove, to, canvas->mapToGlobal(to), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
  QApplication::sendEvent(canvas, &move);
  QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, to);
  EXPECT_TRUE(window->document().strokes().empty()) << "a handle drag draws no stroke";
  const Construction& c = window->document().constructions()[0];
  ASSERT_TRUE(c.result.ok) << c.result.message;
  const double chord = (c.handles[3] - c.handles[0]).norm();
  const QPointF w = canvas->toWorld(to);
  EXPECT_LT((c.handles[3] - Vec2(w.x(), w.y())).norm(), 1e-9 * chord);
  EXPECT_LT((c.result.points.front() - c.handles[0]).norm(), 1e-8 * chord);
  EXPECT_LT((c.result.points.back() - c.handles[3]).norm(), 1e-8 * chord) << "the curve ends on the dragged handle";
  if (c.result.curve) {
    const auto& pieces = c.result.curve->pieces;
    for (std::size_t i = 1; i < pieces.size(); ++i) {
      const LaSegment &a = pieces[i - 1].segment, &b = pieces[i].segment;
      EXPECT_LT((a.end() - b.start()).norm(), 1e-9 * chord) << "joint " << i;
      EXPECT_NEAR(a.theta(a.length()), b.theta0(), 1e-9) << "joint " << i;
      EXPECT_NEAR(a.kappaEnd(), b.kappaStart(), 1e-8 * std::max(1.0, std::abs(a.kappaEnd()))) << "joint " << i;
    }
  }
  window->undoStack()->undo();
  EXPECT_EQ(window->document().constructions()[0].handles[3], start_handle) << "undo puts the handle back";
  window->undoStack()->redo();

  const QString path = dir.filePath("constructed.lafair.json");
  ASSERT_TRUE(window->saveFile(path));
  MainWindow other;
  ASSERT_TRUE(other.openFile(path));
  ASSERT_EQ(other.document().constructions().size(), 1u);
  EXPECT_EQ(other.document().constructions()[0].handles, window->document().constructions()[0].handles);
  EXPECT_EQ(other.document().constructions()[0].result.points.size(), c.result.points.size());
  for (const char* ext : {"svg", "dxf", "json", "csv"}) {
    const QString out = dir.filePath(QString("construction.") + ext);
    ASSERT_TRUE(window->exportFile(out, true)) << ext;
    QFile f(out);
    ASSERT_TRUE(f.open(QIODevice::ReadOnly)) << ext;
    EXPECT_GT(f.size(), 100) << ext;
  }
}

INSTANTIATE_TEST_SUITE_P(Kinds, ConstructionKindTest,
                         ::testing::Values(ConstructionKind::kCompound, ConstructionKind::kHermite, ConstructionKind::kAlp),
                         [](const ::testing::TestParamInfo<ConstructionKind>& info) { return std::string(toString(info.param)); });

}  // namespace
}  // namespace la::gui

int main(int argc, char** argv) {
  if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
  // CTest runs each test in a process of its own, several at once: each gets its own
  // home, so no two share the autosave file and its crash marker (a test saw another's
  // window remove the marker it had just left).
  const QTemporaryDir home;
  qputenv("HOME", home.path().toLocal8Bit());
  QApplication app(argc, argv);
  QStandardPaths::setTestModeEnabled(true);  // autosave and settings go to a test location
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
