// Cubic B-splines (core/bspline.h): the span lookup that walks from a hint gives the
// binary search's span for every parameter and every hint, open and periodic, with a
// repeated interior knot (a zero-width span) too.

#include "core/bspline.h"

#include <gtest/gtest.h>

#include <random>

namespace la {
namespace {

void expectSameSpans(const CubicBSpline& s) {
  std::mt19937 rng(3);
  const double lo = s.tMin(), hi = s.tMax(), width = hi - lo;
  std::uniform_real_distribution<double> any(lo - 0.5 * width, hi + 0.5 * width);  // wrapped / clamped too
  std::vector<double> ts = s.knots();  // every knot exactly
  for (int k = 0; k < 500; ++k) ts.push_back(any(rng));
  const int spans = static_cast<int>(s.control().size());
  for (double t : ts)
    for (int hint = -2; hint <= spans + 2; ++hint)
      ASSERT_EQ(s.spanFrom(s.wrap(t), hint), s.span(t)) << "t " << t << " hint " << hint;
}

TEST(CubicBSpline, SpanFromAHintIsTheSpan) {
  const std::vector<Vec2> control = {{0, 0}, {1, 2}, {2, -1}, {3, 1}, {4, 0}, {5, 2}, {6, 1}};
  expectSameSpans(CubicBSpline::clamped({0.0, 0.2, 0.5, 0.7, 1.0}, control));
  expectSameSpans(CubicBSpline({0, 0, 0, 0, 0.3, 0.3, 0.6, 1, 1, 1, 1}, control));  // a double interior knot
  expectSameSpans(CubicBSpline::periodic({0.0, 0.1, 0.35, 0.5, 0.8, 1.0}, {{0, 0}, {1, 1}, {2, 0}, {1, -1}, {0.5, -0.5}}));
}

}  // namespace
}  // namespace la
