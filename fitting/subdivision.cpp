#include "fitting/subdivision.h"

#include <algorithm>

#include "fitting/stroke_noise.h"

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
// Filled steps: at least this share of the points are the resampler's.
constexpr double kFilledShare = 0.5;
// ... and on a pixel grid, the samples' grid is at least this many times coarser than
// the points' (a straight pixel line with a step skipped now and then: twice).
constexpr double kCoarserGrid = 3.0;

// |a + c - 2b| <= 2 r |c - a|: b is within r of its neighbours' distance from their
// midpoint (squared, so no square root).
bool nearMidpoint(const Vec2& a, const Vec2& b, const Vec2& c, double r) {
  const double span2 = (c - a).squaredNorm();
  return span2 > 0.0 && (a + c - 2.0 * b).squaredNorm() <= 4.0 * r * r * span2;
}

// Per point, whether it is at the midpoint of its neighbours (the ends are not): both
// detectors read these, computed once per clean-up round.
std::vector<bool> midpointsOf(const std::vector<Vec2>& p) {
  std::vector<bool> midpoint(p.size(), false);
  for (std::size_t i = 1; i + 1 < p.size(); ++i) midpoint[i] = nearMidpoint(p[i - 1], p[i], p[i + 1], kMidpointRounding);
  return midpoint;
}

std::vector<bool> subdivisionOf(const std::vector<bool>& midpoint) {
  const std::size_t n = midpoint.size();
  if (n < 2 * kSubdividedClass + 2) return {};
  // (two neighbours both off a midpoint are rare in a subdivided stroke: each of the
  // resampler's points off one, at most 1 in 20 of them, makes at most two such pairs; a
  // drawn stroke, whose points are seldom midpoints, is told after a few)
  const double most_pairs = 2.0 * (1.0 - kSubdividedShare) * static_cast<double>(n) + 2.0;
  std::size_t pairs = 0;  // (of neighbours neither at a midpoint)
  for (std::size_t i = 2; i + 1 < n; ++i)
    if (!midpoint[i] && !midpoint[i - 1] && static_cast<double>(++pairs) > most_pairs) return {};
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

std::vector<bool> filledStepsOf(const std::vector<Vec2>& p, const std::vector<bool>& midpoint) {
  const std::size_t n = p.size();
  if (n < 2 * kSubdividedClass + 2) return {};
  const double least = kFilledShare * static_cast<double>(n - 2);
  if (static_cast<double>(std::count(midpoint.begin(), midpoint.end(), true)) < least) return {};  // (a drawn stroke)
  std::vector<bool> sample(n);
  for (std::size_t i = 0; i < n; ++i) sample[i] = !midpoint[i];
  auto keepRun = [&](std::size_t first, std::size_t end) {
    std::fill(sample.begin() + static_cast<std::ptrdiff_t>(first), sample.begin() + static_cast<std::ptrdiff_t>(end), true);
  };
  // The runs of points at midpoints, [first, end). Each lies on the chord between the
  // samples around it, to the same rounding: a gently curved outline's points are each
  // nearly a midpoint, but a run of them bends away from its chord as the square of its
  // length, and stays. A run across a sample that barely turns the stroke (its
  // neighbours are midpoints too) is two straight runs either side of its point furthest
  // from the chord, which is a sample.
  auto farthest = [&](std::size_t first, std::size_t end) {  // (from the chord p[first - 1] p[end]; and which)
    const Vec2 a = p[first - 1], along = (p[end] - a).normalized();
    std::pair<double, std::size_t> out{0.0, first};
    for (std::size_t k = first; k < end; ++k) out = std::max(out, {std::abs(cross(along, p[k] - a)), k});
    return out;
  };
  auto straight = [&](std::size_t first, std::size_t end) {
    return first == end || farthest(first, end).first <= kMidpointRounding * (p[end] - p[first - 1]).norm();
  };
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  for (std::size_t first = 1, end; first + 1 < n; first = std::max(end, first + 1)) {
    for (end = first; !sample[end];) ++end;
    if (end == first) continue;
    if (straight(first, end)) {
      runs.emplace_back(first, end);
      continue;
    }
    const std::size_t turn = farthest(first, end).second;
    if (straight(first, turn) && straight(turn + 1, end)) {
      sample[turn] = true;
      if (first < turn) runs.emplace_back(first, turn);
      if (turn + 1 < end) runs.emplace_back(turn + 1, end);
      continue;
    }
    keepRun(first, end);
  }
  // On a pixel grid, a pointer walking along a row or column puts its samples at
  // midpoints too. A stroke whose points all lie on one grid is as drawn, unless the
  // other samples lie on a grid several times coarser (a pixel stroke filled at a
  // fraction of a pixel); a run wholly on the other samples' grid is drawn.
  std::vector<Vec2> kept;
  for (std::size_t i = 0; i < n; ++i)
    if (sample[i]) kept.push_back(p[i]);
  const std::optional<PixelGrid> grid = pixelGridOf(kept);
  if (const std::optional<PixelGrid> all = pixelGridOf(p))
    if (!grid || (grid->step.array() < kCoarserGrid * all->step.array()).any()) return {};
  std::size_t filled = 0;
  for (const auto& [first, end] : runs) {
    bool drawn = grid.has_value();
    for (std::size_t k = first; k < end && drawn; ++k) drawn = grid->holds(p[k]);
    if (drawn) keepRun(first, end);
    else filled += end - first;
  }
  if (static_cast<double>(filled) < least || n - filled < kSubdividedClass) return {};
  return sample;
}

}  // namespace

std::vector<bool> subdivisionSamples(const std::vector<Vec2>& p) { return subdivisionOf(midpointsOf(p)); }

std::vector<bool> filledStepSamples(const std::vector<Vec2>& p) { return filledStepsOf(p, midpointsOf(p)); }

std::vector<bool> resamplerSamples(const std::vector<Vec2>& p) {
  const std::vector<bool> midpoint = midpointsOf(p);
  std::vector<bool> subdivided = subdivisionOf(midpoint);
  bool exact = !subdivided.empty();  // (every point it leaves out at a midpoint)
  for (std::size_t i = 1; exact && i + 1 < p.size(); ++i) exact = subdivided[i] || midpoint[i];
  if (exact) return subdivided;
  if (std::vector<bool> filled = filledStepsOf(p, midpoint); !filled.empty()) return filled;
  return subdivided;
}

}  // namespace la
