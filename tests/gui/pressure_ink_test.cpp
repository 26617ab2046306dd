// Ink from pen pressure (issue 17, part 8): the stroke being drawn (ink) and a drawn
// stroke's raw samples (dots as wide as the ink) follow the pen's pressure in width, as in
// tablet drawing apps; the View menu turns it off (constant-width ink, and dots of one
// size for the raw samples). Widths are read off the canvas as drawn: the ink across the
// stroke in one column, by coverage.

#include <QImage>
#include <algorithm>

#include "tests/gui/window_test_support.h"

namespace la::gui {
namespace {

// The ink across column x, in pixels of full ink: each pixel's darkness against the white
// canvas as a share of the ink's own (`ink_gray`), so antialiased edges count by coverage.
double inkAcross(const QImage& image, int x, int ink_gray) {
  double n = 0.0;
  for (int y = 0; y < image.height(); ++y) n += std::max(0.0, (255.0 - qGray(image.pixel(x, y))) / (255.0 - ink_gray));
  return n;
}

// A horizontal pen stroke at y = 200 from x = 60 to 540, its pressure rising from 0.1 to 1,
// left down (released by the caller).
void penAcross(QWidget* canvas) {
  sendPen(canvas, QEvent::TabletPress, QPointF(60, 200), 0.1);
  for (int x = 62; x <= 540; x += 2) sendPen(canvas, QEvent::TabletMove, QPointF(x, 200), 0.1 + 0.9 * (x - 60) / 480.0);
}

TEST_F(MainWindowTest, InkWidthFollowsThePenPressure) {
  Canvas* canvas = window->canvas();
  QAction* ink = actionNamed(*window, "Ink from pen &pressure");
  ASSERT_NE(ink, nullptr);
  ASSERT_TRUE(ink->isChecked()) << "on by default, as in tablet drawing apps";

  // nothing over the ink: the curve (and the live preview's), comb and marks off
  for (const char* layer : {"LA curve", "Curvature comb", "Joints, inflections, corners"}) {
    QAction* a = actionNamed(*window, layer);
    ASSERT_NE(a, nullptr) << layer;
    if (a->isChecked()) a->trigger();
  }
  penAcross(canvas);  // the stroke in progress (ink color 60, 60, 60)
  QImage drawn = canvas->grab().toImage();
  // pressure 0.175 and 0.925 of the full 4 px
  const double light = inkAcross(drawn, 100, 60), heavy = inkAcross(drawn, 500, 60);
  EXPECT_NEAR(light, 0.7, 0.2);
  EXPECT_NEAR(heavy, 3.7, 0.3);
  saveScreenshot(*window, "pressure-ink");

  ink->trigger();  // off: one width along the stroke
  drawn = canvas->grab().toImage();
  EXPECT_NEAR(inkAcross(drawn, 100, 60), inkAcross(drawn, 500, 60), 0.2);
  ink->trigger();
  sendPen(canvas, QEvent::TabletRelease, QPointF(540, 200), 0.0);
  window->finishBackgroundFits();
  ASSERT_EQ(window->document().strokes().size(), 1u);

  // the drawn stroke's raw samples (grey 150), as dots as wide as the ink (a dot under a
  // pixel wide blits lighter than a line that wide)
  drawn = canvas->grab().toImage();
  EXPECT_NEAR(inkAcross(drawn, 100, 150), 0.7, 0.35);
  EXPECT_NEAR(inkAcross(drawn, 500, 150), 3.7, 0.3);
}

}  // namespace
}  // namespace la::gui
