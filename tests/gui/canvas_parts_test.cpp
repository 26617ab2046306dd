// The canvas' parts without a window: the comb's teeth (comb.h), the marks on a curve
// (markers.h), moving a fitted stroke (translate.h) and picking strokes (selection.h).
// Curves are built from LA segments with known curvatures, so every expected value is
// exact; strokes are made by formula (no random data).

#include <gtest/gtest.h>

#include <QImage>
#include <QPainter>
#include <QTransform>
#include <cmath>

#include "app/gui/comb.h"
#include "app/gui/document.h"
#include "app/gui/markers.h"
#include "app/gui/selection.h"
#include "app/gui/stroke_drawing.h"
#include "app/gui/translate.h"

namespace la::gui {
namespace {

// A chain of LA segments (alpha -1, a clothoid) through the given end curvatures, each of
// length `length`, joined G2 except where `corner` says (the tangent turns by 1 rad there).
Curve chain(const std::vector<std::pair<double, double>>& kappas, const std::vector<bool>& corner, double length = 10.0) {
  Curve c;
  Vec2 at(0, 0);
  double theta = 0.0;
  for (std::size_t i = 0; i < kappas.size(); ++i) {
    if (corner[i]) theta += 1.0;
    const auto [k0, k1] = kappas[i];
    const LaSegment seg = k0 == k1 ? LaSegment::arc(length, at, theta, k0) : LaSegment(-1.0, length, at, theta, k0, k1);
    c.pieces.push_back({seg, static_cast<bool>(corner[i])});
    at = seg.end();
    theta = seg.theta(seg.length());
  }
  return c;
}

// rising, rising, falling (an extremum at joint 2), falling to 0, 0 to negative (an
// inflection at joint 4), a corner into an arc
Curve markedCurve() {
  return chain({{0.05, 0.1}, {0.1, 0.15}, {0.15, 0.05}, {0.05, 0.0}, {0.0, -0.1}, {-0.08, -0.08}},
               {false, false, false, false, false, true});
}

TEST(CurveMarkers, OneSymbolPerMeaningAtEveryJoint) {
  const std::vector<CurveMarker> marks = curveMarkers(markedCurve(), 50.0);
  const std::vector<MarkerKind> want{MarkerKind::kEnd,      MarkerKind::kJoint,      MarkerKind::kExtremum, MarkerKind::kJoint,
                                     MarkerKind::kInflection, MarkerKind::kCorner, MarkerKind::kEnd};
  ASSERT_EQ(marks.size(), want.size());
  const Curve c = markedCurve();
  for (std::size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(static_cast<int>(marks[i].kind), static_cast<int>(want[i])) << "joint " << i;
    const Vec2 at = i < c.pieces.size() ? c.pieces[i].segment.start() : c.pieces.back().segment.end();
    EXPECT_LT((marks[i].at - at).norm(), 1e-12) << "joint " << i;
  }
  for (MarkerKind a : kMarkerKinds)
    for (MarkerKind b : kMarkerKinds)
      if (a != b) {
        EXPECT_NE(markerName(a), markerName(b));
      }
}

TEST(CurvatureComb, TeethEvenInArcLengthAcrossJointsAndTheEnvelopeJumpsAtACorner) {
  const Curve c = markedCurve();
  const double length = 6 * 10.0, gain = 20.0;
  const int teeth = 17;  // 60 / 16 = 3.75 apart: teeth fall between the joints (every 10)
  const Comb comb = curvatureComb(c, gain, teeth);
  ASSERT_EQ(comb.base.size(), static_cast<std::size_t>(teeth));
  for (int k = 0; k < teeth; ++k) {
    const double s = length * k / (teeth - 1);
    EXPECT_NEAR(comb.s[k], s, 1e-12 * length);
    const std::size_t piece = std::min<std::size_t>(static_cast<std::size_t>(s / 10.0), 5);
    const LaSegment& seg = c.pieces[piece].segment;
    const double local = s - 10.0 * piece;
    EXPECT_LT((comb.base[k] - seg.position(local)).norm(), 1e-9) << "tooth " << k;
    const Vec2 normal(-seg.tangent(local).y(), seg.tangent(local).x());
    EXPECT_LT((comb.tip[k] - (seg.position(local) - gain * seg.kappa(local) * normal)).norm(), 1e-9) << "tooth " << k;
  }
  // the envelope passes through both sides of the corner at joint 5: the tips of the
  // curvature -0.1 before it (a tooth 2 long) and -0.08 after it (1.6 long)
  const Vec2 corner = c.pieces[5].segment.start();
  bool before = false, after = false;
  for (const Vec2& q : comb.envelope) {
    before = before || std::abs((q - corner).norm() - gain * 0.1) < 1e-9;
    after = after || std::abs((q - corner).norm() - gain * 0.08) < 1e-9;
  }
  EXPECT_TRUE(before && after) << "the envelope does not show the jump at the corner";
  EXPECT_DOUBLE_EQ(maxAbsCurvature(c), 0.15);
}

TEST(CurvatureComb, FromSamplesInterpolatesEvenTeeth) {
  std::vector<double> s, kappa;
  std::vector<Vec2> points, normals;
  for (int i = 0; i <= 100; ++i) {  // a circle's quarter of radius 10: kappa 0.1
    const double a = 0.5 * M_PI * i / 100.0;
    s.push_back(10.0 * a);
    points.emplace_back(10 * std::cos(a), 10 * std::sin(a));
    normals.emplace_back(-std::cos(a), -std::sin(a));  // left of a counter-clockwise turn
    kappa.push_back(0.1);
  }
  const Comb comb = curvatureComb(s, points, normals, kappa, 30.0, 9);
  ASSERT_EQ(comb.base.size(), 9u);
  for (std::size_t k = 0; k < 9; ++k) {
    EXPECT_NEAR(comb.s[k], s.back() * k / 8.0, 1e-12);
    EXPECT_NEAR(comb.base[k].norm(), 10.0, 2e-3) << "on the circle (chords of 0.9 degrees)";
    EXPECT_NEAR(comb.tip[k].norm(), 13.0, 2e-3) << "outside, 0.1 * 30 long";
  }
}

// A closed stroke (a periodic spline) and an open one: moved, every position in the fit
// moves by the same vector and nothing else changes.
TEST(TranslateStroke, MovesEveryPositionOfTheFitAndNothingElse) {
  for (const bool closed : {false, true}) {
    Stroke raw;
    for (int i = 0; i <= 120; ++i) {
      const double a = (closed ? 2.0 : 1.2) * M_PI * i / 120.0;
      raw.samples.push_back({Vec2(100 * std::cos(a), 60 * std::sin(a) + 10 * std::sin(3 * a)), 8.0 * i});
    }
    Document doc;
    doc.addStroke(raw);
    ASSERT_TRUE(doc.strokes()[0].fit) << doc.strokes()[0].error;
    const DocumentStroke before = doc.strokes()[0];
    ASSERT_EQ(before.fit->curve.closed, closed);
    ASSERT_FALSE(before.fit->splines.empty());
    if (closed) {
      ASSERT_TRUE(before.fit->splines[0].isPeriodic()) << "the closed case should test a periodic spline";
    }
    const Vec2 d(-31.5, 270.25);
    doc.translateStrokes({0}, d);
    const DocumentStroke& after = doc.strokes()[0];
    for (std::size_t i = 0; i < raw.samples.size(); ++i) {
      EXPECT_LT((after.raw.samples[i].p - before.raw.samples[i].p - d).norm(), 1e-12);
      EXPECT_EQ(after.raw.samples[i].t, before.raw.samples[i].t);
    }
    const FitResult &a = *before.fit, &b = *after.fit;
    for (std::size_t i = 0; i < a.curve.pieces.size(); ++i) {
      const LaSegment &sa = a.curve.pieces[i].segment, &sb = b.curve.pieces[i].segment;
      for (double f : {0.0, 0.3, 1.0}) {
        EXPECT_LT((sb.position(f * sa.length()) - sa.position(f * sa.length()) - d).norm(), 1e-9);
        EXPECT_EQ(sb.theta(f * sa.length()), sa.theta(f * sa.length()));
        EXPECT_EQ(sb.kappa(f * sa.length()), sa.kappa(f * sa.length()));
      }
    }
    for (std::size_t k = 0; k < a.splines.size(); ++k) {
      EXPECT_EQ(b.splines[k].isPeriodic(), a.splines[k].isPeriodic());
      for (int j = 0; j <= 10; ++j) {
        const double t = a.splines[k].tMin() + (a.splines[k].tMax() - a.splines[k].tMin()) * j / 10.0;
        EXPECT_LT((b.splines[k].point(t) - a.splines[k].point(t) - d).norm(), 1e-9) << "spline " << k << " t " << t;
        EXPECT_NEAR(b.splines[k].curvature(t), a.splines[k].curvature(t), 1e-12);
      }
    }
    for (std::size_t i = 0; i < a.cleaned.points.size(); ++i) EXPECT_LT((b.cleaned.points[i] - a.cleaned.points[i] - d).norm(), 1e-12);
    EXPECT_EQ(b.quality.max_dev, a.quality.max_dev);
  }
}

TEST(TranslateStroke, MovesTheUsersJointAndApexPositions) {
  DocumentStroke s;
  s.raw.samples.push_back({Vec2(1, 2)});
  s.joint_overrides[1] = Vec2(3, 4);
  s.apex_overrides[0] = Vec2(5, 6);
  s.alpha_overrides[0] = -0.5;
  translateStroke(s, Vec2(10, 20));
  EXPECT_EQ(s.raw.samples[0].p, Vec2(11, 22));
  EXPECT_EQ(s.joint_overrides[1], Vec2(13, 24));
  EXPECT_EQ(s.apex_overrides[0], Vec2(15, 26));
  EXPECT_EQ(s.alpha_overrides[0], -0.5);
}

TEST(StrokePicking, NearestWithinReachAndWhollyInsideTheBand) {
  Document doc;
  for (double y : {0.0, 100.0}) {
    Stroke raw;
    for (int i = 0; i <= 60; ++i) raw.samples.push_back({Vec2(5.0 * i, y + 20 * std::sin(i / 10.0))});
    doc.addStroke(raw);
  }
  QTransform view;
  view.translate(50, 50);  // world to widget
  const LaSegment& seg = doc.strokes()[1].fit->curve.pieces.front().segment;
  const Vec2 on = seg.position(0.5 * seg.length());
  const QPointF at = view.map(QPointF(on.x(), on.y()));
  EXPECT_EQ(strokeAt(doc, view, at).stroke, 1);
  EXPECT_EQ(strokeAt(doc, view, at).piece, 0);
  EXPECT_EQ(strokeAt(doc, view, at + QPointF(0, kPickReachPixels - 1)).stroke, 1);
  EXPECT_EQ(strokeAt(doc, view, at + QPointF(0, 40)).stroke, -1) << "40 pixels from both";
  EXPECT_EQ(strokesInside(doc, view, QRectF(0, 0, 400, 100)), std::vector<std::size_t>{0});
  EXPECT_EQ(strokesInside(doc, view, QRectF(0, 0, 400, 200)), (std::vector<std::size_t>{0, 1}));
  EXPECT_TRUE(strokesInside(doc, view, QRectF(0, 0, 200, 200)).empty()) << "half a stroke is not inside";

  Selection selection;
  selection.set(doc, {1});
  const std::uint64_t id1 = doc.strokes()[1].id;
  doc.removeStroke(0);  // ids, not indices: the selected stroke is still selected at its new index
  EXPECT_EQ(selection.indices(doc), std::vector<std::size_t>{0});
  EXPECT_EQ(doc.strokes()[0].id, id1);
  selection.toggle(doc.strokes()[0]);
  EXPECT_TRUE(selection.indices(doc).empty());
}

// Level of detail: 200,000 samples along 1000 pixels, with 0.3 px of jitter, are drawn as
// at most ~2 per pixel of length per pixel of width (one per 0.5 px cell); the ends stay.
TEST(StrokeDrawing, RawPointsAreThinnedToAboutTwoPerPixel) {
  std::vector<StrokeSample> pts(200000);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double x = 1000.0 * static_cast<double>(i) / (pts.size() - 1);
    pts[i].p = Vec2(x, 300.0 + 0.3 * std::sin(0.7 * static_cast<double>(i)));  // jitter by formula
  }
  const QPolygonF drawn = decimatedPoints(pts, QTransform());
  const double cells_per_pixel = 1.0 / kRawPointStepPixels;
  const double bound = 1000.0 * cells_per_pixel * (0.6 * 2 + 1) * cells_per_pixel;  // length x (band width + 1 cell)
  EXPECT_LE(drawn.size(), bound) << "kept " << drawn.size() << " of 200000";
  EXPECT_GE(drawn.size(), 1000.0 * cells_per_pixel) << "every half pixel along the stroke has its dot";
  EXPECT_EQ(drawn.front(), QPointF(0, 300));
  EXPECT_EQ(drawn.back(), QPointF(pts.back().p.x(), pts.back().p.y()));
  // zoomed out 10x, the same stroke is 100 px long: ~10x fewer dots
  QTransform zoom;
  zoom.scale(0.1, 0.1);
  EXPECT_LE(decimatedPoints(pts, zoom).size(), 100.0 * cells_per_pixel * 3 + 2);
}

// The cache is keyed by the stroke's revision: a move (a new revision) is drawn where the
// stroke went, and the drawing of the old revision is forgotten.
TEST(StrokeDrawing, AMovedStrokeIsDrawnAnew) {
  Document doc;
  Stroke s;
  for (int i = 0; i < 80; ++i) {
    StrokeSample q;
    q.p = Vec2(5.0 * i, 40.0 * std::sin(i / 12.0));
    s.samples.push_back(q);
  }
  doc.addStroke(s);
  StrokeDrawings drawings;
  const std::uint64_t first = doc.strokes()[0].revision;
  const StrokeDrawing& d = drawings.of(doc.strokes()[0], 1.0, 24);
  ASSERT_FALSE(d.segments.empty());
  const QPointF start = d.segments.front().front();
  EXPECT_NEAR(start.x(), doc.strokes()[0].fit->curve.pieces.front().segment.start().x(), 1e-9);
  // the comb from the unit comb equals the comb computed at that gain
  const Comb direct = curvatureComb(doc.strokes()[0].fit->curve, 7.0, 24), scaled = d.comb(7.0);
  ASSERT_EQ(direct.tip.size(), scaled.tip.size());
  for (std::size_t i = 0; i < direct.tip.size(); ++i) EXPECT_LT((direct.tip[i] - scaled.tip[i]).norm(), 1e-9);
  ASSERT_EQ(direct.envelope.size(), scaled.envelope.size());
  for (std::size_t i = 0; i < direct.envelope.size(); ++i) EXPECT_LT((direct.envelope[i] - scaled.envelope[i]).norm(), 1e-9);

  doc.translateStrokes({0}, Vec2(100, 50));
  EXPECT_NE(doc.strokes()[0].revision, first);
  drawings.prune(doc);
  EXPECT_EQ(drawings.size(), 0u) << "the old revision's drawing is forgotten";
  const StrokeDrawing& moved = drawings.of(doc.strokes()[0], 1.0, 24);
  EXPECT_NEAR(moved.segments.front().front().x(), start.x() + 100, 1e-9);
  EXPECT_NEAR(moved.segments.front().front().y(), start.y() + 50, 1e-9);
}

// Ink from pen pressure (issue 17, part 8): a straight stroke along x whose pressure rises
// from 0 to 1 is as wide at each point as its pressure says, the lightest touch still shows,
// pressure in device units reads against the stroke's largest, a dropped report takes its
// neighbours' mean, and the ink drawn is as wide as that.
TEST(PressureInk, TheWidthFollowsThePressure) {
  std::vector<StrokeSample> line;
  for (int i = 0; i <= 200; ++i) {
    StrokeSample q;
    q.p = Vec2(i, 0.0);
    q.pressure = i / 200.0;
    line.push_back(q);
  }
  ASSERT_TRUE(hasPressure(line));
  const std::vector<double> widths = inkWidths(line, 4.0);
  EXPECT_NEAR(widths[150], 3.0, 1e-12);
  EXPECT_NEAR(widths[200], 4.0, 1e-12);
  EXPECT_NEAR(widths[0], 4.0 * kInkLeastShare, 1e-12) << "a touch without pressure still leaves ink";

  // the ink drawn 4x magnified (widths of whole pixels), black on white: across the column
  // at x = 150 (pressure 0.75) 12 pixels of ink, at x = 50 (pressure 0.25) 4
  QImage image(840, 40, QImage::Format_ARGB32);
  image.fill(Qt::white);
  {
    QPainter p(&image);
    p.setRenderHint(QPainter::Antialiasing);
    drawPressureInk(p, line, QTransform::fromTranslate(0, 20).scale(4.0, 4.0), Qt::black, 16.0);
  }
  auto inkAcross = [&](int x) {
    double ink = 0.0;
    for (int y = 0; y < image.height(); ++y) ink += (255.0 - qGray(image.pixel(x, y))) / 255.0;
    return ink;
  };
  EXPECT_NEAR(inkAcross(600), 12.0, 0.5);
  EXPECT_NEAR(inkAcross(602), 12.0, 0.5) << "between samples";
  EXPECT_NEAR(inkAcross(200), 4.0, 0.5);

  // device units (a tablet's 0..1024): read against the stroke's largest
  std::vector<StrokeSample> device = line;
  for (StrokeSample& q : device) q.pressure *= 1024.0;
  EXPECT_NEAR(inkWidths(device, 4.0)[150], 3.0, 1e-12);
  // a dropped report between 0.5 and 0.6: their mean
  std::vector<StrokeSample> dropped(3, line[0]);
  dropped[0].pressure = 0.5, dropped[1].pressure = NAN, dropped[2].pressure = 0.6;
  EXPECT_NEAR(inkWidths(dropped, 1.0)[1], 0.55, 1e-12);

  // a mouse stroke has no pressure
  for (StrokeSample& q : line) q.pressure = NAN;
  EXPECT_FALSE(hasPressure(line));
}

}  // namespace
}  // namespace la::gui
