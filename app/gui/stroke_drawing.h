#pragma once
// What the canvas draws of a stroke, computed once per stroke revision (DocumentStroke::
// revision) in world coordinates, so a repaint, a zoom or a pan only maps points through
// the view: the curve's polyline per segment, the comb at unit gain (a comb is linear in
// its gain: tip = base - gain kappa n), the marks and the largest curvature. Sampling the
// LA segments and finding the marks is what made a repaint of 50 faired strokes take
// ~60 ms (tests/benchmarks/gui_paint_benchmark.cpp).
//
// Level of detail: raw points are drawn at most ~2 per screen pixel along the stroke
// (decimated), as round points in one call, so a 200,000-point stroke costs what the
// pixels it covers cost.
//
// Ink from pen pressure: a drawn stroke can be shown as tablet drawing apps show it, its
// width following the pen's pressure sample by sample (a view option, Layers::pressure_ink).

#include <QColor>
#include <QPainter>
#include <QPointF>
#include <QPolygonF>
#include <QTransform>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "app/gui/comb.h"
#include "app/gui/document.h"
#include "app/gui/markers.h"

namespace la::gui {

/// Raw points closer than this (widget pixels) to the last one drawn are skipped: at most
/// ~2 per pixel of the stroke's length on screen, where the dots (3.6 px wide) overlap anyway.
inline constexpr double kRawPointStepPixels = 0.5;

/// The points of `points` mapped through `view` and thinned to one per `step` pixels along
/// the way (each kept point at least `step` from the one kept before; the last always kept).
QPolygonF decimatedPoints(const std::vector<StrokeSample>& points, const QTransform& view,
                          double step = kRawPointStepPixels);

/// Indices of the points `decimatedPoints` keeps, in order.
std::vector<std::size_t> decimatedIndices(const std::vector<StrokeSample>& points, const QTransform& view,
                                          double step = kRawPointStepPixels);

/// Ink at full pressure is this wide (pixels); the lightest touch keeps kInkLeastShare of it,
/// so a stroke never vanishes where the pen barely touched.
inline constexpr double kInkWidthPixels = 4.0;
inline constexpr double kInkLeastShare = 0.15;

/// Whether the samples carry pen pressure (some sample has a finite pressure above 0):
/// a mouse stroke or an imported file without pressure has none.
bool hasPressure(const std::vector<StrokeSample>& points);

/// The ink's width (pixels) at each sample: `width` times its pressure, the pressure read
/// against the stroke's largest where that exceeds 1 (device units rather than 0..1), at
/// least kInkLeastShare of `width`; a sample without pressure gets its neighbours' mean share.
std::vector<double> inkWidths(const std::vector<StrokeSample>& points, double width = kInkWidthPixels);

/// Ink widths are drawn in steps of this many pixels: one round-capped pen per step.
inline constexpr double kInkWidthStep = 0.25;

/// Ink follows the samples kept one per this many pixels (its widths are at most 4).
inline constexpr double kInkStepPixels = 1.5;

/// The stroke mapped through `view` as ink of opaque `color` whose width follows the pen
/// pressure (inkWidths): the samples kept one per kInkStepPixels (decimatedIndices), each
/// run of steps of one width (their ends' mean, in kInkWidthStep) one round-joined
/// polyline. (One filled outline of discs and quads cost 60 ms a repaint of 50 strokes.)
void drawPressureInk(QPainter& p, const std::vector<StrokeSample>& points, const QTransform& view, const QColor& color,
                     double width = kInkWidthPixels);

/// The same ink as dots, ~2 per pixel (decimatedPoints), each as wide as the pen's
/// pressure makes the ink there, blitted per width step: a drawn stroke's raw samples,
/// repainted with every stroke (as polylines, 50 pen strokes took 23 ms a repaint).
void drawPressureDots(QPainter& p, const std::vector<StrokeSample>& points, const QTransform& view,
                      const QColor& color, double width = kInkWidthPixels);

/// Round dots of `diameter` pixels centred on `at` (widget pixels), drawn in one call.
void drawDots(QPainter& p, const QPolygonF& at, const QColor& color, double diameter);

/// One stroke's drawing in world coordinates.
struct StrokeDrawing {
  std::uint64_t revision = 0;
  std::vector<QPolygonF> segments;  // the fitted curve, one polyline per segment (world)
  double sampled_scale = 0.0;       // the view scale (pixels per world unit) they were sampled for
  Comb unit_comb;                   // the comb at gain 1, and its envelope at gain 0 (the bases)
  std::vector<Vec2> envelope_base;
  int comb_teeth = -1;
  std::vector<CurveMarker> markers;
  double max_abs_kappa = 0.0;
  /// The comb at `gain`, from the unit comb (no LA evaluation).
  Comb comb(double gain) const;
};

class StrokeDrawings {
 public:
  /// The drawing of a fitted stroke at view scale `scale` with `teeth` comb teeth: made
  /// or brought up to date (the curve is resampled where the view zoomed in more than 2x
  /// or out more than 8x since it was sampled; the comb where the teeth changed).
  const StrokeDrawing& of(const DocumentStroke& stroke, double scale, int teeth);
  /// Forgets the drawings of revisions no longer in `document`.
  void prune(const Document& document);
  std::size_t size() const { return m_drawings.size(); }

 private:
  std::unordered_map<std::uint64_t, StrokeDrawing> m_drawings;  // by revision
};

}  // namespace la::gui
