#pragma once
// Stage 7 (ours; seed 003 stops at stage 6): the whole G2 chain of LA segments fitted to
// the stroke's points by least squares, in intrinsic form, where G2 holds by
// construction.
//
// Why. Stages 4-6 build each segment from a control triangle whose end tangents come
// from the smoothing spline, with alpha from the spline's LCG; both are poor witnesses
// of the stroke (a cubic spline's curvature derivative jumps at every knot), so alphas
// come out far from the truth and segments stray from the points. Fitting the chain
// itself fixes both, and moves the joints to where the stroke wants them.
//
// Unknowns (a normalized frame: the chain's start at the origin, unit bounding-box
// diagonal), each with bounds:
//   the start point (unless fixed: a part that starts at a corner), the start tangent
//   theta0, the signed curvature kappa_j at every joint (its sign kept and |kappa_j| at
//   least 1e-3 of the largest; an inflection joint stays at 0; a closed chain's last
//   joint is its first), each segment's log |total turning| (which, with its law, sets
//   its length) and its alpha in [min_alpha, max_alpha] (at most kInflectionAlphaCap
//   for a segment with a zero-curvature end, DESIGN.md section 2).
// Segment i is LaSegment(alpha_i, L_i, end of segment i-1, its end tangent, kappa_i,
// kappa_i+1), so positions, tangents and curvature are continuous at every joint.
//
// Residuals. Each point X_k has a foot (segment, fraction of its length); its residual
// is the tangent distance n . (P(foot) - X_k) (Wang, Pottmann & Liu 2006, "Fitting
// B-spline curves to point clouds by curvature-based squared distance minimization";
// it lets the points slide along the curve). The feet are projected again (Newton on
// the closest-point condition, across joints) at every evaluation, so the cost is the
// sum of squared distances. An open chain's free ends are pinned to the first / last
// point. A weak prior on each alpha (ChainFitOptions::noise) keeps alphas the points do
// not determine from wandering. A fixed end (a part that ends at a corner), a closed
// chain's closure (end point and tangent back at the start) and a window's ends (the
// pose and curvature where the segments beside it start and end, ChainFitOptions::window)
// are equality constraints, met on the exact chain (LaSegment positions) to rounding
// where a few Newton steps get there; snapToJoints (below) closes what is left.
//
// Corners (ChainFitOptions::corners, for a stroke drawn with sharp corners, fitted as one
// chain so that the fit places the corners): at a corner joint the tangent turns by an
// unknown angle and each side has its own curvature, so only the position is
// continuous. Each point's foot stays on the segments of its own part (the points
// between two corners' points, on the segments between the two corners), so a point
// beside a hairpin corner is not claimed by the other side; a corner's own point may lie
// on either side (or is held at the corner: hold_corner_points). A point whose foot ends
// at a corner has no normal foot there: its residual is the distance itself.
//
// Evaluation. theta(u) and kappa(u) of a segment have closed forms (written with
// expm1/log1p so that alpha = 0, alpha = 1 and the circle are ordinary points),
// differentiated by Ceres' Jet (forward mode) on a coarser panel grid. Positions come
// from panels (Hermite rules from the ends' tangent, curvature and its slopes: the
// model's from the ends alone, the Jacobian's with the middle too; 3-point Gauss-Legendre
// at zero ends and sharp panels) and, between panel ends, quintic Hermite interpolation;
// the Jacobian of a point is that of its own segment's local curve plus the rigid motion
// the earlier segments give its start.
// Levenberg-Marquardt with the constraints in each step's KKT system and the bounds by
// active sets (an unknown held at its bound, never clipped), geodesic acceleration and a
// second-order correction, on bins of the points (the unknowns are few: about 3 per
// segment; ChainFitOptions::max_points). The iteration is the fit's own, not
// ceres::Solver's nor core/least_squares.h's: a closed chain's closure and a fixed end
// are equality constraints in every step (Ceres has bounds but no equality
// constraints), and geodesic acceleration needs the model's second derivative along
// the step.

#include <optional>
#include <vector>

#include "core/la_segment.h"
#include "core/solve_report.h"
#include "fitting/budget.h"
#include "fitting/chain.h"
#include "fitting/g2_joints.h"

