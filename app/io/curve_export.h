#pragma once
// Writers for the export formats every front end shares (lafit and the GUI):
// SVG (cubic Beziers, optional input points and curvature comb), DXF (one SPLINE
// entity per curve), and CSV samples (x, y, s, theta, kappa). All return text; the
// caller writes it with writeFileAtomically.
//
// The writers work on chains of arc-length curves (core/arc_length_curve.h): the
// curvesTo* functions take LA curves (core/curve.h), the alpCurvesTo* functions ALP
// curves (core/alp_curve.h, one chain per curve), and the exportCurvesTo* functions
// any mix of both as ExportCurve chains. For LA curves the output is the same as
// before the generalization, byte for byte.

#include <string>
#include <vector>

#include "core/alp_curve.h"
#include "core/arc_length_curve.h"
#include "core/curve.h"
#include "core/geometry.h"

namespace la {

/// One piece of an export chain: a curve that must outlive the call, and whether it
/// starts at a deliberate G0 corner (for CSV: its first sample is then kept).
struct ExportPiece {
  const ArcLengthCurve* curve = nullptr;
  bool corner = false;
};

/// A chain of pieces, each starting where the previous one ends: an LA curve's
/// segments, or a single ALP curve. Drawn as one SVG path / one DXF SPLINE.
struct ExportCurve {
  std::vector<ExportPiece> pieces;
  bool closed = false;
};

/// Samples along a whole curve (all its segments), uniform in arc length per segment.
struct CurveSampling {
  int per_segment = 64;
};

struct SvgOptions {
  double bezier_tolerance = 1e-4;  // relative to the drawing's bounding-box diagonal
  /// An absolute tolerance instead (drawing units; used where > 0): the GUI asks for a
  /// tenth of the fit tolerance. The file states the tolerance it was written with.
  double bezier_tolerance_absolute = 0.0;
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

/// DXF $INSUNITS codes (AutoCAD's drawing-units table) for the units the GUI offers.
enum class DxfUnits { kUnitless = 0, kInches = 1, kMillimeters = 4 };

struct DxfOptions {
  double relative_tolerance = 1e-4;  // of the Bezier approximation, relative to the diagonal
  double absolute_tolerance = 0.0;   // drawing units; used instead where > 0
  DxfUnits units = DxfUnits::kUnitless;
  std::string units_comment;         // a 999 comment after the header (e.g. why px is unitless)
};

/// DXF (AutoCAD R2000 ASCII) with one degree-3 SPLINE per curve on layer CURVES, its
/// control points those of the Bezier approximation within tolerance, the points as
/// POINT entities on layer POINTS (both layers declared in the LAYER table), and the
/// units in the header ($INSUNITS).
std::string curvesToDxf(const std::vector<Curve>& curves, double relative_tolerance = 1e-4);

/// CSV with header `x,y,s,theta,kappa`, a blank line between curves (so the file is
/// itself a point file).
std::string curvesToCsv(const std::vector<Curve>& curves, const CurveSampling& sampling = {});

// ALP curves (for lafit alp and the GUI's ALP construction). Same formats and
// options as the LA writers above; the Bezier pieces stay within bezier_tolerance *
// diagonal of the curve (inflections and curvature extrema included), the comb is
// scaled by the largest |kappa| on the curve, and the CSV has per_segment samples per
// ALP curve.

std::string alpCurvesToSvg(const std::vector<AlpCurve>& curves, const std::vector<std::vector<Vec2>>& points = {},
                           const SvgOptions& options = {});
std::string alpCurvesToDxf(const std::vector<AlpCurve>& curves, double relative_tolerance = 1e-4);
std::string alpCurvesToCsv(const std::vector<AlpCurve>& curves, const CurveSampling& sampling = {});

// The general writers, for chains of any arc-length curves (e.g. LA and ALP curves
// in one drawing: build LaSegmentView adapters for the LA segments).

/// The LA curves as export chains; `views` owns the adapters the chains point to, so it
/// must outlive them.
std::vector<ExportCurve> exportChains(const std::vector<Curve>& curves, std::vector<LaSegmentView>& views);
/// ALP curves as export chains, one each; they point into `curves`.
std::vector<ExportCurve> exportChains(const std::vector<AlpCurve>& curves);

double exportDrawingDiagonal(const std::vector<ExportCurve>& curves, const std::vector<std::vector<Vec2>>& points);
std::string exportCurvesToSvg(const std::vector<ExportCurve>& curves, const std::vector<std::vector<Vec2>>& points,
                              const SvgOptions& options = {});
std::string exportCurvesToDxf(const std::vector<ExportCurve>& curves, double relative_tolerance = 1e-4);
std::string exportCurvesToDxf(const std::vector<ExportCurve>& curves, const std::vector<std::vector<Vec2>>& points,
                              const DxfOptions& options);
std::string exportCurvesToCsv(const std::vector<ExportCurve>& curves, const CurveSampling& sampling = {});

}  // namespace la
