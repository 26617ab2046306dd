// The curvature plot (issue 17, part 3, its plot half): it shows the selected stroke and
// shades the selected segment's arc-length range, its legend sits above the data, and it
// reads curvature, |curvature| on a log scale or radius. Driven through the real window.

#include <gtest/gtest.h>

#include <QComboBox>
#include <cmath>

#include "app/gui/curvature_plot.h"
#include "tests/gui/window_test_support.h"

namespace la::gui {
namespace {

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

}  // namespace
}  // namespace la::gui
