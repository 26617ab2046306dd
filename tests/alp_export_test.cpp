// Tests of the export writers for ALP curves (app/io/curve_export.h) and of the Bezier
// approximation over the ArcLengthCurve interface (core/bezier_approximation.h):
// the Beziers stay within the tolerance of curves with inflections and extrema, CSV
// samples are the curve's, DXF has the right shape, and the generic writers give the
// LA writers' output for LA curves.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "app/io/curve_export.h"
#include "core/alp_curve.h"
#include "core/bezier_approximation.h"
#include "core/curve.h"

namespace la {
namespace {

// Two-sided distance between the curve and the Bezier chain, both densely sampled
// (independent of the approximation's own Newton-projection check).
double chainDistance(const AlpCurve& c, const std::vector<CubicBezier>& chain) {
  std::vector<Vec2> bez;
  for (const CubicBezier& b : chain)
    for (int k = 0; k <= 400; ++k) bez.push_back(b.point(k / 400.0));
  const CurveSamples smp = c.sample(4001);
  auto nearest = [](const Vec2& p, const std::vector<Vec2>& poly) {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i + 1 < poly.size(); ++i) d = std::min(d, distanceToSegment(p, poly[i], poly[i + 1]));
    return d;
  };
  double worst = 0.0;
  for (const Vec2& p : smp.point) worst = std::max(worst, nearest(p, bez));
  for (std::size_t i = 0; i < bez.size(); i += 7) worst = std::max(worst, nearest(bez[i], smp.point));
  return worst;
}

TEST(AlpExport, BeziersWithinToleranceThroughInflectionsAndExtrema) {
  const std::vector<AlpCurve> curves = {
      AlpCurve({2.0, -6.0, 5.0, -1.0}, {}, 3.0, Vec2(1, 2), 0.3),             // two inflections
      AlpCurve({0.0, 8.0, -2.0, 3.0, 0.5}, {1, 2, 0.5, 1, 3}, 2.0, Vec2(0, 0), -1.0),  // rational, loops
      AlpCurve({1.0, 1.0}, {}, 5.0, Vec2(0, 0), 0.0)};                        // circle of 5 rad
  for (const AlpCurve& c : curves) {
    for (double tol : {1e-3, 1e-5}) {
      const BezierApproximation a = approximateWithBeziers(c, tol);
      ASSERT_FALSE(a.pieces.empty());
      EXPECT_LE(a.max_error, tol);
      EXPECT_EQ(a.pieces.front().p0, c.start());
      EXPECT_LE((a.pieces.back().p3 - c.end()).norm(), 1e-12);
      // sampled polylines add their own chord error ~ (h kappa)^2 / 8 ~ 1e-7 here
      EXPECT_LE(chainDistance(c, a.pieces), tol + 2e-7) << "degree " << c.degree() << " tol " << tol;
    }
  }
}

TEST(AlpExport, CsvHoldsTheCurvesSamples) {
  const AlpCurve c({2.0, -6.0, 5.0, -1.0}, {}, 3.0, Vec2(1, 2), 0.3);
  const std::string csv = alpCurvesToCsv({c}, CurveSampling{101});
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "x,y,s,theta,kappa");
  int rows = 0;
  while (std::getline(in, line)) {
    double x, y, s, th, k;
    char comma;
    std::istringstream row(line);
    row >> x >> comma >> y >> comma >> s >> comma >> th >> comma >> k;
    ASSERT_TRUE(row) << line;
    EXPECT_LE((Vec2(x, y) - c.position(s, 1e-13)).norm(), 1e-8) << line;  // 10 significant digits
    EXPECT_NEAR(th, c.theta(s), 1e-8);
    EXPECT_NEAR(k, c.kappa(s), 1e-8 * (1 + std::abs(k)));
    ++rows;
  }
  EXPECT_EQ(rows, 101);
}

TEST(AlpExport, SvgAndDxfShapes) {
  const AlpCurve c({2.0, -6.0, 5.0, -1.0}, {}, 3.0, Vec2(1, 2), 0.3);
  SvgOptions options;
  options.show_comb = true;
  const std::string svg = alpCurvesToSvg({c}, {{c.start(), c.end()}}, options);
  EXPECT_NE(svg.find("<g id=\"curves\""), std::string::npos);
  EXPECT_NE(svg.find("<g id=\"comb\""), std::string::npos);
  EXPECT_NE(svg.find(" C"), std::string::npos);
  const std::string dxf = alpCurvesToDxf({c});
  EXPECT_NE(dxf.find("SPLINE"), std::string::npos);
  // control points: 3 per Bezier + 1, matching the approximation at the same tolerance
  const double diag = exportDrawingDiagonal({{{{&c, false}}, false}}, {});
  const std::size_t pieces = approximateWithBeziers(c, 1e-4 * diag).pieces.size();
  std::size_t count = 0;  // group code 10 (x of a control point), read as code/value pairs
  std::istringstream in(dxf);
  std::string code, value;
  while (std::getline(in, code) && std::getline(in, value)) count += code == "10";
  EXPECT_EQ(count, 3 * pieces + 1);
}

TEST(AlpExport, GenericWritersMatchTheLaWriters) {
  Curve curve;
  const LaSegment a(0.5, 2.0, Vec2(0, 0), 0.2, 0.3, 0.9);
  curve.pieces.push_back({a, false});
  curve.pieces.push_back({LaSegment(-1.0, 1.0, a.end(), a.theta(a.length()), 0.9, 0.1), false});
  std::vector<LaSegmentView> views;
  for (const CurvePiece& p : curve.pieces) views.emplace_back(p.segment);
  const ExportCurve chain{{{&views[0], false}, {&views[1], false}}, false};
  SvgOptions options;
  options.show_comb = true;
  EXPECT_EQ(exportCurvesToSvg({chain}, {}, options), curvesToSvg({curve}, {}, options));
  EXPECT_EQ(exportCurvesToCsv({chain}), curvesToCsv({curve}));
  EXPECT_EQ(exportCurvesToDxf({chain}), curvesToDxf({curve}));
}

}  // namespace
}  // namespace la
