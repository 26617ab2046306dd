#pragma once
// The whole fitting pipeline of DESIGN.md section 3 (seed 003 section 3): a raw stroke
// in, a fair curve of LA segments with continuous curvature out, with every
// intermediate stage, the quality figures of DESIGN.md section 6 and per-stage timings.
//
// What it looks for (DESIGN.md sections 3 and 6), in this order:
//   - G2 at every joint but the corners;
//   - the user's limits: at most segmentation.max_extrema curvature extrema per smooth
//     part (a hard cap: where the tolerance cannot be kept under it, the cap wins and the
//     figures report the deviation), every alpha in [min_alpha, max_alpha] (lines and
//     circular arcs, the family's alpha = infinity, apart);
//   - every point within the tolerance, no bend tighter than it (tighter is a corner);
//   - the fewest curvature extrema, then the fewest segments, then the least squares.
// The last line is approached, not proven: stage 7's edits merge at every weak
// curvature extremum the tolerance lets go, one at a time (a search, not an optimum),
// but try no merge at a strong one, and keep a merge at a monotone joint or a collapse
// only where the points do not object (an F-test); so a curve may keep an extremum or a
// segment the tolerance alone would let go.
//
//   1 cleanStroke       duplicates, hooks, corners, closed, straight?   fitting/stroke.h
//     noiseOf           the tolerance's floor                           fitting/stroke_noise.h
//     splitAtCorners    corner-to-corner parts                          fitting/parts.h
//   2-6 fitPart         per part, the paper's stages:                   fitting/paper_stages.h
//       2 smoothWithBSpline  cubic B-spline within the tolerance        fitting/spline_smoothing.h
//       3 segmentSpline      split at inflections, curvature extrema    fitting/segmentation.h
//       4 alpha per piece    LCG regression                             core/lcg.h
//       5 LA segment per piece from its control triangle                fitting/chain.h
//       6 makeG2             rotate joint tangents to G2                fitting/g2_joints.h
//   7 polishPart        the part's G2 chain fitted to its points by     fitting/stage7.h,
//                       least squares, its segments chosen (ours; on    fitting/model_selection.h,
//                       by default); fitAcrossCorners: all parts as     fitting/chain_fit.h,
//                       one chain with free corners                     fitting/spline_chain.h
//   8 measureQuality    the figures                                     fitting/quality.h
// The steps shared by one fit (tolerance, noise, timings, time budget): fitting/
// fit_context.h. The user's edits of a fitted curve: fitting/user_edits.h.
//
// Special shapes. Points all on one line are a line (or lines where the stroke turns
// back). A whole open stroke without corners that turns further than a merge may is
// first tried as one LA segment (a clothoid, a spiral of several turns), stages 2-6
// skipped where it fits (fitting/one_segment.h).
//
// A stroke with deliberate corners is fitted piecewise between them; the segment after
// a corner carries corner = true. With stage 7, a corner beside a part that misses the
// tolerance goes where the two parts fitted as one smooth part keep it (a tight bend
// the clean-up took for a corner); then all parts are fitted again as one chain whose
// corners are free, so each corner lands where its two sides meet rather than on the
// sample nearest it (fitChain's corners). A step more than ten median steps long (a font
// outline's unsampled straight edge, samples the digitizer lost) is filled with points
// along it for stages 2-7; the quality figures are measured on the stroke's own points.
//
// With stage 7 on, stages 2-6 only prepare its start: the spline is fitted to the
// tolerance (not tighter), alphas start at the fit's prior, and no piece is cut where its
// segment strays (the fit closes such misses, and cuts leave slivers). Where stage 6 finds
// no G2 chain the fit starts from the spline itself; where its result still misses the
// tolerance or G2, stages 2-6 as the paper has them (cutting what strays) give a second
// start, for pixel-quantized strokes stages 2-6 on the points with their stairs
// smoothed a third, and one LA segment between the part's ends a last; the best result
// stays (G2 first, then the cap, then the bound on the radius, then the deviation, the
// stray counted). Stage 7 bends no tighter than the tolerance; where the curve misses it
// (a tight bend the clean-up did not take for a corner), the fit runs again with corners
// at the bends on the bound, or where none is, at the point farthest from the curve.
// Where that misses, or still bends tighter, it runs without the bound (under a cap on
// extrema, not where it misses by more than half the tolerance again: that is the cap's
// cost), then with corners at the bends that came out tighter, and, where one still does
// (a capped stroke's part), with those corners and the bound everywhere: the bound
// wins. A rerun keeps the first fit's tolerance, and is not kept where it loops
// away from the stroke.

#include <optional>
#include <string>
#include <vector>

#include "core/bspline.h"
#include "core/curve.h"
#include "fitting/chain.h"
#include "fitting/g2_joints.h"
#include "fitting/quality.h"
#include "fitting/segmentation.h"
#include "fitting/spline_smoothing.h"
#include "fitting/stroke.h"

