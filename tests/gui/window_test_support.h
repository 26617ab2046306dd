#pragma once
// What the GUI tests share: strokes drawn with synthesized mouse and tablet events, drags
// and clicks on the canvas, and the fixture that shows the real window offscreen.

#include <gtest/gtest.h>

#include <QAction>
#include <QApplication>
#include <QDir>
#include <QImage>
#include <QMouseEvent>
#include <QPointingDevice>
#include <QTabletEvent>
#include <QTemporaryDir>
#include <QTest>
#include <cmath>
#include <memory>
#include <vector>

#include "app/gui/canvas.h"
#include "app/gui/main_window.h"

namespace la::gui {

// A wavy stroke across the canvas in widget coordinates.
inline std::vector<QPoint> wave(int n = 120) {
  std::vector<QPoint> pts;
  for (int i = 0; i < n; ++i) {
    const double x = 60 + 5.0 * i;
    pts.emplace_back(static_cast<int>(x), static_cast<int>(300 + 90 * std::sin(x / 110.0)));
  }
  return pts;
}

inline void drawWithMouse(QWidget* canvas, const std::vector<QPoint>& pts) {
  QTest::mousePress(canvas, Qt::LeftButton, Qt::NoModifier, pts.front());
  for (std::size_t i = 1; i < pts.size(); ++i) {
    QMouseEvent move(QEvent::MouseMove, pts[i], canvas->mapToGlobal(pts[i]), Qt::NoButton, Qt::LeftButton, Qt::NoModifier);
    QApplication::sendEvent(canvas, &move);
  }
  QTest::mouseRelease(canvas, Qt::LeftButton, Qt::NoModifier, pts.back());
}

// One tablet event of the pen at `pos` (widget pixels) with `pressure` (0..1).
inline void sendPen(QWidget* canvas, QEvent::Type type, QPointF pos, double pressure) {
  QTabletEvent e(type, QPointingDevice::primaryPointingDevice(), pos, canvas->mapToGlobal(pos), pressure, 0.0f, 0.0f,
                 0.0f, 0.0f, 0.0f, Qt::NoModifier, type == QEvent::TabletRelease ? Qt::NoButton : Qt::LeftButton,
                 Qt::LeftButton);
  QApplication::sendEvent(canvas, &e);
}

// A pen stroke whose pressure rises from 0.3 to 0.7.
inline void drawWithPen(QWidget* canvas, const std::vector<QPoint>& pts) {
  sendPen(canvas, QEvent::TabletPress, pts.front(), 0.3);
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) sendPen(canvas, QEvent::TabletMove, pts[i], 0.3 + 0.4 * i / pts.size());
  sendPen(canvas, QEvent::TabletRelease, pts.back(), 0.0);
}

// A drag with the left button from `from` to `to` in `steps` moves, as a hand makes it.
inline void dragOnCanvas(QWidget* canvas, QPoint from, QPoint to, Qt::KeyboardModifiers modifiers = Qt::NoModifier,
                         int steps = 6) {
  QTest::mousePress(canvas, Qt::LeftButton, modifiers, from);
  for (int i = 1; i <= steps; ++i) {
    const QPoint at = from + (to - from) * i / steps;
    QMouseEvent move(QEvent::MouseMove, at, canvas->mapToGlobal(at), Qt::NoButton, Qt::LeftButton, modifiers);
    QApplication::sendEvent(canvas, &move);
  }
  QTest::mouseRelease(canvas, Qt::LeftButton, modifiers, to);
}

// The window's action with this text (mnemonic ampersands included), or null.
inline QAction* actionNamed(QWidget& w, const QString& text) {
  for (QAction* a : w.findChildren<QAction*>())
    if (a->text() == text) return a;
  return nullptr;
}

// The whole window as it is, saved as <build>/screenshots/<name>.png: what a test checked,
// for a person to look at (the issues' closing notes point at them).
inline void saveScreenshot(QWidget& window, const QString& name) {
  QApplication::processEvents();
  const QString folder = QString(LAFAIR_BINARY_DIR) + "/screenshots";
  QDir().mkpath(folder);
  EXPECT_TRUE(window.grab().toImage().save(folder + "/" + name + ".png")) << name.toStdString();
}

class MainWindowTest : public ::testing::Test {
 protected:
  void SetUp() override {
    qputenv("LAFAIR_NO_DIALOGS", "1");  // errors go to the status bar, not a modal box
    window = std::make_unique<MainWindow>();
    window->resize(1100, 760);
    window->show();
    // Most tests draw strokes over each other on purpose (wave() then wave(70), its first
    // part): those are new strokes there, not oversketches. The oversketch tests turn it on.
    window->setOversketch(false);
    ASSERT_TRUE(dir.isValid());
  }
  // The last stroke's fit as it ends up (stage 7 done: it runs off the UI thread).
  const FitResult& lastFit() {
    window->finishBackgroundFits();
    const auto& s = window->document().strokes();
    EXPECT_FALSE(s.empty());
    EXPECT_TRUE(s.back().fit.has_value()) << s.back().error;
    return *s.back().fit;
  }
  std::unique_ptr<MainWindow> window;
  QTemporaryDir dir;
};

}  // namespace la::gui
