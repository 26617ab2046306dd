// Fit to view (app/gui/import_placement.h), without a window: the points' bounding box
// fills kFitToViewFill of the view in its tighter direction, centred; one scale for x and
// y; a line and a single point are placed without dividing by zero.

#include <gtest/gtest.h>

#include "app/gui/import_placement.h"

namespace la::gui {
namespace {

Stroke strokeOf(std::initializer_list<Vec2> pts) {
  Stroke s;
  for (const Vec2& p : pts) {
    StrokeSample q;
    q.p = p;
    q.t = 7.0;
    s.samples.push_back(q);
  }
  return s;
}

TEST(ImportPlacement, AChordOfOneFillsEightyPercentOfAPixelView) {
  std::vector<Stroke> strokes{strokeOf({{0, 0}, {1, 0.1}, {0.5, -0.05}})};
  const WorldBox view{Vec2(0, 0), Vec2(800, 600)};
  const auto t = fitToView(strokes, view);
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->scale, 0.8 * 800.0, 1e-9);  // width-limited: 800/1 < 600/0.15
  applySimilarity(strokes, *t);
  const WorldBox box = *boundsOf(strokes);
  EXPECT_NEAR(box.size().x(), 640.0, 1e-9);
  EXPECT_NEAR(box.size().y(), 0.15 * 640.0, 1e-9) << "not one scale for x and y";
  EXPECT_LT((box.center() - view.center()).norm(), 1e-9);
  EXPECT_EQ(strokes[0].samples[0].t, 7.0) << "time is not a position";
}

TEST(ImportPlacement, TheTighterDirectionDecidesAndANegativeViewWorks) {
  // a tall shape in a wide view, the view in negative coordinates (panned)
  std::vector<Stroke> strokes{strokeOf({{10, 10}, {12, 50}}), strokeOf({{11, 30}})};
  const WorldBox view{Vec2(-500, -300), Vec2(-100, -100)};
  const auto t = fitToView(strokes, view);
  ASSERT_TRUE(t);
  EXPECT_NEAR(t->scale, 0.8 * 200.0 / 40.0, 1e-12);
  applySimilarity(strokes, *t);
  const WorldBox box = *boundsOf(strokes);
  EXPECT_NEAR(box.size().y(), 160.0, 1e-9);
  EXPECT_LT((box.center() - view.center()).norm(), 1e-9);
}

TEST(ImportPlacement, ALineAndAPointArePlacedWithoutDividingByZero) {
  const WorldBox view{Vec2(0, 0), Vec2(100, 100)};
  const auto line = fitToView({strokeOf({{0, 5}, {4, 5}})}, view);
  ASSERT_TRUE(line);
  EXPECT_NEAR(line->scale, 20.0, 1e-12);  // by its length alone
  const auto point = fitToView({strokeOf({{3, 4}})}, view);
  ASSERT_TRUE(point);
  EXPECT_EQ(point->scale, 1.0);
  EXPECT_LT((point->apply(Vec2(3, 4)) - Vec2(50, 50)).norm(), 1e-12) << "moved to the view's centre";
  EXPECT_FALSE(fitToView({}, view)) << "no points";
  EXPECT_FALSE(fitToView({strokeOf({{0, 0}, {1, 1}})}, WorldBox{})) << "an empty view";
}

}  // namespace
}  // namespace la::gui