namespace la {

struct FitOptions {
  double tolerance_fraction = 0.005;  // max distance, relative to the stroke's bounding-box diagonal
  double tolerance = 0.0;             // absolute max distance; overrides the fraction when > 0
  CleanupOptions cleanup;
  SegmentationOptions segmentation;   // significance, max_extrema, max_piece_turning
  G2Method g2 = G2Method::kNewton;
  /// Relative curvature gap stage 6 leaves at a joint (DESIGN.md section 6). Newton
  /// converges quadratically, so 1e-10 costs a step or two more than the 1e-6 it was:
  /// at 1e-6 a paper's chain that stage 7 kept was G2 to 1e-7 only.
  double g2_threshold = 1e-10;
  /// Alpha from the LCG is kept inside this range (a noisy LCG can be steep).
  double min_alpha = -3.0, max_alpha = 3.0;
  /// Stage 7 (fitting/model_selection.h): fit each part's G2 chain to its points by
  /// least squares and choose its segments. Off: the paper's pipeline alone (stages 1-6;
  /// the app's live preview, which must keep up with the pen). Ignored with g2 = kOff
  /// (stage 7's chains are G2 by construction).
  bool polish = true;
  /// Whether stage 7 runs: polish, and a G2 method to start it from.
  bool polishes() const { return polish && g2 != G2Method::kOff; }
  /// Stage 7's segments get the standard error of their alpha (PieceReport::
  /// alpha_standard_error: how well the points determine it), at a Jacobian and a
  /// decomposition more per chain fit a selection keeps: 3.5% of the shared data's fit
  /// time, for a figure neither lafit nor the app shows. Off: infinite.
  bool alpha_standard_errors = false;
  /// Wall time the fit may take (ms; 0: no limit). When it runs out, stage 7 stops
  /// editing and trying other starts, and the fit keeps the best G2 chain found so far,
  /// with its true figures (FitResult::out_of_time says so). Stages 1-6 and the cap on
  /// extrema are kept even then. The app's background fit uses it, so that a hard stroke
  /// arrives in bounded time.
  double time_budget_ms = 0.0;
  /// Bounded work. A stroke of more raw samples is refused (StrokeError) before any work:
  /// the clean-up and stages 1-6 grow as n log n with the samples. Stage 7 fits a part's
  /// whole chain at once, at a cost growing with the cube of its segments: it runs on the
  /// parts in turn while their stage-6 chains add up to at most max_polish_segments; the
  /// others keep the stage-6 chain, with a warning (a scribble of a thousand turns); where
  /// that chain has gaps (pieces no LA segment fits), stage 7 fits it without choosing its
  /// segments, while those add up to at most max_polish_segments again; where an open
  /// part's chain still has gaps or bends tighter than the tolerance, stage 7 fits it in
  /// pieces of a dozen spline spans (polishInPieces, fitting/stage7.h). The shared data's
  /// strokes have at most 27. lafit --max-points, --max-polish-segments.
  std::size_t max_points = 1'000'000;
  std::size_t max_polish_segments = 40;
};

/// One piece of the segmentation and how its LA segment was made.
struct PieceReport {
  double t0 = 0.0, t1 = 0.0;  // spline parameters of its ends
  SplitKind start_kind = SplitKind::kEnd, end_kind = SplitKind::kEnd;
  PieceKind kind = PieceKind::kThreePoint;
  double lcg_alpha = 0.0;     // slope of the LCG regression on the smoothed piece (NaN if none)
  double lcg_r2 = 0.0;
  double alpha = 0.0;         // alpha used (moved into the feasible range if needed)
  bool alpha_moved = false;
  /// Standard error of the fitted alpha (stage 7, fitting/chain_fit.h): how well the
  /// points determine it; infinite when stage 7 did not run or was not asked for it
  /// (FitOptions::alpha_standard_errors).
  double alpha_standard_error = INFINITY;
  int part = 0;               // which corner-to-corner part it belongs to
  int spline = -1;            // index into FitResult::splines of that part's spline (-1: a straight part)
};

/// Wall time per stage. Stage 5 (one LA segment per piece) has no line of its own:
/// its solves happen inside alpha_ms (feasibility of each piece's alpha) and g2_ms
/// (the first build of the chain and every rebuild while the joints move).
/// The stages are those of the fit returned; total_ms also counts a first fit it
/// replaced (the reruns with corners at tight bends or without the bound, fitStroke).
struct StageTimings {
  double cleanup_ms = 0, smoothing_ms = 0, segmentation_ms = 0, alpha_ms = 0, g2_ms = 0, polish_ms = 0,
         quality_ms = 0, total_ms = 0;
};

struct FitResult {
  Curve curve;
  QualityFigures quality;
  StageTimings timings;
  CleanStroke cleaned;
  double tolerance = 0.0;  // absolute, as used
  /// The tolerance the options asked for (absolute). Where the points are noisier (their
  /// noise floor, fitting/stroke_noise.h), `tolerance` is raised to it: information, not
  /// a warning (it is so on nearly every pen stroke).
  double requested_tolerance = 0.0;
  std::vector<CubicBSpline> splines;  // stage 2, one per part (straight parts have none)
  std::vector<std::vector<SplitPoint>> splits;  // stage 3, per part
  std::vector<PieceReport> pieces;    // stages 4-5, one per segment of `curve`
  SolveReport smoothing;              // worst part's smoothing report
  SolveReport g2;                     // worst part's G2 report
  bool out_of_time = false;  // the time budget ran out: stage 7 stopped early
  bool over_polish_limit = false;  // parts kept their stage-6 chain (FitOptions::max_polish_segments)
  /// The largest distance from every finite raw sample to the curve, those the clean-up
  /// left out included (cleaned.left_out; quality.max_dev is over the kept points).
  double max_dev_all_points = 0.0;
  /// How far the curve goes from the stroke's polyline where it is longer than it (a
  /// loop where no point is); warned above twice the tolerance.
  double stray = 0.0;
  std::vector<std::string> warnings;
};

/// Throws StrokeError for a stroke that cannot be fitted (too few distinct points,
/// all collinear). Solver trouble (tolerance not reached, G2 not converged) is
/// reported in the result and its warnings, with the curve as far as it got.
FitResult fitStroke(const Stroke& stroke, const FitOptions& options = {});

}  // namespace la
