#pragma once
// A whole open stroke drawn as one LA curve (a clothoid, a logarithmic spiral or a circle
// involute of any number of turns, an arc) fitted as that one segment, before stages
// 2-6: no edit of a chain of several finds such a segment where it turns further than a
// merge may (SelectionOptions::max_turning), and a smoothing spline of a spiral of
// several turns is slow and may loop.

#include <optional>

#include "fitting/fit_context.h"
#include "fitting/parts.h"

namespace la {

/// The part as one LA segment (its max_dev says whether within the tolerance: where none
/// is, the closest, which the caller may keep if the chains of several do worse), or
/// nullopt: a part that is closed, between two corners, turns no further than a merge
/// may (beside one corner: less than a whole turn), turns back (an LA segment inflects
/// at an end only), or whose curvature rises and falls, is not tried. Beside a corner,
/// the segment is pinned there. No spline: stages 2-6 are not needed. The fit
/// starts from the segments, one per alpha of a grid, whose turning along the points
/// follows the chords' best (least squares by Ceres), the closest first. fitStroke also
/// tries a whole open stroke this way before the parts its corners cut it into.
std::optional<PartFit> oneSegmentPart(const Part& part, const FitContext& context);

/// Where the part's one LA segment (oneSegmentPart, its feet in `one.feet`) misses the
/// tolerance: stage 7's model selection from it (pinned at the part's corner, if any),
/// which splits it at its worst points (an LA segment's pieces are LA segments of its
/// alpha: each split starts where the one segment was) and fits again, until the chain
/// keeps the tolerance or the edits run out. A spiral that is no LA curve (an Archimedean
/// one from its tight centre) is a few segments so, where stages 2-6 from its spline set
/// off astray. Nullopt where the selection has no chain.
std::optional<PartFit> splitOneSegment(const PartFit& one, const Part& part, const FitContext& context);

}  // namespace la
