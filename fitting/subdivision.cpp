#include "fitting/subdivision.h"

namespace la {
namespace {

// A point within this fraction of its neighbours' distance from their midpoint lies on
// their chord, evenly: a resampler put it there (files printed to 4 decimals leave
// midpoints 3e-5 off; a drawn point lands there by chance far less often than the
// share below allows).
constexpr double kMidpointRounding = 1e-3;
// A class of the points by index (mod k) is the resampler's where at least this share of
// it is at midpoints; the drawn strokes have at most 75% in one class of two.
constexpr double kSubdividedShare = 0.95;
// Each class holds at least this many points (fewer tell nothing).
constexpr std::size_t kSubdividedClass = 8;

}  // namespace

std::vector<bool> subdivisionSamples(const std::vector<Vec2>& p) {
  const std::size_t n = p.size();
  if (n < 2 * kSubdividedClass + 2) return {};
  std::vector<bool> midpoint(n, false);
  constexpr double kOff = 4.0 * kMidpointRounding * kMidpointRounding;  // (|a + c - 2b| <= 2 rounding |c - a|, squared)
  // (two neighbours both off a midpoint are rare in a subdivided stroke: each of the
  // resampler's points off one, at most 1 in 20 of them, makes at most two such pairs; a
  // drawn stroke, whose points are seldom midpoints, is told after a few)
  const double most_pairs = 2.0 * (1.0 - kSubdividedShare) * static_cast<double>(n) + 2.0;
  std::size_t pairs = 0;  // (of neighbours neither at a midpoint)
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double span2 = (p[i + 1] - p[i - 1]).squaredNorm();
    midpoint[i] = span2 > 0.0 && (p[i - 1] + p[i + 1] - 2.0 * p[i]).squaredNorm() <= kOff * span2;
    if (i > 1 && !midpoint[i] && !midpoint[i - 1] && static_cast<double>(++pairs) > most_pairs) return {};
  }
  for (std::size_t k = 2; k <= 3; ++k) {
    std::vector<std::size_t> count(k, 0), at_midpoints(k, 0);
    for (std::size_t i = 1; i + 1 < n; ++i) ++count[i % k], at_midpoints[i % k] += midpoint[i];
    std::size_t samples_class = 0, drawn_classes = 0;
    for (std::size_t r = 0; r < k; ++r) {
      if (count[r] < kSubdividedClass) return {};
      if (static_cast<double>(at_midpoints[r]) < kSubdividedShare * static_cast<double>(count[r]))
        samples_class = r, ++drawn_classes;
    }
    if (drawn_classes != 1) continue;
    std::vector<bool> sample(n);
    for (std::size_t i = 0; i < n; ++i) sample[i] = i == 0 || i + 1 == n || i % k == samples_class;
    return sample;
  }
  return {};
}

}  // namespace la
