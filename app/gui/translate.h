#pragma once
// Moving strokes (the Select tool's drag): a translation does not change a fit (the
// pipeline is invariant under rigid motions, tested in fitting/), so a moved stroke is not
// refitted: its raw samples, fitted segments, smoothed splines, cleaned points and the
// user's joint and apex positions are translated, its alphas kept.

#include "app/gui/document.h"

namespace la::gui {

/// The fit moved by `d`: every position in it (segments' starts, splines' control points,
/// the cleaned points); curvatures, parameters and quality figures unchanged.
FitResult translated(const FitResult& fit, const Vec2& d);

/// Moves a document stroke by `d`, as above, with the user's edits that are positions.
void translateStroke(DocumentStroke& stroke, const Vec2& d);

}  // namespace la::gui
