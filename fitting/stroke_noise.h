#pragma once
// The noise of a stroke's points, which sets the smallest tolerance a fit can keep:
// their jitter, estimated from fourth differences (which cancel the curve's own
// bending), also of every second and third sample where neighbours share it (a device's
// smoothing), and for points on a pixel grid the quantization (stroke_noise.cpp says how).

#include <optional>
#include <vector>

#include "core/geometry.h"

namespace la {

struct Noise {
  double sigma = 0.0;    // per coordinate, world units
  double floor = 0.0;    // the smallest tolerance the points allow
  bool on_grid = false;  // the points lie on a pixel grid
};

/// `corners`: indices of the points' deliberate corners (CleanStroke::corners). Where
/// the differences across them are what sets the estimate (a zigzag whose legs are a
/// few samples long: most differences span a vertex), they are left out, so the zigzag
/// is not taken for noise of its own size.
Noise noiseOf(const std::vector<Vec2>& points, const std::vector<std::size_t>& corners = {});

/// A pixel grid: the points origin + (i, j) * step, i and j integers.
struct PixelGrid {
  Vec2 origin, step;
  bool holds(const Vec2& point) const;  // (to a thousandth of a step: printed files round)
};

/// The grid the points lie on: along both axes every value an integer number of one step
/// from the smallest (pixels, possibly shifted and scaled, as Omniglot's canvas units
/// are), that step the smallest change between neighbours. Nullopt where they do not.
std::optional<PixelGrid> pixelGridOf(const std::vector<Vec2>& points);

/// The points with a binomial filter (1 4 6 4 1)/16 over five neighbours; an open
/// part's ends stay. On a pixel grid it turns a one-pixel stair into a slope.
std::vector<Vec2> withoutStairs(const std::vector<Vec2>& points, bool closed);

}  // namespace la
