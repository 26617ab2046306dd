#pragma once
// End conditions of a Hermite interpolation problem (DESIGN.md section 4): a point,
// the tangent direction there and, for G2, the curvature. Shared by the triple-LA G2
// Hermite curve (seed 002) and the ALP curves with explicit Bezier curvature
// functions (seeds 000, 004), so both read the same user input.

#include "core/geometry.h"

namespace la {

struct HermiteEnd {
  Vec2 point = Vec2::Zero();
  double theta = 0.0;  // tangent direction (radians), the direction of travel
  double kappa = 0.0;  // signed curvature, left turn positive; unused by G1 problems
};

}  // namespace la
