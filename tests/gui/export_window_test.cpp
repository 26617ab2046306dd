// Export that fits the user's units (issue 17, part 6): the SVG holds the curves only by
// default, as cubic Beziers within the tolerance it states (a tenth of the fit's) of the
// LA curve; points and comb are options in groups of their own; the DXF puts curves and
// points on the layers CURVES and POINTS and states the sketch's units ($INSUNITS); the
// units are saved with the sketch.

#include <gtest/gtest.h>

#include <QComboBox>
#include <QFile>
#include <cmath>
#include <fstream>
#include <sstream>

#include "core/bezier_approximation.h"
#include "tests/gui/window_test_support.h"
#include "tests/svg_bezier_paths.h"

namespace la::gui {
namespace {

std::string readText(const QString& path) {
  QFile f(path);
  EXPECT_TRUE(f.open(QIODevice::ReadOnly)) << path.toStdString();
  return f.readAll().toStdString();
}

TEST_F(MainWindowTest, SvgOfAnAirfoilIsWithinTheStatedToleranceOfTheLaCurve) {
  ASSERT_TRUE(window->importPoints(QString(LAFAIR_SHARED_DATA_DIR) + "/curves/airfoils/naca-m6.dat"));
  const FitResult& fit = lastFit();
  const QString path = dir.filePath("airfoil.svg");
  ASSERT_TRUE(window->exportFile(path));
  const std::string svg = readText(path);
  EXPECT_EQ(svg.find("id=\"points\""), std::string::npos) << "curves only by default";
  EXPECT_EQ(svg.find("id=\"comb\""), std::string::npos);
  EXPECT_NE(svg.find("inkscape:label=\"curves\""), std::string::npos);

  // the tolerance the file states: a tenth of the fit's
  const double tolerance = test::statedBezierTolerance(svg);
  ASSERT_FALSE(std::isnan(tolerance));
  EXPECT_NEAR(tolerance, 0.1 * fit.tolerance, 1e-6 * fit.tolerance);

  const std::vector<std::vector<CubicBezier>> paths = test::curvePathsOf(svg);
  ASSERT_EQ(paths.size(), 1u);
  const std::vector<CubicBezier>& path_cubics = paths[0];
  ASSERT_FALSE(path_cubics.empty());
  double worst = 0.0;
  for (const CurvePiece& piece : fit.curve.pieces)
    for (const Vec2& q : piece.segment.sample(400).point)
      worst = std::max(worst, test::distanceToBeziers(path_cubics, q));
  // (the file's numbers have 10 significant digits: their rounding is far below this)
  EXPECT_LE(worst, tolerance) << "every point of the LA curve within the stated tolerance of the Bezier path";

  window->setExportExtras(true, true);
  ASSERT_TRUE(window->exportFile(path));
  const std::string full = readText(path);
  EXPECT_NE(full.find("<g id=\"points\" inkscape:label=\"points\""), std::string::npos);
  EXPECT_NE(full.find("<g id=\"comb\" inkscape:label=\"comb\""), std::string::npos);
}

TEST_F(MainWindowTest, DxfHasCurveAndPointLayersAndTheUnits) {
  drawWithMouse(window->canvas(), wave());
  window->finishBackgroundFits();
  auto* units = window->findChild<QComboBox*>("units");
  ASSERT_NE(units, nullptr);
  EXPECT_EQ(units->currentText(), "px") << "px by default";
  const QString path = dir.filePath("curve.dxf");
  window->setExportExtras(true, false);
  ASSERT_TRUE(window->exportFile(path));
  std::string dxf = readText(path);
  // code/value pairs
  auto pairs = [](const std::string& text) {
    std::vector<std::pair<std::string, std::string>> out;
    std::istringstream in(text);
    std::string code, value;
    while (std::getline(in, code) && std::getline(in, value)) out.emplace_back(code, value);
    return out;
  };
  auto after = [&](const std::string& text, const std::string& key) {  // the value after a 9 key
    const auto p = pairs(text);
    for (std::size_t i = 0; i + 1 < p.size(); ++i)
      if (p[i].first == "9" && p[i].second == key) return p[i + 1];
    return std::pair<std::string, std::string>{};
  };
  EXPECT_EQ(after(dxf, "$INSUNITS"), (std::pair<std::string, std::string>{"70", "0"})) << "px: unitless";
  EXPECT_NE(dxf.find("999\nlafair: drawing units are px"), std::string::npos) << "with a comment saying so";
  int layers = 0, curves_on = 0, points_on = 0;
  const auto p = pairs(dxf);
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    if (p[i] == std::pair<std::string, std::string>{"0", "LAYER"} && p[i + 1].first == "2")
      layers += p[i + 1].second == "CURVES" || p[i + 1].second == "POINTS";
    if (p[i].first == "0" && (p[i].second == "SPLINE" || p[i].second == "POINT")) {
      ASSERT_EQ(p[i + 1].first, "8");
      (p[i].second == "SPLINE" ? curves_on : points_on) += p[i + 1].second == (p[i].second == "SPLINE" ? "CURVES" : "POINTS");
    }
  }
  EXPECT_EQ(layers, 2) << "CURVES and POINTS declared in the LAYER table";
  EXPECT_EQ(curves_on, 1);
  EXPECT_GT(points_on, 50);

  units->setCurrentText("mm");
  ASSERT_TRUE(window->exportFile(path));
  EXPECT_EQ(after(readText(path), "$INSUNITS"), (std::pair<std::string, std::string>{"70", "4"}));
  units->setCurrentText("in");
  ASSERT_TRUE(window->exportFile(path));
  EXPECT_EQ(after(readText(path), "$INSUNITS"), (std::pair<std::string, std::string>{"70", "1"}));

  // the units are saved with the sketch
  units->setCurrentText("mm");
  const QString sketch = dir.filePath("s.lafair.json");
  ASSERT_TRUE(window->saveFile(sketch));
  units->setCurrentText("px");
  ASSERT_TRUE(window->openFile(sketch));
  EXPECT_EQ(window->document().units(), "mm");
  EXPECT_EQ(units->currentText(), "mm");
}

}  // namespace
}  // namespace la::gui
