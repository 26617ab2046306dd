#pragma once
// Writers for the export formats every front end shares (lafit and the GUI):
// SVG (cubic Beziers, optional input points and curvature comb), DXF (one SPLINE
// entity per curve), and CSV samples (x, y, s, theta, kappa). All return text; the
// caller writes it with writeFileAtomically.

#include <string>
#include <vector>

#include "core/curve.h"
#include "core/geometry.h"

namespace la {

/// Samples along a whole curve (all its segments), uniform in arc length per segment.
struct CurveSampling {
  int per_segment = 64;
};

struct SvgOptions {
  double bezier_tolerance = 1e-4;  // relative to the drawing's bounding-box diagonal
  bool show_points = true;         // the input points, as small dots
  bool show_comb = false;          // curvature comb (normals scaled by kappa)
  double comb_scale = 0.1;         // longest comb tooth, relative to the diagonal
  int comb_teeth_per_segment = 24;
  double stroke_width = 0.0;       // 0: 0.2% of the diagonal
  bool y_up = false;               // the data's y axis points up (profiles, fonts): flip for SVG's y-down
};

/// Bounding-box diagonal of curves and points together (1 if empty or a single point).
double drawingDiagonal(const std::vector<Curve>& curves, const std::vector<std::vector<Vec2>>& points);

std::string curvesToSvg(const std::vector<Curve>& curves, const std::vector<std::vector<Vec2>>& points,
                        const SvgOptions& options = {});

/// DXF (AutoCAD R2000 ASCII) with one degree-3 SPLINE per curve, its control points
/// those of the Bezier approximation within tolerance (relative to the diagonal).
std::string curvesToDxf(const std::vector<Curve>& curves, double relative_tolerance = 1e-4);

/// CSV with header `x,y,s,theta,kappa`, a blank line between curves (so the file is
/// itself a point file).
std::string curvesToCsv(const std::vector<Curve>& curves, const CurveSampling& sampling = {});

}  // namespace la
