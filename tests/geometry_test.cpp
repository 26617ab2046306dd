// core/geometry.h: ceilWithin, the float-to-int conversion every panel and piece count
// goes through (a NaN or 1e12 converted to int is undefined; the fuzzers found one).

#include "core/geometry.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

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

}  // namespace
}  // namespace la
