#pragma once
// The curvature comb (Rhino's and Alias' curvature graph): teeth normal to the curve, as
// long as the curvature times a gain, pointing away from the centre of curvature, and the
// envelope through their tips. The teeth are spaced evenly along the whole curve's arc
// length, across its joints, so a long segment gets as many teeth per unit length as a
// short one; the envelope also passes through every joint (both sides of a corner), so a
// jump in curvature shows where it is.
//
// The gain comes from the comb scale: the longest tooth is `scale` times the view's
// shorter side, either per curve (each curve's own largest curvature) or shared (the
// largest over every curve shown), so teeth of different curves compare.

#include <vector>

#include "core/curve.h"

namespace la::gui {

struct Comb {
  std::vector<double> s;                 // arc length of each tooth from the curve's start
  std::vector<Vec2> base, tip;           // each tooth, world coordinates
  std::vector<Vec2> envelope;            // the tips in order along the curve, joints included
  double gain = 0.0;                     // tooth length per unit curvature (world length squared)
};

/// `teeth` >= 2 teeth along `curve`: at s = k L / (teeth - 1) for an open curve (both ends
/// included), s = k L / teeth for a closed one.
Comb curvatureComb(const Curve& curve, double gain, int teeth);

/// The same for a curve known only by dense samples (a construction): arc length,
/// points, left normals and curvature, interpolated linearly between samples.
Comb curvatureComb(const std::vector<double>& s, const std::vector<Vec2>& points, const std::vector<Vec2>& normals,
                   const std::vector<double>& kappa, double gain, int teeth);

/// The largest |curvature| of a curve (at a segment's end: LA segments are monotone).
double maxAbsCurvature(const Curve& curve);

}  // namespace la::gui
