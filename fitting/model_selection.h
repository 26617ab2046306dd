#pragma once
// Stage 7b (ours): how many segments the fitted chain needs. The segmentation of stage 3
// reads extrema and inflections off a smoothing spline, which noise can fool both ways:
// a spline wiggle near an inflection or a noisy end adds a piece the stroke does not
// have; a curvature extremum flattened by the smoothing goes missing. After the chain is
// fitted to the points (fitting/chain_fit.h), this stage edits it and fits again:
//
//  - split: while some point is further than the tolerance (also after a few rounds of
//    Lawson's reweighting towards the smallest largest distance), the segment holding
//    the worst one is cut at that point's foot (an LA segment's sub-pieces are LA
//    segments of the same alpha, so the cut itself changes nothing);
//  - collapse: a segment that turns by almost nothing (noise across an inflection, or a
//    sliver at a stroke's end) is removed, its neighbours meeting at one joint; so is a
//    stub, shorter than the tolerance (no point places it: it only kinks the chain),
//    and a spike of two stubs between inflections (0 -> kappa -> 0) goes as one;
//  - merge: two segments whose joint is a weak curvature extremum or none at all (the
//    curvature passes through it monotonically) become one;
//  - straighten: a nearly straight run of one or two segments between zero-curvature
//    joints or the chain's ends becomes one line (no LA segment has two zero ends, so
//    the fit could only approach a line there, often with a stub), if the refit is
//    within the tolerance; so does a bump (0 -> kappa -> 0, two segments) however far
//    it turns, where its points lie near a line and the chain keeps the tolerance, and a
//    side (the segments between two corners, or a corner and an open chain's end) whose
//    points lie near a line meeting its neighbours near the corners' points (a side
//    that curls into its corner has extrema a straight one has not);
//  - bend: a line the worst point is off is bent towards it (one arc between corners
//    or a chain's ends, else two segments), where another segment would be split;
//  - level: last, on a chain within the tolerance, a segment between a curvature peak
//    and a dip of its part, or between an extremum and its part's end (a side curling
//    into its corner), is held as a circular arc (ChainFitOptions::arcs), where the
//    refit stays within the tolerance and its curvature reverses less often.
//
// A chain with corners (ChainFitOptions::corners) keeps them: no merge across a corner;
// a short segment beside one (a hook) is a collapse candidate, the corner then taking its
// turning; a part keeps at least one segment; an edit renumbers the corners
// (SelectionResult::corners).
//
// Every fit here keeps segments from shrinking below the tolerance unless the points
// insist (ChainFitOptions::min_length): such a segment is a stub.
//
// A collapse or merge is kept when the refitted chain stays within the tolerance and
// the points do not object: the rise of the sum of squared distances, per unknown
// removed, is below `significance` times the residual variance (the F-test of nested
// least-squares models). So segments the points need stay, and the count follows the
// stroke, not the noise. A merge at a weak extremum, and a bump or a side straightened,
// are kept on the tolerance alone: the fewest extrema come before the least squares
// (fitting/pipeline.h); under the F-test, the shared data's curves kept 20 more extrema
// of 802 (extrema_dense), and their bumps 79 of 6,137 (--variants=8). A merge at a
// strong one is not tried: on the tolerance alone, a chain built with 4 extrema (one a
// curvature dip to a third of its neighbours') came back with 3.
//
// The cap on curvature extrema (SelectionOptions::max_extrema) is a hard limit, counted
// per smooth part (between corners) as the quality figures count them
// (QualityFigures::extrema_per_part). It is met before the splits, and a split (or a
// Lawson round) is kept only where its refit keeps it. While a part has more, the
// segments meeting at its weakest extrema (the smallest curvature change beside the
// joint) are merged, whatever the deviation costs: all those beyond the cap at once,
// fitted once, then one at a time; a closed part without corners that still has
// too many, or whose cap is under 4 (a simple closed curve other than a circle has at
// least 4: the four-vertex theorem), becomes the circle closest to its points.

#include <cmath>
#include <optional>
#include <vector>

#include "fitting/chain_fit.h"

