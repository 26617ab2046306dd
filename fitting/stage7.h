#pragma once
// Stage 7 (ours): each part's G2 chain fitted to its points by least squares, its
// segments chosen by the model selection (fitting/model_selection.h), then all parts
// fitted again as one chain whose corners are free. Also how the parts' chains are
// measured (deviation, stray) and joined at their corners.

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "fitting/fit_context.h"
#include "fitting/model_selection.h"
#include "fitting/parts.h"

namespace la {

/// A curve further than this many tolerances from the stroke's polyline (a loop between
/// two points) is reported as straying: between sparse points a fair curve may leave the
/// chords by about a tolerance.
inline constexpr double kStrayWarning = 2.0;

/// A part's stage 7 fit from the spline's chain that ends further than this many
/// tolerances from its points has set off astray: it is tried again from a finer start.
inline constexpr double kAstrayFit = 2.0;

/// How stage 7 starts from a part's spline (where stage 6 has no G2 chain): one segment
/// shot per span, and where that fit ends astray (kAstrayFit) but not for the cap on
/// extrema's merges, again from the spans halved where a shot sets off astray, the closer
/// kept; or only the first (the caller has other
/// starts: a first fit far astray is left unedited), or only the second (nothing changes
/// where halving changes no span).
enum class SplineStart { kShotThenHalved, kShot, kHalved };

/// Stage 7 on one part, from stage 6's chain or, where that has no G2 chain, from the
/// spline (fitting/spline_chain.h). The result replaces the part's chain where it is
/// within the tolerance, closer to the points than that chain, or that chain has gaps,
/// more extrema than the cap (FitOptions::segmentation.max_extrema) or an alpha outside
/// [FitOptions::min_alpha, max_alpha]; fit.max_dev is then
/// known. Without `choose_segments`, only the cap's merges edit the chain (the paper's
/// pipeline over the cap).
void polishPart(PartFit& fit, const Part& part, const FitContext& context, bool choose_segments = true,
                SplineStart spline_start = SplineStart::kShotThenHalved);

/// Stage 7 on an open part whose chain is past the room of its fit as a whole (whose
/// linear algebra grows with the cube of the segments): in pieces of a dozen of the
/// spline's spans, one after another, each started from the spline (fitting/
/// spline_chain.h) where the piece before it ends, its segments chosen and fitted to its
/// points and to the next piece's first few with its start held there (position,
/// tangent, curvature: G2 by construction), and kept up to its own points' last foot.
/// The work grows with the pieces. Where `fit` has a kink and a piece's start or fit is
/// refused, or the chain strays from the points, pieces of other sizes are tried too, the
/// closest chain kept. True where it made a chain (fit updated as polishPart updates it);
/// false, and the chain as it was, where no size did.
bool polishInPieces(PartFit& fit, const Part& part, const FitContext& context);

/// Stage 7's selection options: the tolerance less a margin, the alpha range and the
/// bound on curvature, the points and iterations per fit, the noise, the cap and the
/// budget; closure, fixed ends and corners are the caller's (a part's: the overload below).
SelectionOptions stage7Selection(const FitContext& context);
/// The same for one part's chain: closed as the part is, its ends held at its corners.
SelectionOptions stage7Selection(const FitContext& context, const Part& part);

/// A curvature above this many times 1 / tolerance bends tighter than the tolerance (the
/// bound itself, to rounding, does not).
inline constexpr double kTighterThanTolerance = 1.0 + 1e-6;

/// The largest |kappa| of a chain.
double largestKappa(const std::vector<LaSegment>& segments);

/// Some segment of the chain bends tighter than the tolerance.
bool bendsTighterThan(const std::vector<LaSegment>& segments, double tolerance);

/// The chain keeps the bound on the radius where the context promises it (any chain
/// does where the context fits without it).
bool keepsTheBound(const std::vector<LaSegment>& segments, const FitContext& context);

/// A part's chain (corner-free, closed or not) has more curvature extrema than the cap.
bool overCap(const std::vector<LaSegment>& segments, bool closed, const FitContext& context);

/// A part's fit from a chain of stage 7's alone (no spline: stages 2-6 did not run or do
/// not stand behind it), its points' feet on it kept, its reports from its segments;
/// `what` says how it was made.
PartFit partFitOf(const ChainFitResult& chain, const std::string& what);

/// One LA segment fitted to an open part's points between its ends (held where they are
/// corners), from the arc through its ends and its middle point, or where that fit fails,
/// that arc; `what` says why. Nullopt for a closed part, one of fewer than 3 points or
/// whose ends meet, or where that arc passes further than `screen` from some point.
std::optional<PartFit> oneArcPart(const Part& part, const FitContext& context, const std::string& what,
                                  double screen = INFINITY);

/// The circular arc between an open part's first and last points (held) that passes
/// closest to its points (the smallest largest distance), no tighter than the bound on the
/// radius where the context promises it; `what` says why. An arc's curvature is constant:
/// no trend, so no reversal of it at its ends. Nullopt for a closed part, one of fewer than
/// 3 points or whose ends meet, and where that arc does not keep every point within `limit`.
std::optional<PartFit> closestArcPart(const Part& part, const FitContext& context, const std::string& what,
                                      double limit = INFINITY);

/// The cap on extrema wins: a part's chain still over it (a part whose capped chain could
/// not be snapped onto its corner keeps the chain of stages 2-6) becomes one LA segment
/// fitted to its points between its ends (an LA segment has no curvature extremum), from
/// the arc through its ends and its middle point, or where that fit fails, that arc; a
/// closed part under a cap below 4, the circle closest to its points. A part from a
/// corner back to it is left: no LA segment closes without an inflection (its osculating
/// circles are nested, Tait-Kneser).
void keepTheCap(PartFit& fit, const Part& part, const FitContext& context);

/// Stage 7 across corners: all parts' chains fitted as one chain whose corners are
/// free. True if it changed the chains; false where a part has no G2 chain or the fit
/// brought nothing.
bool fitAcrossCorners(std::vector<PartFit>& fits, const std::vector<Part>& parts, bool closed,
                      const FitContext& context);

/// Makes the parts' chains meet at their corners (each pair of ends moved to their
/// midpoint, each chain by a similarity).
void joinAtCorners(std::vector<PartFit>& fits, const std::vector<Part>& parts, const G2Options& g2);

/// How far a part's chain goes from the part's polyline, measured where the chain is
/// longer than the polyline (else 0); with `tip_allowance` (world units) always, and
/// counted where above it.
double strayOf(const std::vector<LaSegment>& segments, const Part& part, double diag,
               double tip_allowance = INFINITY);

/// strayOf `fit`'s chain, measured once (kept in fit.stray, NaN until then).
double strayOfFit(PartFit& fit, const Part& part, double diag);

/// The larger of `fit`'s deviation from the part's points and its stray, each measured
/// once (kept in fit.max_dev and fit.stray).
double worstOf(PartFit& fit, const Part& part, double diag);

}  // namespace la