namespace la {

/// A segment with a zero-curvature end keeps alpha at most this: steeper laws
/// (alpha -> 0-) put all the turning at the far end, a corner in all but name.
inline constexpr double kInflectionAlphaCap = -0.2;

/// Where a point's nearest point on a chain is: segment and fraction of its length.
struct ChainFoot {
  std::size_t segment = 0;
  double u = 0.0;
};

/// A corner of a chain: the start of segment `joint`, drawn at point `point`.
struct ChainCorner {
  std::size_t joint = 0, point = 0;
};

struct ChainFitOptions {
  double min_alpha = -3.0, max_alpha = 3.0;
  bool closed = false;      // the chain is closed: its end returns to its start, G2
  bool fix_start = false;   // the chain starts at the first point (a corner) and stays there
  bool fix_end = false;     // the chain ends at the last point (a corner) and stays there
  /// With fix_start: the start's tangent angle and signed curvature (world units) are
  /// held at these too: the chain goes on G2 from one fitted before it, whose end is the
  /// first point. Not with closed or window.
  struct HeldStart {
    double theta = 0.0, kappa = 0.0;
  };
  std::optional<HeldStart> held_start;
  /// Segments held as circular arcs: both ends share one curvature unknown (started at
  /// the geometric mean of the two) and the alpha, meaningless on an arc, is held. Each
  /// must bend (neither end curvature zero, both of one sign), and with `window` or
  /// `held_start` neither end may be one the chain holds.
  std::vector<std::size_t> arcs;
  /// The chain is a window of a longer G2 chain (its segments near an edit), to stay G2
  /// with the segments on either side: it keeps its start's position, tangent and
  /// curvature as `initial` has them, and ends at `window_end` (position, tangent) with
  /// the curvature `initial` ends with; only its inside moves. The points are those near
  /// it, none of them pinned to its ends. (Not with closed, fix_start, fix_end or corners.)
  bool window = false;
  struct Pose {
    Vec2 point = Vec2::Zero();
    double theta = 0.0;
  } window_end;
  /// Corners, in order along the chain: the chain is continuous there in position only,
  /// the tangent turns by a free angle and each side has its own curvature; where the
  /// corner lands is fitted. The points between two corners are those of the segments
  /// between them. A closed chain with corners has its first at its seam (joint and point 0).
  std::vector<ChainCorner> corners;
  /// Each corner's own point is held at the corner (its residual: the distance between
  /// them), instead of lying on either side like any point. A drawn corner is rounded and
  /// its point is the tip of the rounding: held there, the corner stays near the stroke.
  bool hold_corner_points = false;
  int max_iterations = 30;  // Levenberg-Marquardt steps
  /// No step starts once it is spent (fitting/budget.h): the best chain so far is kept,
  /// as at the iteration limit. Each step charges it the Jacobian's size.
  Budget budget;
  /// Stop when a step lowers the cost by less than this fraction, or by less than a
  /// tenth of one point's noise variance, or by less than least_decrease.
  double relative_decrease = 1e-7;
  /// The smallest decrease of the sum of squared distances worth a step (world units
  /// squared; 0: none). Stage 7 sets it from the tolerance: noise-free points have no
  /// noise floor to stop at, and a relative stop loose enough to end their crawl also
  /// ends fits still far from the points.
  double least_decrease = 0.0;
  /// A fit whose points (the binned ones it iterates on) are still further than `beyond`
  /// (world units) from the chain after `after` steps stops there (0 steps: never): a
  /// trial that has to end within a distance a few steps cannot reach is dropped anyway.
  struct Abandon {
    int after = 0;
    double beyond = INFINITY;
  } abandon;
  /// Iterate on at most this many points (0: all): an even subsample, the ends kept,
  /// each picked point standing in for its bin of neighbours by their centroid where the
  /// noise (below) is given and the chain is nearly straight across the bin, so the fit
  /// is the all-points fit. Distances are reported for every point.
  std::size_t max_points = 0;
  /// A broad prior on every alpha, N(alpha_prior, alpha_spread^2), weighed against the
  /// points by their noise (standard deviation, world units; 0: no prior). Where the
  /// points determine alpha it changes nothing; where they hardly do (a short segment
  /// whose curvature barely changes), alpha no longer wanders to a bound while the
  /// solver crawls along a flat valley: the maximum a posteriori estimate.
  double noise = 0.0;
  /// Segments shorter than this (world units; 0: none) are penalized, weighed by the
  /// noise above (chain_fit.cpp, kShortSegmentWeight): a bend tighter than the points
  /// can tell (a sharp vertex of noisy points under the corner angle) spreads over at
  /// least this length unless the points insist. The model selection sets its tolerance.
  double min_length = 0.0;
  /// The largest |curvature| at any joint (world units; 0: none), so at any point (an LA
  /// segment's curvature is monotone): no bend tighter than 1 / max_curvature. A start
  /// with a tighter joint is eased to it before the fit.
  double max_curvature = 0.0;
  double alpha_prior = 0.5, alpha_spread = 2.0;
  /// Compute ChainFitResult::alpha_standard_error (a Jacobian and a decomposition more
  /// per fit). The model selection's trial fits, most of which it drops, go without; it
  /// measures a kept edit's with alphaStandardErrorsOf.
  bool standard_errors = true;
  /// Per point, the weight of its residual (empty: all 1). Raising the weights of the
  /// points furthest off moves the least-squares fit towards the smallest largest
  /// distance (Lawson's iteration); the distances reported stay unweighted.
  std::vector<double> weights;
};

struct ChainFitResult {
  std::vector<LaSegment> segments;  // the fitted chain (the initial one if not improved)
  std::vector<ChainFoot> feet;      // of every point on `segments`
  std::vector<double> distance;     // of every point to `segments` (at its foot)
  double ssr = 0.0;                 // sum of squared distances
  double max_distance = 0.0;
  int unknowns = 0;                 // number of fitted parameters
  /// Per segment, the standard error of its alpha (least-squares covariance at the fit):
  /// how well the points determine it. Empty if the fit did not improve the chain, or
  /// with ChainFitOptions::standard_errors off.
  std::vector<double> alpha_standard_error;
  bool improved = false;            // closer to the points (ssr) than the initial chain
  SolveReport report;
};

/// Fits `initial` (an open or closed G2 chain of LA segments, every one with a finite
/// alpha, a circular arc with nonzero curvature or a straight line, whose neighbours
/// have zero curvature where they meet it; consecutive segments meeting in position,
/// tangent and curvature) to `points`, given in order along it (a closed
/// chain's points start anywhere). `feet`, if not empty, are the points' feet on
/// `initial` (one per point); otherwise they are found from scratch. A chain it cannot
/// take comes back unchanged with kBadInput. A fix_end or closed chain comes back closed
/// to rounding where a few Newton steps on its exact (LaSegment) geometry get there;
/// pass it through snapToJoints, which closes what is left.
ChainFitResult fitChain(const std::vector<LaSegment>& initial, const std::vector<Vec2>& points,
                        const std::vector<ChainFoot>& feet, const ChainFitOptions& options = {});

/// Per segment, the standard error of its alpha for `chain` and `points` as fitChain
/// reports it for a fit that ends at `chain` (with `options`; none taken as a step).
/// Empty where fitChain would refuse the chain.
std::vector<double> alphaStandardErrorsOf(const std::vector<LaSegment>& chain, const std::vector<Vec2>& points,
                                          const std::vector<ChainFoot>& feet, const ChainFitOptions& options = {});

/// Feet and distances of `points` on `segments` (in order along the chain), starting from
/// `feet` when given (one per point). For a chain that fitChain did not make.
void projectOnChain(const std::vector<LaSegment>& segments, bool closed, const std::vector<Vec2>& points,
                    std::vector<ChainFoot>& feet, std::vector<double>& distance);

/// The chain as joints, tangent angles and alphas (fitting/chain.h): a segment with a
/// zero-curvature end becomes an inflection piece. The last joint is `end` (a corner,
/// or the start again for a closed chain).
Chain chainOfSegments(const std::vector<LaSegment>& segments, bool closed, const Vec2& end);

/// The chain moved, turned and scaled so that its start lands on `start` and its end on
/// `end` (the similarity of those two points): G2 and the alphas stay exactly; a point
/// moves by at most the larger of the two ends' moves. Its start and end must differ,
/// as must `start` and `end`.
std::vector<LaSegment> movedOntoEnds(const std::vector<LaSegment>& segments, const Vec2& start, const Vec2& end);

/// Makes a nearly closed or nearly corner-ended chain exact. A closed chain of one segment
/// becomes the circle of its mean curvature. One that is, to 1e-10 of its
/// length (and in tangent, closed), comes back as it is. An open chain is scaled and
/// rotated about its start until its end is at `end`, if that moves no point of it by
/// more than `reach` (G2 and alphas kept exactly). Otherwise, and for a closed chain:
/// joints where the segments start (the last one at `end`), tangents and alphas kept,
/// then G2 by rotating the joint tangents (makeG2) as in stage 6, which fails where a
/// nearly straight segment has no control triangle. Empty if that fails.
std::vector<LaSegment> snapToJoints(const std::vector<LaSegment>& segments, bool closed, const Vec2& end,
                                    const G2Options& options, double reach = 0.0);

}  // namespace la