namespace la {

/// A simplifying edit of a chain (selectChain): which, at which segment or joint, over how
/// many segments.
enum class EditKind { kCollapse, kMerge, kStraighten, kStraightenSide };
struct TrialEdit {
  EditKind kind;
  std::size_t index, count;
  bool operator==(const TrialEdit&) const = default;
};

struct SelectionOptions {
  double tolerance = 0.0;     // max distance from any point to the chain (world units, > 0)
  double significance = 4.0;  // F threshold (about the 1% level for a few unknowns and many points)
  int max_edits = 12;         // splits, collapses and merges together
  /// A split comes no closer to a segment's end than 15% of its length, or this (world
  /// units) where less: a segment of a spiral's several turns is split where it misses,
  /// near its tight centre.
  double split_margin = INFINITY;
  int patience = 4;           // a fit outside the tolerance may take this many times fit.max_iterations more (0: none)
  int reweighing_rounds = 8;  // Lawson rounds before a split (0: none)
  /// A segment turning less than this (radians) is a collapse candidate; a joint whose
  /// curvature changes by less than this fraction on either side, a merge candidate.
  double sliver_turning = 0.08;
  double weak_extremum = 0.5;
  /// A run of one or two segments between zero-curvature joints (or a chain's ends)
  /// turning less than this (radians) is a line candidate. (A line is a stronger claim
  /// than a sliver: at the sliver's 0.08, the shared data came out with 17 segments
  /// fewer of 1,299, and one more stroke missed the tolerance, by 2%.)
  double straight_turning = 0.04;
  /// Merged segments turn at most this (radians), so every control triangle stays well
  /// shaped (the app's editing works on them).
  double max_turning = 2.0;
  /// Slivers collapsed, splits (after Lawson's reweighting) and merges tried; false: only
  /// hooks beside corners and stubs are collapsed and nearly straight runs (where
  /// straighten_runs) and sides between corners straightened (for segments chosen already).
  bool refine = true;
  /// Nearly straight runs (of one or two segments) tried as lines. False where an earlier
  /// selection chose the segments and tried their runs already (see fitAcrossCorners);
  /// sides between corners are still tried.
  bool straighten_runs = true;
  /// Segments levelled into circular arcs where the curvature reverses less often (the
  /// last edit, see above): for the chain's final selection (stage 7 across corners).
  bool level_arcs = false;
  /// Curvature extrema allowed per smooth part (-1: no cap), counted and weighed as the
  /// quality figures count them, against this diagonal (the whole stroke's; 0: the points').
  int max_extrema = -1;
  double diagonal = 0.0;
  /// No edit starts once it is spent (the cap's merges excepted): the chain as it is then
  /// is the result.
  Budget budget;
  /// A first fit (its patience included) further than this from the points is the result,
  /// unedited: the caller has other starts to try.
  double hopeless_start = INFINITY;
  /// Trial edits of the chain handed in that another selection of it did not keep.
  std::vector<TrialEdit> not_kept;
  ChainFitOptions fit;
};

struct SelectionResult {
  ChainFitResult fit;  // of the chain finally chosen
  std::vector<ChainCorner> corners;  // of that chain (options.fit.corners, renumbered by the edits)
  int splits = 0, collapses = 0, merges = 0, straightenings = 0;
  int cap_merges = 0;     // merges the cap on extrema forced
  int arcs = 0;           // segments levelled into circular arcs
  bool over_cap = false;  // some part still has more extrema than the cap
  bool out_of_time = false;  // the budget stopped the edits
  std::vector<TrialEdit> not_kept;  // trial edits of the chain chosen that were not kept
};

/// The circle closest to the points (least squares on x^2 + y^2 + D x + E y + F = 0), as
/// one closed arc starting at the foot of the first point, turning the way the points go
/// round; nullopt if the points are on a line. (A closed part's curve under a cap on
/// extrema below 4.)
std::optional<LaSegment> closestCircle(const std::vector<Vec2>& points);

/// Fits `chain` to `points` (fitChain with options.fit; `feet` as there) and edits it as
/// above. The result is the last accepted chain's fit (the plain fit if no edit helped).
SelectionResult selectChain(const std::vector<LaSegment>& chain, const std::vector<Vec2>& points,
                            const std::vector<ChainFoot>& feet, const SelectionOptions& options);

}  // namespace la
