// The comb as live controls (issue 17, part 3): scale and teeth in a dock change the
// canvas' comb as they move; teeth are spaced evenly along each curve's arc length across
// its joints; the comb's scale is each curve's own or one shared by all; the marks on a
// curve have one symbol per meaning, named in a legend. Driven through the real window.

#include <gtest/gtest.h>

#include <QDoubleSpinBox>
#include <QRadioButton>
#include <QSlider>
#include <QSpinBox>
#include <algorithm>
#include <cmath>

#include "app/gui/canvas.h"
#include "app/gui/comb_panel.h"
#include "app/gui/markers.h"
#include "fitting/quality.h"
#include "tests/gui/window_test_support.h"

namespace la::gui {
namespace {

// Position, tangent and curvature of a curve at arc length s from its start.
struct AtArcLength {
  Vec2 point, tangent;
  double kappa;
};
AtArcLength atArcLength(const Curve& curve, double s) {
  for (std::size_t i = 0; i < curve.pieces.size(); ++i) {
    const LaSegment& seg = curve.pieces[i].segment;
    if (s <= seg.length() || i + 1 == curve.pieces.size()) {
      s = std::min(s, seg.length());
      return {seg.position(s), seg.tangent(s), seg.kappa(s)};
    }
    s -= seg.length();
  }
  return {};
}

double curveLength(const Curve& curve) {
  double length = 0.0;
  for (const CurvePiece& piece : curve.pieces) length += piece.segment.length();
  return length;
}

// Reddish comb pixels in a grab of the canvas.
int combPixels(QWidget* canvas) {
  const QImage image = canvas->grab().toImage();
  int n = 0;
  for (int y = 0; y < image.height(); ++y)
    for (int x = 0; x < image.width(); ++x) {
      const QColor c = image.pixelColor(x, y);
      n += c.red() > 200 && c.green() < 190 && c.blue() < 190 && c.red() - c.green() > 40;
    }
  return n;
}

TEST_F(MainWindowTest, CombControlsAreLiveAndTeethEvenAlongTheArc) {
  drawWithMouse(window->canvas(), wave());
  const FitResult& fit = lastFit();
  ASSERT_GE(fit.curve.pieces.size(), 3u) << "a stroke of several segments";
  Canvas* canvas = window->canvas();
  auto* panel = window->findChild<CombPanel*>();
  ASSERT_NE(panel, nullptr);
  EXPECT_TRUE(panel->isVisible()) << "the comb controls are in a dock on screen";
  auto* teeth = panel->findChild<QSpinBox*>("comb-teeth");
  auto* scale_slider = panel->findChild<QSlider*>("comb-scale-slider");
  auto* scale = panel->findChild<QDoubleSpinBox*>("comb-scale");
  ASSERT_TRUE(teeth && scale_slider && scale);

  teeth->setValue(50);
  EXPECT_EQ(canvas->layers().comb_teeth, 50) << "not live";
  const Comb comb = canvas->combOf(0);
  ASSERT_EQ(comb.base.size(), 50u);
  const double length = curveLength(fit.curve);
  const double spacing = length / 49.0;
  for (std::size_t k = 0; k < comb.base.size(); ++k) {
    EXPECT_NEAR(comb.s[k], k * spacing, 1e-9 * length) << "tooth " << k;
    const AtArcLength at = atArcLength(fit.curve, comb.s[k]);
    EXPECT_LT((comb.base[k] - at.point).norm(), 1e-8 * length) << "tooth " << k << " is not on the curve at its arc length";
    const Vec2 tooth = comb.tip[k] - comb.base[k];
    EXPECT_NEAR(tooth.norm(), comb.gain * std::abs(at.kappa), 1e-9 * comb.gain * fit.quality.max_abs_kappa) << "tooth " << k;
    EXPECT_LT(std::abs(tooth.dot(at.tangent)), 1e-9 * (1 + tooth.norm())) << "tooth " << k << " not normal to the curve";
    if (std::abs(at.kappa) > 1e-9) {
      EXPECT_LT(tooth.dot(Vec2(-at.tangent.y(), at.tangent.x())) * at.kappa, 0.0) << "points inward";
    }
  }
  // the longest tooth is the scale's share of the view's shorter side
  const double side = std::min(canvas->width(), canvas->height());
  EXPECT_NEAR(comb.gain * fit.quality.max_abs_kappa * canvas->view().m11(), 0.08 * side, 1e-9 * side);

  const int pixels_before = combPixels(canvas);
  scale_slider->setValue(250);  // 25 % of the view
  EXPECT_DOUBLE_EQ(scale->value(), 25.0) << "slider and field disagree";
  EXPECT_DOUBLE_EQ(canvas->layers().comb_scale, 0.25) << "not live";
  EXPECT_NEAR(canvas->combOf(0).gain / comb.gain, 0.25 / 0.08, 1e-12);
  EXPECT_GT(combPixels(canvas), pixels_before + 100) << "the drawn comb did not grow";
  scale->setValue(4.0);
  EXPECT_EQ(scale_slider->value(), 40);
  EXPECT_DOUBLE_EQ(canvas->layers().comb_scale, 0.04);
}

// Per curve, each curve's largest curvature gets the full tooth; shared, one gain for all
// (set by the largest curvature of any curve), so the combs of two curves compare.
TEST_F(MainWindowTest, CombScaleIsPerCurveOrSharedByAllCurves) {
  drawWithMouse(window->canvas(), wave());
  std::vector<QPoint> tight;  // a small, tightly bent arc: larger curvature
  for (int i = 0; i <= 40; ++i) {
    const double a = M_PI * i / 40.0;
    tight.emplace_back(static_cast<int>(600 + 40 * std::cos(a)), static_cast<int>(120 - 40 * std::sin(a)));
  }
  drawWithMouse(window->canvas(), tight);
  window->finishBackgroundFits();
  ASSERT_EQ(window->document().strokes().size(), 2u);
  Canvas* canvas = window->canvas();
  const double k0 = maxAbsCurvature(window->document().strokes()[0].fit->curve);
  const double k1 = maxAbsCurvature(window->document().strokes()[1].fit->curve);
  ASSERT_GT(k1, 1.5 * k0) << "the arc should bend tighter than the wave";
  auto* panel = window->findChild<CombPanel*>();
  auto* per_curve = panel->findChild<QRadioButton*>("comb-per-curve");
  auto* shared = panel->findChild<QRadioButton*>("comb-shared");
  ASSERT_TRUE(per_curve && shared);
  EXPECT_TRUE(per_curve->isChecked());
  EXPECT_NEAR(canvas->combOf(0).gain * k0, canvas->combOf(1).gain * k1, 1e-9 * canvas->combOf(1).gain * k1)
      << "per curve: each curve's largest curvature has the longest tooth";
  shared->click();
  EXPECT_TRUE(canvas->layers().comb_shared) << "not live";
  EXPECT_DOUBLE_EQ(canvas->combOf(0).gain, canvas->combOf(1).gain) << "shared: one gain";
  EXPECT_NEAR(canvas->combOf(1).gain * k1 * canvas->view().m11(), canvas->layers().comb_scale * std::min(canvas->width(), canvas->height()), 1e-6);
  saveScreenshot(*window, "comb-shared-scale");
  per_curve->click();
  EXPECT_FALSE(canvas->layers().comb_shared);
}

// Joint, inflection, curvature extremum and corner have symbols of their own (the square
// meant both joint and extremum), named in the dock's legend with the same drawing; on a
// wave the marks agree with the quality figures' extrema and inflections.
TEST_F(MainWindowTest, MarksHaveDistinctSymbolsNamedInALegend) {
  auto* legend = window->findChild<MarkerLegend*>();
  ASSERT_NE(legend, nullptr);
  EXPECT_TRUE(legend->isVisible());
  for (const char* name : {"joint (G2)", "inflection", "curvature extremum", "corner (G0)"})
    EXPECT_TRUE(legend->entries().contains(name)) << name;
  std::vector<QImage> symbols;
  for (MarkerKind kind : kMarkerKinds) {
    QImage image(24, 24, QImage::Format_ARGB32);
    image.fill(Qt::white);
    QPainter p(&image);
    p.setPen(QPen(Qt::black, 1.0));
    drawMarker(p, kind, QPointF(12, 12));
    p.end();
    for (const QImage& other : symbols) EXPECT_NE(image, other) << markerName(kind).toStdString() << " looks like another mark";
    symbols.push_back(image);
  }

  drawWithMouse(window->canvas(), wave());
  const FitResult& fit = lastFit();
  ASSERT_EQ(fit.quality.corners, 0);
  const std::vector<CurveMarker> marks = curveMarkers(fit.curve, fit.quality.diagonal);
  ASSERT_EQ(marks.size(), fit.curve.pieces.size() + 1) << "one at each joint and end";
  auto count = [&](MarkerKind kind) { return std::count_if(marks.begin(), marks.end(), [&](const CurveMarker& m) { return m.kind == kind; }); };
  int extrema = 0;
  for (int n : fit.quality.extrema_per_part) extrema += n;
  EXPECT_EQ(count(MarkerKind::kExtremum), extrema);
  EXPECT_EQ(count(MarkerKind::kInflection), fit.quality.inflections);
  EXPECT_GT(count(MarkerKind::kExtremum) + count(MarkerKind::kInflection), 0) << "a wave has both";
  EXPECT_EQ(count(MarkerKind::kEnd), 2);
}

}  // namespace
}  // namespace la::gui
