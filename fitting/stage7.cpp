#include "fitting/stage7.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "fitting/model_selection.h"
#include "fitting/paper_stages.h"
#include "fitting/quality.h"
#include "fitting/spline_chain.h"

namespace la {
namespace {

// Stage 7's fit: points it iterates on (bins of the points, ChainFitOptions::max_points)
// and Levenberg-Marquardt steps per fit. Measured on the ground-truth chains
// (tests/pipeline_test.cpp) and the shared data: fewer points lose alpha accuracy on
// clean strokes (where nothing is binned); 8 more steps on the chosen chain bring its sum
// of squares to the optimum (alphas more than 0.3 off the truth: 27 of 78 instead of
// 32) but cost about 1 ms on a 1,000-point stroke, half the time budget. The fit across
// corners takes as many as one part's fit, not as many per part: a glyph's outline of
// 5 parts fitted all its 668 points, 1.4 ms per step (on the shared data: 2% fewer
// instructions, 5 segments more of 10,165 over data_benchmark --variants=8).
constexpr std::size_t kFitPoints = 250;
constexpr int kFitIterations = 8;
// Where the parts keep the tolerance already, the fit across corners only moves their
// corners off the samples, from chains close to their optimum: it takes this many steps.
// (With 8, the steps after the corners have moved reshape the sides for the sum of
// squares alone: on the shared data, 4 gave 44 curvature extrema fewer of 5,911 for 10
// segments more of 9,950 over data_benchmark --variants=8; 2 and 3, 36-37 extrema fewer
// for 23-28 more; 5 and 6, 25 and 13 fewer for 24 and 12 more.) And no more where it
// misses (no patience): its chain is kept there only within the tolerance. With the
// patience, such fits took 3% of the shared data's instructions and 15% of DejaVu's S,
// for 6 curves of 232 that changed, each within the tolerance either way.
constexpr int kPolishAcrossIterations = 4;
// A step of stage 7's fit lowering the sum of squared distances by less than the square
// of this fraction of the tolerance moves no point by a visible part of it: the fit stops
// (ChainFitOptions::least_decrease).
constexpr double kNegligibleMove = 0.01;
// Stage 7 selects its segments for this much inside the tolerance: its model (~1e-6 of
// a segment's length) and the move onto a corner (below) shift the exact chain a little.
constexpr double kSelectionMargin = 0.01;
// Stage 7's chain is moved onto its corner by a similarity where that moves no point by
// more than this fraction of the tolerance, else by stage 6's joint rotation, which
// fails on nearly straight segments (see snapToJoints).
constexpr double kSnapReach = 0.1;
// A part's curve is measured for straying (fitStroke's alternative starts) where it is
// longer than the part's polyline by this factor.
constexpr double kStrayLength = 1.02;
// closestArcPart searches this many of a part's points first, where it has more than
// twice as many: where even they are further than the limit from every arc, all are.
constexpr std::size_t kArcFirstPoints = 64;
// A part's chain shot from its spline whose first fit ends further than this many
// tolerances off is not edited where other starts follow (SplineStart::kShot): their
// chains are kept over its edits. (DejaVu's g: its first part's shot chain, 8.5
// tolerances off after 40 steps, took 20 ms of edits to end 5 off, and the paper's chain
// was kept: 43-75 ms -> 28-29 ms. On the shared data 13 segments more of 9,713, the same
// extrema; at 4, 27 more and 20 extrema more.)
constexpr double kHopelessStart = 8.0;

// The piece reports of a chain stage 7 made (its segments need not be the segmentation's
// pieces any more): each segment's span of spline parameters (those of the points whose
// feet are on it), the kind of its ends (an inflection where the curvature is 0, an
// extremum where |kappa| turns, else a cut by turning), its kind, alpha, and the LCG of
// the smoothed stroke over it.
std::vector<PieceReport> reportsOf(const std::vector<LaSegment>& segments, const std::vector<ChainFoot>& feet,
                                   const std::vector<double>& parameters, const CubicBSpline& spline, bool closed) {
  const std::size_t n = segments.size();
  const double period = spline.tMax() - spline.tMin();
  std::vector<PieceReport> out(n);
  std::vector<bool> seen(n, false);
  for (std::size_t k = 0; k < feet.size() && k < parameters.size(); ++k) {
    PieceReport& r = out[feet[k].segment];
    double t = parameters[k];
    if (!seen[feet[k].segment]) {
      r.t0 = r.t1 = t;
      seen[feet[k].segment] = true;
      continue;
    }
    if (closed && t < r.t1) t += period;  // through the seam
    r.t1 = t;
  }
  auto trend = [](const LaSegment& s) { return std::abs(s.kappaEnd()) > std::abs(s.kappaStart()); };
  for (std::size_t i = 0; i < n; ++i) {
    const LaSegment& seg = segments[i];
    PieceReport& r = out[i];
    if (!seen[i]) r.t0 = r.t1 = i > 0 ? out[i - 1].t1 : spline.tMin();
    auto kindAt = [&](std::size_t joint) {
      if (!closed && (joint == 0 || joint == n)) return SplitKind::kEnd;
      const LaSegment& before = segments[(joint + n - 1) % n];
      const LaSegment& after = segments[joint % n];
      if (after.kappaStart() == 0.0) return SplitKind::kInflection;
      return trend(before) != trend(after) ? SplitKind::kExtremum : SplitKind::kTurning;
    };
    r.start_kind = kindAt(i);
    r.end_kind = kindAt(i + 1);
    r.kind = seg.kappaStart() == 0.0 ? PieceKind::kInflectionStart
             : seg.kappaEnd() == 0.0 ? PieceKind::kInflectionEnd
                                     : PieceKind::kThreePoint;
    r.alpha = seg.alpha();
    if (r.t1 > r.t0) {
      const LcgFit lcg = lcgOfPiece(spline, r.t0, r.t1);
      r.lcg_alpha = lcg.alpha;
      r.lcg_r2 = lcg.r2;
    } else {
      r.lcg_alpha = r.lcg_r2 = NAN;
    }
  }
  return out;
}

}  // namespace

SelectionOptions stage7Selection(const FitContext& context) {
  const FitOptions& options = context.options;
  SelectionOptions so;
  so.tolerance = (1.0 - kSelectionMargin) * context.tolerance;
  ChainFitOptions& co = so.fit;
  co.min_alpha = options.min_alpha;
  co.max_alpha = options.max_alpha;
  co.max_points = kFitPoints;
  co.max_iterations = kFitIterations;
  co.standard_errors = options.alpha_standard_errors;
  co.noise = context.noise.sigma;
  const double negligible_move = kNegligibleMove * context.tolerance;
  co.least_decrease = negligible_move * negligible_move;
  so.max_extrema = options.segmentation.max_extrema;
  so.diagonal = context.diagonal;
  so.budget = co.budget = context.budget;
  // (DESIGN.md section 6: a bend tighter than the tolerance is a corner; a hair inside,
  // so that rounding leaves no radius under it)
  if (context.radius_bound != RadiusBound::kFree) co.max_curvature = (1.0 - 1e-9) / context.tolerance;
  return so;
}

SelectionOptions stage7Selection(const FitContext& context, const Part& part) {
  SelectionOptions so = stage7Selection(context);
  so.fit.closed = part.closed;
  so.fit.fix_start = part.starts_at_corner;
  so.fit.fix_end = part.ends_at_corner;
  return so;
}

double largestKappa(const std::vector<LaSegment>& segments) {
  double most = 0.0;
  for (const LaSegment& s : segments) most = std::max(most, s.maxAbsKappa());
  return most;
}

bool bendsTighterThan(const std::vector<LaSegment>& segments, double tolerance) {
  return largestKappa(segments) * tolerance > kTighterThanTolerance;
}

bool keepsTheBound(const std::vector<LaSegment>& segments, const FitContext& context) {
  return context.radius_bound == RadiusBound::kFree || !bendsTighterThan(segments, context.tolerance);
}

bool overCap(const std::vector<LaSegment>& segments, bool closed, const FitContext& context) {
  const int cap = context.options.segmentation.max_extrema;
  return cap >= 0 && overExtremaCap(curveOf(segments, closed), context.diagonal, cap);
}

PartFit partFitOf(const ChainFitResult& chain, const std::string& what) {
  PartFit fit;
  fit.segments = chain.segments;
  for (std::size_t i = 0; i < fit.segments.size(); ++i) {
    const LaSegment& s = fit.segments[i];
    PieceReport report;
    report.kind = s.kappaStart() == 0.0 ? PieceKind::kInflectionStart
                  : s.kappaEnd() == 0.0 ? PieceKind::kInflectionEnd
                                        : PieceKind::kThreePoint;
    report.alpha = s.alpha();
    report.lcg_alpha = report.lcg_r2 = NAN;
    if (i < chain.alpha_standard_error.size()) report.alpha_standard_error = chain.alpha_standard_error[i];
    fit.reports.push_back(report);
  }
  fit.max_dev = chain.max_distance;
  fit.feet = chain.feet;
  fit.smoothing = {SolveStatus::kConverged, 0, 0.0, "not needed: " + what};
  fit.g2 = {SolveStatus::kConverged, chain.report.iterations, 0.0, what + " (stage 7)"};
  return fit;
}

namespace {

// The signed curvature of the circle through a, the part's middle point m and b (the
// chord from a to b of length `chord`): 2 sin(angle at m) / chord; 0 where m is on an end.
double curvatureThroughMiddle(const Part& part, double chord) {
  const Vec2 a = part.points.front(), m = part.points[part.points.size() / 2], b = part.points.back();
  const double kappa = 2.0 * cross(m - a, b - m) / ((m - a).norm() * (b - m).norm() * chord);
  return std::isfinite(kappa) ? kappa : 0.0;
}

// The minor circular arc of curvature kappa from a to b (turning kappa L, it starts turned
// back by half of that from the chord).
LaSegment arcOverChord(const Vec2& a, const Vec2& b, double kappa) {
  const double chord = (b - a).norm();
  const double half = std::asin(std::min(1.0, 0.5 * std::abs(kappa) * chord));
  const double length = kappa == 0.0 ? chord : 2.0 * half / std::abs(kappa);
  return LaSegment::arc(length, a, angleOf(b - a) - 0.5 * kappa * length, kappa);
}

}  // namespace

std::optional<PartFit> oneArcPart(const Part& part, const FitContext& context, const std::string& what, double screen) {
  if (part.closed || part.points.size() < 3) return std::nullopt;
  const Vec2 a = part.points.front(), b = part.points.back();
  const double chord = (b - a).norm();
  if (!(chord > 0.0)) return std::nullopt;
  const double kappa = curvatureThroughMiddle(part, chord);
  const LaSegment arc = arcOverChord(a, b, kappa);
  const double theta0 = arc.theta0();
  if (screen < INFINITY) {
    // (each point's distance from the arc's circle, or its line, is at most its distance
    // from the arc: a pass of a few flops a point, where the distance from the arc itself
    // cost a tenth of a 1,000-point stroke's fit)
    const Vec2 centre = kappa == 0.0 ? a : Vec2(a + unitVector(theta0 + 0.5 * std::numbers::pi) / kappa);
    const Vec2 along = (b - a) / chord;
    for (const Vec2& p : part.points) {
      const double off = kappa == 0.0 ? std::abs(cross(along, p - a)) : std::abs((p - centre).norm() - 1.0 / std::abs(kappa));
      if (off > screen) return std::nullopt;
    }
  }
  const ChainFitOptions co = stage7Selection(context, part).fit;
  ChainFitResult r = fitChain({arc}, part.points, {}, co);
  if (r.report.status != SolveStatus::kBadInput && r.improved && co.fix_end)
    r.segments = snapToJoints(r.segments, false, b, context.g2(), kSnapReach * context.tolerance);
  if (r.report.status == SolveStatus::kBadInput || !r.improved || r.segments.empty()) {
    r = ChainFitResult{};  // (that arc, which no fit made)
    r.segments = {arc};
  }
  PartFit fit = partFitOf(r, what);
  fit.max_dev = maxDeviationOf(fit.segments, part.points, context.diagonal);
  return fit;
}

namespace {

// A point in the frame of a chord of length c (q: the point less the chord's middle, u
// along the chord, n = u turned left): what its distance from any arc over the chord needs.
struct PointAboutChord {
  PointAboutChord(const Vec2& q, const Vec2& u, double c)
      : t(q.dot(u)),
        qn(cross(u, q)),
        power(q.squaredNorm() - 0.25 * c * c),
        to_end(std::min((q + 0.5 * c * u).norm(), (q - 0.5 * c * u).norm())) {}
  double t, qn, power, to_end;  // (q.u, q.n, |q|^2 - c^2/4, the distance to the nearer end)
};

// Its distance from the minor circular arc of curvature kappa over the chord, or from the
// nearer chord end where it lies outside the arc's sector. In the chord's frame, so that a
// nearly straight arc (its centre far away) loses no digits: with hk = sqrt(1 - (kappa c /
// 2)^2), the signed distance from the circle is (kappa (|q|^2 - c^2/4) - 2 hk q.n) /
// (1 + sqrt(1 + kappa^2 (|q|^2 - c^2/4) - 2 kappa hk q.n)) (times the sign of kappa),
// and q is in the sector where |q.u| <= c/2 (1 - kappa q.n / hk).
double distanceFromArc(const PointAboutChord& p, double c, double kappa, double hk) {
  if (std::abs(p.t) > 0.5 * c * (1.0 - kappa * p.qn / std::max(hk, 1e-300))) return p.to_end;
  return std::abs(kappa * p.power - 2.0 * hk * p.qn) /
         (1.0 + std::sqrt(std::max(0.0, 1.0 + kappa * kappa * p.power - 2.0 * kappa * hk * p.qn)));
}

// The curvature of the minor arc over the chord (length c) whose largest distance from
// the points is the smallest, and that distance; no curvature beyond `reach` either way.
// A scan of the curvatures, then golden sections about the best: the largest distance is
// a maximum of functions each unimodal in the curvature. `through`: a curvature near the
// best (the scan starts there, so that most curvatures further off stop at their first
// point; of equal distances it keeps the straight chord's, then the smallest curvature's,
// whatever the order).
std::pair<double, double> closestArc(const std::vector<PointAboutChord>& points, double c, double reach, double through) {
  // The largest distance of the points from the arc of curvature kappa, or a value above
  // `above` once one point is that far (the search compares, it needs no larger values
  // exactly). The point that was farthest last time goes first: it usually is again.
  std::size_t farthest = 0;
  auto worst = [&](double kappa, double above = std::numeric_limits<double>::infinity()) {
    const double hk = std::sqrt(std::max(0.0, 1.0 - 0.25 * kappa * kappa * c * c));
    double most = distanceFromArc(points[farthest], c, kappa, hk);
    if (most > above) return most;
    for (std::size_t i = 0; i < points.size(); ++i) {
      const double d = distanceFromArc(points[i], c, kappa, hk);
      if (d <= most) continue;
      most = d, farthest = i;
      if (most > above) break;
    }
    return most;
  };
  constexpr int kScan = 24, kSections = 30;
  const int start = static_cast<int>(std::lround(std::clamp(through / reach, -1.0, 1.0) * kScan));
  int best_k = 0;
  double best_worst = worst(0.0);
  for (int i = -kScan - 1; i <= kScan; ++i) {
    const int k = i < -kScan ? start : i;
    if (k == 0 || (i >= -kScan && k == start)) continue;
    const double w = worst(reach * k / kScan, best_worst);
    if (w < best_worst || (w == best_worst && best_k != 0 && k < best_k)) best_k = k, best_worst = w;
  }
  const double best = reach * best_k / kScan;
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = std::max(-reach, best - reach / kScan), hi = std::min(reach, best + reach / kScan);
  double x1 = hi - golden * (hi - lo), x2 = lo + golden * (hi - lo), w1 = worst(x1), w2 = worst(x2, w1);
  for (int k = 0; k < kSections; ++k) {
    if (w1 < w2) {
      hi = x2, x2 = x1, w2 = w1;
      x1 = hi - golden * (hi - lo), w1 = worst(x1, w2);
    } else {
      lo = x1, x1 = x2, w1 = w2;
      x2 = lo + golden * (hi - lo), w2 = worst(x2, w1);
    }
  }
  if (!(std::min(w1, w2) < best_worst)) return {best, best_worst};
  return w1 < w2 ? std::pair{x1, w1} : std::pair{x2, w2};
}

}  // namespace

std::optional<PartFit> closestArcPart(const Part& part, const FitContext& context, const std::string& what, double limit) {
  if (part.closed || part.points.size() < 3) return std::nullopt;
  const Vec2 a = part.points.front(), b = part.points.back();
  const double c = (b - a).norm();
  if (!(c > 0.0)) return std::nullopt;
  const Vec2 u = (b - a) / c, middle = 0.5 * (a + b);
  std::vector<PointAboutChord> points;
  points.reserve(part.points.size());
  for (const Vec2& p : part.points) points.emplace_back(p - middle, u, c);
  // (a minor arc, no tighter than the bound on the radius where it is promised; the scan
  // from the circle through the ends and the middle point)
  double reach = 2.0 / c;
  if (context.radius_bound != RadiusBound::kFree) reach = std::min(reach, (1.0 - 1e-9) / context.tolerance);
  const double through = curvatureThroughMiddle(part, c);
  // (the arcs mostly miss: a search over a few points first, which costs a fraction of
  // the search over all, on a 1,000-point stroke a tenth of the fit's time; their arc is
  // no further from them than the closest arc to all)
  if (limit < INFINITY && points.size() > 2 * kArcFirstPoints) {
    std::vector<PointAboutChord> some;
    for (std::size_t i = 0; i < points.size(); i += points.size() / kArcFirstPoints) some.push_back(points[i]);
    if (closestArc(some, c, reach, through).second > limit * (1.0 + 1e-9)) return std::nullopt;
  }
  const auto [chosen, best_worst] = closestArc(points, c, reach, through);
  if (best_worst > limit) return std::nullopt;
  ChainFitResult alone;  // (an arc no fit made)
  alone.segments = {arcOverChord(a, b, chosen)};
  PartFit fit = partFitOf(alone, what);
  fit.max_dev = best_worst;  // (the points' exact distances from the arc)
  return fit;
}

void keepTheCap(PartFit& fit, const Part& part, const FitContext& context) {
  if (part.points.size() < 3 || !overCap(fit.segments, part.closed, context)) return;
  if (part.closed) {
    // (a simple closed curve other than a circle has at least 4 extrema)
    if (context.options.segmentation.max_extrema >= 4) return;
    if (const std::optional<LaSegment> circle = closestCircle(part.points)) {
      ChainFitResult alone;  // (a circle no fit made)
      alone.segments = {*circle};
      fit = partFitOf(alone, "the closest circle, for the cap on extrema");
      fit.capped = true;
      fit.max_dev = maxDeviationOf(fit.segments, part.points, context.diagonal);
    }
    return;
  }
  if (std::optional<PartFit> arc = oneArcPart(part, context, "one LA segment, for the cap on extrema")) {
    fit = std::move(*arc);
    fit.capped = true;
  }
}

// (fits its chain to the points and selects its segments, fitting/model_selection.h)
void polishPart(PartFit& fit, const Part& part, const FitContext& context, bool choose_segments,
                SplineStart spline_start) {
  if (!fit.spline) return;  // a straight part
  const FitOptions& options = context.options;
  const double tol = context.tolerance, diag = context.diagonal;
  SelectionOptions so = stage7Selection(context, part);
  so.refine = choose_segments;
  ChainFitOptions& co = so.fit;
  std::vector<LaSegment> start = fit.segments;
  const bool straight = std::any_of(start.begin(), start.end(), [](const LaSegment& s) { return s.isStraight(); });
  std::vector<ChainFoot> feet = fit.feet;
  const bool from_spline = !fit.g2.usable() || straight || start.size() != fit.spans.size();
  // (with `halve`, the spline's spans where a shot segment sets off astray are halved)
  auto startFromSpline = [&](bool halve) {
    std::vector<PieceReport> spans = fit.spans;
    start = chainFromSpline(*fit.spline, spans, part.closed, options.min_alpha, options.max_alpha, halve, context.budget);
    feet = feetOnSpans(spans, fit.parameters, part.closed, fit.spline->tMax() - fit.spline->tMin());
  };
  if (spline_start == SplineStart::kHalved) {
    if (!from_spline) return;
    startFromSpline(false);
    const std::size_t shot = start.size();
    startFromSpline(true);
    if (start.empty() || start.size() == shot) return;
  } else if (from_spline) {
    startFromSpline(false);
  }
  if (start.empty()) return;
  if (from_spline && spline_start == SplineStart::kShot) so.hopeless_start = kHopelessStart * tol;
  SelectionResult selected = selectChain(start, part.points, feet, so);
  if (from_spline && spline_start == SplineStart::kShotThenHalved && selected.fit.max_distance > kAstrayFit * tol &&
      selected.cap_merges == 0) {
    // Far outside the tolerance from the spline's chain: again from its spans halved
    // where it set off astray, the closer kept. (Within twice the tolerance, the fit
    // across corners usually closes the gap, and the halved start only adds segments.
    // Not where the cap on extrema merged segments: that is why it is far, and the cap
    // merges the finer start's as well. On the shared data under a cap of 1, time p99
    // 649 -> 297 ms for it, and the 3 curves that changed came closer to their points.)
    const std::size_t count = start.size();
    startFromSpline(true);
    if (!start.empty() && start.size() != count) {
      SelectionResult again = selectChain(start, part.points, feet, so);
      if (again.fit.report.status != SolveStatus::kBadInput && again.fit.max_distance < selected.fit.max_distance)
        selected = std::move(again);
    }
  }
  const ChainFitResult& polished = selected.fit;
  if (polished.report.status == SolveStatus::kBadInput) return;
  std::vector<LaSegment> segments = polished.segments;
  if (co.closed || co.fix_end) {
    const G2Options g2 = context.g2();
    segments = snapToJoints(segments, co.closed, part.points.back(), g2, kSnapReach * tol);
    if (segments.empty()) return;
  }
  // (the user's limits and the bound on the chain it started from: looked at only where
  // stage 7 misses)
  auto withinLimits = [&] {
    auto in_range = [&](const LaSegment& s) {
      return s.isStraight() || (s.alpha() >= options.min_alpha && s.alpha() <= options.max_alpha);
    };
    return !overCap(fit.segments, part.closed, context) &&
           (polished.max_distance > kAstrayFit * tol ||
            (keepsTheBound(fit.segments, context) && std::all_of(fit.segments.begin(), fit.segments.end(), in_range)));
  };
  if (polished.max_distance > tol && fit.g2.usable() && withinLimits()) {
    // Outside the tolerance: kept if closer to the points than the G2 chain it started
    // from. A chain with curvature or tangent gaps is always replaced: G2 is the promise
    // (a kink where the user drew none is worse than a miss, which the figures report);
    // so is one over the cap on extrema (the cap wins over the tolerance), and one with an
    // alpha outside the options' range (the paper's inflection segments reach such
    // alphas; stage 7 keeps its own within it) or bending tighter than the tolerance
    // where the bound is promised (a noisy 8-point side: stage 6's chain 21 times
    // tighter), unless stage 7's chain is astray (a fit the time budget cut short: a
    // glyph's part 6 tolerances off, its paper chain 0.6).
    fit.max_dev = maxDeviationOf(fit.segments, part.points, diag);
    if (polished.max_distance >= fit.max_dev) return;
  }
  // (a chain the snap moved is measured again; one already exact keeps the fit's figure,
  // saving a distance pass on every part that ends at a corner)
  const bool moved = segments.size() != polished.segments.size() || segments.back().end() != polished.segments.back().end();
  fit.max_dev = moved ? maxDeviationOf(segments, part.points, diag) : polished.max_distance;
  fit.warnings.clear();
  fit.capped = selected.cap_merges > 0;
  fit.segments = segments;
  fit.g2 = {SolveStatus::kConverged, polished.report.iterations, 0.0, "G2 by construction (stage 7)"};
  fit.reports = reportsOf(fit.segments, polished.feet, fit.parameters, *fit.spline, part.closed);
  for (std::size_t i = 0; i < fit.reports.size() && i < polished.alpha_standard_error.size(); ++i)
    fit.reports[i].alpha_standard_error = polished.alpha_standard_error[i];
}

namespace {

// polishInPieces: a piece is kPieceSpans of the spline's spans (stage 7's fit of a
// piece's chain grows with the cube of its segments, about 1.5 per span) and is fitted
// with kPieceOverlap of the next piece's; its joints meet G2 where the tangent (radians)
// and the relative curvature agree to kG2Joint (data_benchmark's kKink). Where that chain
// strays from the points (a loop between two of them), pieces of kOtherPieceSpans are
// tried too, the closest kept: which piece sets off on a loop follows the last bits of
// the fits (a walked stroke's chain in pieces of 12 spans kept 1.75 tolerances with
// glibc's FMA paths and went 103 tolerances astray without them, where pieces of 8 or
// 20 spans kept 1.5-2.2 and 1.5 either way). Only where the chain the pieces would
// replace is kinked (G2 comes first): tried also where it only bends tighter than the
// tolerance, they cost the shared data's walked strokes 15 s more of 108 s instead of 10,
// for 2 curves changed more.
constexpr std::size_t kPieceSpans = 12, kPieceOverlap = 3;
constexpr std::size_t kOtherPieceSpans[] = {8, 20};
constexpr double kG2Joint = 1e-9;

// polishInPieces in pieces of `piece_spans` spans.
bool polishInPiecesOf(PartFit& fit, const Part& part, const FitContext& context, std::size_t piece_spans) {
  const std::vector<Vec2>& points = part.points;
  const double diag = context.diagonal, tol = context.tolerance;
  const std::vector<PieceReport>& spans = fit.spans;
  const std::size_t n = spans.size();
  if (part.closed || !fit.spline || n < 2 || fit.parameters.size() != points.size()) return false;
  const FitOptions& options = context.options;
  const SelectionOptions part_options = stage7Selection(context, part);
  // (the first point at or past spline parameter t: the points' parameters grow)
  auto pointAt = [&](double t) {
    return static_cast<std::size_t>(std::lower_bound(fit.parameters.begin(), fit.parameters.end(), t) - fit.parameters.begin());
  };
  std::vector<LaSegment> out;
  std::vector<ChainFoot> feet;
  for (std::size_t a = 0, p0 = 0; a < n;) {
    // Each piece is fitted over its spans and a few of the next piece's, and keeps its
    // segments up to its own points' last foot: where it ends, the points on both sides
    // have placed it. Points p0..p1 are its own, p1..p2 the next piece's it also fits.
    std::size_t b = std::min(n, a + piece_spans);
    if (n - b < piece_spans / 2) b = n;
    const std::size_t reach = b == n ? n : std::min(n, b + kPieceOverlap);
    const bool first = out.empty(), last = b == n;
    const std::size_t p1 = last ? points.size() : pointAt(spans[b].t0);
    const std::size_t p2 = reach == n ? points.size() : pointAt(spans[reach].t0);
    if (p1 < p0 + 2) return false;
    std::optional<ChainStart> from;
    if (!first) from = ChainStart{out.back().end(), out.back().theta(out.back().length()), out.back().kappaEnd()};
    std::vector<PieceReport> piece(spans.begin() + static_cast<std::ptrdiff_t>(a), spans.begin() + static_cast<std::ptrdiff_t>(reach));
    if (!first) piece.front().t0 = std::max(piece.front().t0, fit.parameters[p0]);
    auto shoot = [&] {
      std::vector<PieceReport> shot = piece;
      return chainFromSpline(*fit.spline, shot, false, options.min_alpha, options.max_alpha, true, context.budget, from);
    };
    std::vector<LaSegment> start = shoot();
    // (the rest of the span the piece starts in may turn too little, or against the
    // curvature it starts with: it joins the next span)
    for (int joined = 0; start.empty() && joined < 2 && piece.size() > 2; ++joined) {
      piece[1].t0 = piece[0].t0;
      piece[1].start_kind = piece[0].start_kind;
      piece.erase(piece.begin());
      start = shoot();
    }
    if (start.empty() && from && from->kappa != 0.0) {
      // (no LA segment goes on from the kept segments' end curvature along the spline:
      // a clothoid a tolerance long takes it to 0 first, G2)
      try {
        out.push_back(LaSegment(-1.0, tol, from->point, from->theta, from->kappa, 0.0));
      } catch (const std::invalid_argument&) {
        return false;
      }
      from = ChainStart{out.back().end(), out.back().theta(out.back().length()), 0.0};
      start = shoot();
    }
    std::vector<Vec2> near;
    if (from) near.push_back(from->point);  // (the held start is the first point)
    near.insert(near.end(), points.begin() + static_cast<std::ptrdiff_t>(p0), points.begin() + static_cast<std::ptrdiff_t>(p2));
    if (start.empty() || near.size() < 3) return false;
    SelectionOptions so = part_options;
    so.fit.fix_end = reach == n && part_options.fit.fix_end;
    if (from) {
      so.fit.fix_start = true;
      so.fit.held_start = ChainFitOptions::HeldStart{from->theta, from->kappa};
    }
    const SelectionResult selected = selectChain(start, near, {}, so);
    const ChainFitResult& r = selected.fit;
    if (r.report.status == SolveStatus::kBadInput || r.segments.empty() || r.feet.size() != near.size()) return false;
    const std::size_t offset = from ? 1 : 0;  // (near's index of points[p0])
    const std::size_t kept = last ? r.segments.size() : r.feet[offset + (p1 - 1 - p0)].segment + 1;
    std::size_t next = p0;
    for (std::size_t k = p0; k < p2 && r.feet[offset + k - p0].segment < kept; ++k) {
      feet.push_back({r.feet[offset + k - p0].segment + out.size(), r.feet[offset + k - p0].u});
      next = k + 1;
    }
    if (next <= p0 + 1) return false;
    out.insert(out.end(), r.segments.begin(), r.segments.begin() + static_cast<std::ptrdiff_t>(kept));
    if (last) break;
    p0 = next;
    if (p0 >= points.size()) return false;  // (no point left for the spans left)
    // (the next piece starts in the span holding its first point)
    a = static_cast<std::size_t>(std::upper_bound(spans.begin(), spans.end(), fit.parameters[p0],
                                                  [](double t, const PieceReport& s) { return t < s.t1; }) -
                                 spans.begin());
    if (a >= n) return false;
  }
  if (feet.size() != points.size()) return false;
  for (std::size_t j = 1; j < out.size(); ++j)
    if (std::abs(turnBetween(out[j - 1], out[j])) > kG2Joint || relativeGap(out[j - 1].kappaEnd(), out[j].kappaStart(), diag) > kG2Joint)
      return false;
  fit.segments = std::move(out);
  fit.max_dev = maxDeviationOf(fit.segments, points, diag);
  fit.stray = NAN;
  fit.warnings.clear();
  fit.g2 = {SolveStatus::kConverged, 0, 0.0, "G2 by construction (stage 7, in pieces)"};
  fit.reports = reportsOf(fit.segments, feet, fit.parameters, *fit.spline, false);
  return true;
}

}  // namespace

bool polishInPieces(PartFit& fit, const Part& part, const FitContext& context) {
  // (each chain's stray kept in it: the caller measures the chain by it too)
  auto worst = [&](PartFit& f) { return worstOf(f, part, context.diagonal); };
  PartFit best = fit;
  bool made = polishInPiecesOf(best, part, context, kPieceSpans);
  double best_worst = made ? worst(best) : INFINITY;
  if (!fit.g2.usable() && !(made && best.stray <= kStrayWarning * context.tolerance))
    for (std::size_t spans : kOtherPieceSpans) {
      PartFit other = fit;
      if (!polishInPiecesOf(other, part, context, spans)) continue;
      if (const double w = worst(other); w < best_worst) best = std::move(other), best_worst = w, made = true;
    }
  if (made) fit = std::move(best);
  return made;
}

// How far a part's chain goes from the part's polyline (strayFromPoints), measured only
// where the chain is longer than the polyline (kStrayLength; else 0): a loop adds
// length, noise only to the polyline, and the measure costs a grid of the points. With
// `tip_allowance` (world units), measured always, and counted where above it: a sharp
// corner running past the rounded tip of a drawn corner adds almost no length.
double strayOf(const std::vector<LaSegment>& segments, const Part& part, double diag, double tip_allowance) {
  double curve_length = 0.0, stroke_length = 0.0;
  for (const LaSegment& s : segments) curve_length += s.length();
  for (std::size_t i = 1; i < part.points.size(); ++i) stroke_length += (part.points[i] - part.points[i - 1]).norm();
  if (part.closed) stroke_length += (part.points.front() - part.points.back()).norm();
  const bool longer = curve_length > kStrayLength * stroke_length;
  if (longer) return strayFromPoints(curveOf(segments, part.closed), part.points, diag);
  return tip_allowance == INFINITY ? 0.0 : strayBeyond(curveOf(segments, part.closed), part.points, diag, tip_allowance);
}

double strayOfFit(PartFit& fit, const Part& part, double diag) {
  if (std::isnan(fit.stray)) fit.stray = strayOf(fit.segments, part, diag);
  return fit.stray;
}

double worstOf(PartFit& fit, const Part& part, double diag) {
  if (std::isnan(fit.max_dev)) fit.max_dev = maxDeviationOf(fit.segments, part.points, diag);
  return std::max(fit.max_dev, strayOfFit(fit, part, diag));
}

// Makes the parts' chains meet at their corners. Stage 7 pins a part's ends to its
// corner points, but a part whose chain comes from stages 2-6 (stage 7 off, or its
// result not kept) ends where its smoothing spline does, up to about a tolerance from
// the corner: the curve would be broken there. Each such pair of ends moves to their
// midpoint, each part's chain by the similarity that takes its two ends to their places
// (movedOntoEnds). Where that fails the gap stays, and g0_gap shows it. (After the fit
// across corners the parts meet already, but for a closed chain's seam, to rounding.)
void joinAtCorners(std::vector<PartFit>& fits, const std::vector<Part>& parts, const G2Options& g2) {
  const std::size_t n = fits.size();
  if (n == 0) return;
  std::vector<Vec2> starts(n), ends(n);
  for (std::size_t k = 0; k < n; ++k) {
    if (fits[k].segments.empty()) return;
    starts[k] = fits[k].segments.front().start();
    ends[k] = fits[k].segments.back().end();
  }
  std::vector<Vec2> to_start = starts, to_end = ends;
  for (std::size_t k = 0; k < n; ++k) {
    if (!parts[k].ends_at_corner) continue;
    const std::size_t next = (k + 1) % n;
    to_end[k] = to_start[next] = 0.5 * (ends[k] + starts[next]);
  }
  for (std::size_t k = 0; k < n; ++k) {
    const Vec2 from = ends[k] - starts[k], to = to_end[k] - to_start[k];
    if (to_start[k] == starts[k] && to_end[k] == ends[k]) continue;
    if (!(from.norm() > 0.0 && to.norm() > 0.0)) {
      // A part from a closed stroke's only corner back to it: no similarity closes it, a
      // joint deformation (as stage 6) takes its end to its start.
      std::vector<LaSegment> closed_up = snapToJoints(fits[k].segments, false, starts[k], g2);
      if (closed_up.empty()) continue;
      fits[k].segments = std::move(closed_up);
    } else {
      fits[k].segments = movedOntoEnds(fits[k].segments, to_start[k], to_end[k]);
    }
    fits[k].max_dev = fits[k].stray = NAN;  // (of the chain before the move)
  }
}

// Stage 7 across corners. Each part's chain was fitted with its ends pinned to the
// corner samples, but a corner falls between samples, and a drawn one is rounded: the
// sample is seldom where the two sides' curves meet, and the sides bend to reach it.
// This fits all the parts' chains as one chain whose corners are free (fitChain's
// corners: position continuous, tangent and curvature free), so the fit places each
// corner where the sides meet; where that misses the tolerance, also with each corner's
// point held at the corner (the tip of a rounded corner), starting from the first try's
// chain, the better kept. Where the curve misses, the segments are chosen again too
// (selectChain; else only hooks beside corners are collapsed and sides straightened, in
// fits of kPolishAcrossIterations steps). A straight part stays a line unless the selection
// bends it. Kept where it brings the curve closer to the points, counting the stray, or
// keeps it within the tolerance. True if it changed the chains; false where a part has
// no G2 chain.
bool fitAcrossCorners(std::vector<PartFit>& fits, const std::vector<Part>& parts, bool closed,
                      const FitContext& context) {
  const std::size_t n = parts.size();
  if (n == 0 || !(parts.front().starts_at_corner || parts.front().ends_at_corner)) return false;
  const double tol = context.tolerance, diag = context.diagonal;
  std::vector<LaSegment> chain;
  std::vector<Vec2> points;
  SelectionOptions so = stage7Selection(context);
  ChainFitOptions& co = so.fit;
  co.closed = closed;
  std::vector<std::size_t> first_point;
  for (std::size_t k = 0; k < n; ++k) {
    const PartFit& fit = fits[k];
    if (!fit.g2.usable() || fit.segments.empty()) return false;
    first_point.push_back(points.empty() ? 0 : points.size() - 1);  // (the corner is both parts')
    if (parts[k].starts_at_corner) co.corners.push_back({chain.size(), first_point.back()});
    chain.insert(chain.end(), fit.segments.begin(), fit.segments.end());
    points.insert(points.end(), parts[k].points.begin() + (points.empty() ? 0 : 1), parts[k].points.end());
  }
  if (closed) points.pop_back();  // the first corner again
  // The larger of the deviation and the stray. At a corner's tip, a stray counts beyond
  // the warning's bound and a sample step: the polyline between two samples cuts a sharp
  // corner by up to about a step.
  const double tip_allowance = kStrayWarning * tol + medianStep(points);
  double before = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    PartFit& fit = fits[k];
    if (std::isnan(fit.max_dev)) fit.max_dev = maxDeviationOf(fit.segments, parts[k].points, diag);
    fit.stray = strayOf(fit.segments, parts[k], diag, tip_allowance);
    before = std::max({before, fit.max_dev, fit.stray});
  }

