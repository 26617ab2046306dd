// core/geometry.h: ceilWithin, the float-to-int conversion every panel and piece count
// goes through (a NaN or 1e12 converted to int is undefined; the fuzzers found one), and
// the least-squares line of points placed at known distances from a known line.

#include "core/geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace la {
namespace {

TEST(CeilWithin, RoundsUpInsideAndClampsOutsideAndNaN) {
  EXPECT_EQ(ceilWithin(2.1, 1, 10), 3);
  EXPECT_EQ(ceilWithin(3.0, 1, 10), 3);
  EXPECT_EQ(ceilWithin(-5.0, 1, 10), 1);
  EXPECT_EQ(ceilWithin(0.5, 1, 10), 1);
  EXPECT_EQ(ceilWithin(9.5, 1, 10), 10);
  EXPECT_EQ(ceilWithin(1e12, 1, 10), 10);
  EXPECT_EQ(ceilWithin(std::numeric_limits<double>::infinity(), 1, 10), 10);
  EXPECT_EQ(ceilWithin(-std::numeric_limits<double>::infinity(), 1, 10), 1);
  EXPECT_EQ(ceilWithin(std::nan(""), 1, 10), 1);
  EXPECT_EQ(ceilWithin(1e300, 0, std::numeric_limits<int>::max()), std::numeric_limits<int>::max());
}

// Points alternately 0.3 either side of the line through (2, 1) along 30 degrees, at
// even steps along it: the line is theirs (its centroid and direction), 0.3 the largest
// distance, whatever the order of the points or the direction's sign.
TEST(LeastSquaresLine, FindsTheLineOfPointsAtKnownDistances) {
  const Vec2 through(2.0, 1.0), along = unitVector(0.5236), across(-along.y(), along.x());
  std::vector<Vec2> points;
  for (int k = -10; k <= 10; ++k) points.push_back(through + k * along + (k % 2 == 0 ? 0.3 : -0.3) * across);
  points.push_back(through - 0.3 * across);  // (11 above, 11 below: the centroid is on the line)
  const FittedLine line = leastSquaresLine(points);
  EXPECT_NEAR(std::abs(cross(line.direction, along)), 0.0, 1e-12);
  EXPECT_NEAR(line.direction.norm(), 1.0, 1e-12);
  EXPECT_NEAR(cross(line.point - through, along), 0.0, 1e-12);
  EXPECT_NEAR(line.deviation, 0.3, 1e-12);
  EXPECT_NEAR(lineDeviation(points), 0.3, 1e-12);
  EXPECT_EQ(lineDeviation({through}), 0.0);
}

}  // namespace
}  // namespace la
