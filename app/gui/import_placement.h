#pragma once
// Where imported points go (issue 17, part 6). A point file's coordinates are its own: an
// airfoil's chord is 1, a scan's are millimetres, a tablet's pixels. Imported into a
// sketch drawn in pixels, an airfoil at its own coordinates is a speck. So the user
// chooses: keep the coordinates as written, in the document's units (the view is then
// fitted to the whole sketch), or fit the points to the view: one uniform scale and a
// translation (a similarity, so shapes, alphas and the fit's structure are kept: the
// pipeline is invariant under scaling and rigid motions) that make their bounding box
// fill kFitToViewFill of the current view, centred in it. The transform is applied to the
// raw samples before they become strokes; time, pressure and tilt are kept.

#include <optional>
#include <vector>

#include "fitting/stroke.h"

namespace la::gui {

enum class ImportPlacement {
  kAsk,             // a small dialog on import (File > Import placement)
  kFitToView,       // scaled and moved to fill the current view
  kOwnCoordinates,  // as written, in the document's units; the view is fitted after
};

/// The share of the view's shorter fitting side the imported points' bounding box
/// fills: 80%, as Canvas::fitView leaves a margin (85%) so the ends are not at the edge.
constexpr double kFitToViewFill = 0.8;

/// p -> scale * p + offset.
struct Similarity {
  double scale = 1.0;
  Vec2 offset = Vec2::Zero();
  Vec2 apply(const Vec2& p) const { return scale * p + offset; }
};

/// An axis-aligned box in world coordinates (lo: the smaller corner).
struct WorldBox {
  Vec2 lo = Vec2::Zero(), hi = Vec2::Zero();
  Vec2 center() const { return 0.5 * (lo + hi); }
  Vec2 size() const { return hi - lo; }
};

/// The bounding box of every sample (nullopt: no samples).
std::optional<WorldBox> boundsOf(const std::vector<Stroke>& strokes);

/// The similarity that fits `strokes` into `view` (kFitToViewFill of it, centred). A
/// box flat in one direction (a line) is scaled by the other; a single point is only
/// moved (scale 1). nullopt: no samples, or an empty view.
std::optional<Similarity> fitToView(const std::vector<Stroke>& strokes, const WorldBox& view);

/// Applies `t` to every sample's position.
void applySimilarity(std::vector<Stroke>& strokes, const Similarity& t);

}  // namespace la::gui