  // The parts' chains from one joint fit, with their largest deviation or stray.
  auto split = [&](const SelectionResult& selected, std::vector<PartFit>& out) -> double {
    const ChainFitResult& joint = selected.fit;
    std::vector<std::size_t> first_segment = {0};  // (the edits may have added or removed some)
    for (const ChainCorner& c : selected.corners)
      if (c.joint > 0) first_segment.push_back(c.joint);
    first_segment.push_back(joint.segments.size());
    if (!joint.improved || first_segment.size() != n + 1) return INFINITY;
    out = fits;
    double worst = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      PartFit& fit = out[k];
      const std::size_t s0 = first_segment[k], count = first_segment[k + 1] - s0;
      fit.segments.assign(joint.segments.begin() + static_cast<std::ptrdiff_t>(s0),
                          joint.segments.begin() + static_cast<std::ptrdiff_t>(s0 + count));
      // The part's points: their feet on its own segments (past its corner: its end
      // there) and their distances.
      std::vector<ChainFoot> feet;
      fit.max_dev = 0.0;
      for (std::size_t i = 0; i < parts[k].points.size(); ++i) {
        const std::size_t at = (first_point[k] + i) % points.size();
        const ChainFoot& f = joint.feet[at];
        feet.push_back(f.segment < s0           ? ChainFoot{0, 0.0}
                       : f.segment >= s0 + count ? ChainFoot{count - 1, 1.0}
                                                 : ChainFoot{f.segment - s0, f.u});
        fit.max_dev = std::max(fit.max_dev, joint.distance[at]);
      }
      fit.stray = strayOf(fit.segments, parts[k], diag, tip_allowance);
      worst = std::max({worst, fit.max_dev, fit.stray});
      fit.warnings.clear();  // (of the stages whose chain this replaces)
      fit.g2 = {SolveStatus::kConverged, joint.report.iterations, 0.0, "G2 by construction (stage 7, across corners)"};
      if (fit.spline) {
        fit.reports = reportsOf(fit.segments, feet, fit.parameters, *fit.spline, false);
      } else {  // a straight part: still a line, or bent (and split) by the selection, no spline
        fit.reports.assign(count, fits[k].reports.front());
        for (std::size_t i = 0; i < count; ++i) fit.reports[i].alpha = fit.segments[i].alpha();
      }
      for (std::size_t i = 0; i < count && s0 + i < joint.alpha_standard_error.size(); ++i)
        fit.reports[i].alpha_standard_error = joint.alpha_standard_error[s0 + i];
    }
    return worst;
  };
  // (the segments are chosen again only where the curve misses: else they stay, but for
  // hooks beside corners and sides straightened, and the fits only move the corners. The
  // parts' nearly straight runs were tried as lines when their segments were chosen:
  // tried again across corners, none of 194 was kept on the shared data, variants
  // included, each a fit of the whole chain.)
  so.refine = so.straighten_runs = before > tol;
  // (segments levelled into arcs where the parts keep the tolerance: with its corners
  // free, a side that curled into one to reach its sample can let the curl go. Levelled
  // in the parts' own selections too, the shared data's curves had 44 extrema fewer
  // instead of 18, for 6% more instructions and a median time of 2.18 ms instead of
  // 1.78; in the selection that chooses the segments here, an arc let a side of 6
  // segments and 2 extrema replace a line)
  so.level_arcs = !so.refine;
  if (!so.refine) {
    co.max_iterations = kPolishAcrossIterations;
    so.patience = 0;
  }
  std::vector<PartFit> out, held;
  const SelectionResult free = selectChain(chain, points, {}, so);
  double after = split(free, out);
  if (after > tol) {
    // (from the free fit where it improved: its hooks are gone and its corners near)
    co.hold_corner_points = true;
    SelectionResult held_fit;
    if (free.fit.improved) {
      // (the free fit's trial edits it did not keep are not tried again: holding the
      // corners' points only constrains the fit further; on the shared data one $1 brace
      // came out with two extrema fewer in two of its variants, no other curve changed)
      co.corners = free.corners;
      so.not_kept = free.not_kept;
      held_fit = selectChain(free.fit.segments, points, free.fit.feet, so);
    } else {
      held_fit = selectChain(chain, points, {}, so);
    }
    const double after_held = split(held_fit, held);
    if (after_held < after) after = after_held, out = std::move(held);
  }
  // (within the tolerance, the least-squares corners are the better estimate; a result
  // that leaves points outside it where the parts' own fits had none is not)
  auto deviation = [](const std::vector<PartFit>& f) {
    double worst = 0.0;
    for (const PartFit& p : f) worst = std::max(worst, p.max_dev);
    return worst;
  };
  if (!(after < before) && !(after <= tol)) return false;
  if (deviation(fits) <= tol && !(deviation(out) <= tol)) return false;
  fits = std::move(out);
  return true;
}


}  // namespace la
