#include "fitting/pipeline.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "fitting/fit_context.h"
#include "fitting/one_segment.h"
#include "fitting/paper_stages.h"
#include "fitting/parts.h"
#include "fitting/stage7.h"
#include "fitting/stroke_noise.h"

namespace la {
namespace {

// A stroke whose left-out samples span more than this fraction of its drawn length says
// so (DESIGN.md section 6).
constexpr double kLeftOutWarning = 0.05;
// A curve whose largest curvature is above this fraction of 1 / tolerance has a joint on
// stage 7's bound (see fitStroke).
constexpr double kOnTheBound = 0.999;
// A part whose chain with a joint on the bound misses by more than this many tolerances
// misses for another reason (a scribble's): it is not fitted again without the bound.
constexpr double kBoundsMiss = 4.0;
// A part's one LA segment that misses only this many tolerances or less from its tight
// end misses at a spiral's centre (see missesAtTightEnd in fitOnce).
constexpr double kTightEndReach = 4.0;
// A part's one LA segment for fewer extrema (fitOnce) is not fitted where the arc it
// starts from passes this many tolerances from a point (from its circle: at most its
// distance from the arc): on the shared data none kept started further off than 2.1.
constexpr double kArcStartMiss = 5.0;
// Rounds of corners put at bends tighter than the tolerance (see fitStroke).
constexpr int kTightBendRounds = 2;
// A corner put at a tight bend goes to the point turning most this many points about it.
constexpr std::size_t kCornerReach = 2;
// A curve with its tight bends made corners is kept where it misses the tolerance by at
// most this factor (a bend tighter than the tolerance is DESIGN.md section 6's defect; a
// miss this small, the warning tells).
constexpr double kCorneredMiss = 1.01;
// Where a part's one LA segment misses the tolerance, the chains from stages 2-6 get this
// many times the work it took (fitOneWith); kNearMissTimes where it (or split) misses by
// at most a tenth. (Work counts the chain fits' Jacobians alone: the one segment's tries
// spend most of their time in its starts' shots, so these are 4 times the shares of its
// time they replace, 4 and 1, measured on spiral_benchmark: every counter the same.)
constexpr int kChainPathTimes = 16;
constexpr int kNearMissTimes = 4;
constexpr double kNearMiss = 1.1;
// Under a cap on extrema, a stroke that misses the tolerance by more than this factor
// misses for the cap's merges, which no fit without the bound on the radius buys back:
// it is not fitted again without the bound (--variants=2 under caps of 0, 1 and 2 on
// the shared data: of 198 such fits that missed by more, none was kept; the 2 kept had
// missed by 1.009, and each such fit is a whole fit again, up to a second on a glyph).
constexpr double kCappedMiss = 1.5;

// A straight stroke: its lines, a corner of pi where it turns back.
void fitStraight(FitResult& r) {
  const std::vector<Vec2>& p = r.cleaned.points;
  const std::vector<std::size_t> turns = turnsAlongLine(p, r.tolerance);
  for (std::size_t k = 0; k + 1 < turns.size(); ++k) {
    const Vec2 a = p[turns[k]], b = p[turns[k + 1]];
    r.curve.pieces.push_back({LaSegment::arc((b - a).norm(), a, angleOf(b - a), 0.0), k > 0});
    PieceReport rep;
    rep.alpha = rep.lcg_alpha = INFINITY;
    rep.lcg_r2 = NAN;
    rep.part = static_cast<int>(k);
    r.pieces.push_back(rep);
    r.splits.emplace_back();
    if (k > 0) r.cleaned.corners.push_back(turns[k]);
  }
  const auto tq = Clock::now();
  r.quality = measureQuality(r.curve, r.cleaned.points);
  r.timings.quality_ms = msSince(tq);
}

// The deviation over every finite raw sample, and a warning where the samples the
// clean-up left out span more than kLeftOutWarning of the drawn length.
void measureLeftOut(FitResult& r, const Stroke& stroke) {
  // (a duplicate lies on a kept point, a non-finite sample has no distance: only the
  // other samples left out can lie further)
  r.max_dev_all_points = r.quality.max_dev;
  std::vector<Vec2> others;
  for (const LeftOutPoint& l : r.cleaned.left_out)
    if (l.why != LeftOutReason::kDuplicate && l.why != LeftOutReason::kNonFinite) others.push_back(stroke.samples[l.sample].p);
  for (double d : distancesToCurve(r.curve, others, r.quality.diagonal)) r.max_dev_all_points = std::max(r.max_dev_all_points, d);
  if (!(r.cleaned.left_out_fraction > kLeftOutWarning)) return;
  std::map<std::string, int> reasons;
  for (const LeftOutPoint& l : r.cleaned.left_out) ++reasons[toString(l.why)];
  std::string why;
  for (const auto& [reason, count] : reasons) why += (why.empty() ? "" : ", ") + std::to_string(count) + " " + reason;
  r.warnings.push_back("the curve leaves out " + std::to_string(r.cleaned.left_out.size()) + " samples (" + why + "), " +
                       std::to_string(static_cast<int>(std::round(100.0 * r.cleaned.left_out_fraction))) +
                       "% of the drawn length; over all samples it passes up to " + std::to_string(r.max_dev_all_points) +
                       " from them");
}

// The tolerance asked for on the raw samples' bounding box, which a hook's worth is tied
// to (fitting/stroke.h; the cleaned points' box is known only after the clean-up).
double hookTolerance(const Stroke& stroke, const FitOptions& options) {
  if (options.tolerance > 0.0) return options.tolerance;
  Vec2 lo = Vec2::Constant(INFINITY), hi = -lo;
  for (const StrokeSample& sample : stroke.samples)
    if (allFinite(sample.p)) lo = lo.cwiseMin(sample.p), hi = hi.cwiseMax(sample.p);
  return lo.x() <= hi.x() ? options.tolerance_fraction * (hi - lo).norm() : 0.0;
}

// Whether a fit's curve bends tighter than its tolerance, by its measured figures.
bool bendsTighterThanTolerance(const FitResult& f) { return f.quality.max_abs_kappa * f.tolerance > kTighterThanTolerance; }

// Where the curve bends tighter than `factor` / tolerance: at a G2 joint, the joint;
// towards a corner or the curve's end, where the segment's |kappa| reaches that (the
// side starts to curl into the corner there, which then belongs there).
std::vector<Vec2> tightBends(const FitResult& r, double factor = kTighterThanTolerance) {
  std::vector<Vec2> at;
  const std::vector<CurvePiece>& pieces = r.curve.pieces;
  const double limit = 1.0 / r.tolerance;
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    const LaSegment& seg = pieces[i].segment;
    if (!(seg.maxAbsKappa() * r.tolerance > factor)) continue;
    const bool at_end = std::abs(seg.kappaEnd()) >= std::abs(seg.kappaStart());
    const bool last = i + 1 == pieces.size();
    const bool joint = at_end ? (!last || r.curve.closed) && !pieces[last ? 0 : i + 1].corner
                              : (i > 0 || r.curve.closed) && !pieces[i].corner;
    if (joint) {
      at.push_back(at_end ? seg.end() : seg.start());
      continue;
    }
    // (|kappa| is monotone along the segment: bisection for where it reaches the limit)
    double lo = 0.0, hi = seg.length();  // loose at lo, tight at hi (towards the tight end)
    auto tight = [&](double s) { return std::abs(seg.kappa(at_end ? s : seg.length() - s)) > factor * limit; };
    if (tight(lo)) hi = lo;
    for (int k = 0; k < 50 && hi > lo; ++k) (tight(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
    at.push_back(seg.position(at_end ? hi : seg.length() - hi));
  }
  return at;
}

// The stroke's point farthest from its curve.
Vec2 farthestPoint(const FitResult& r) {
  const std::vector<double> d = distancesToCurve(r.curve, r.cleaned.points, r.quality.diagonal);
  return r.cleaned.points[static_cast<std::size_t>(std::max_element(d.begin(), d.end()) - d.begin())];
}

// The point of `stroke` where it turns most (by the angle between its steps in and out)
// among the point nearest `q` and kCornerReach points either side of it that can be a
// corner (canBeCorner): a star's tip with a pen-up hook turns most at the hook's far
// point, beside the tip's corner, and its side curled into the tip there. Where the point
// turning most is a corner, the bend is that corner's: that point (which addCorner
// refuses, as it refuses the nearest point where none can be a corner).
std::size_t cornerNear(const CleanStroke& stroke, const Vec2& q) {
  const std::vector<Vec2>& p = stroke.points;
  const std::size_t n = p.size();
  const auto nearest = static_cast<std::size_t>(std::min_element(p.begin(), p.end(), [&](const Vec2& a, const Vec2& b) {
                                                  return (a - q).squaredNorm() < (b - q).squaredNorm();
                                                }) - p.begin());
  std::size_t best = nearest, best_free = nearest;
  double most = -1.0, most_free = -1.0;
  for (std::size_t k = nearest + n - kCornerReach; k <= nearest + n + kCornerReach; ++k) {
    const std::size_t i = k % n;
    if (!stroke.closed && (k < n + 1 || k + 2 > 2 * n)) continue;  // (an open stroke's ends turn nowhere)
    const Vec2 in = p[i] - p[(i + n - 1) % n], out = p[(i + 1) % n] - p[i];
    const double turn = std::abs(std::atan2(cross(in, out), in.dot(out)));
    if (turn > most) most = turn, best = i;
    if (turn > most_free && canBeCorner(stroke, i)) most_free = turn, best_free = i;
  }
  return std::find(stroke.corners.begin(), stroke.corners.end(), best) != stroke.corners.end() ? best : best_free;
}

// The whole pipeline, stage 7's radius bounded as `radius_bound` says, with corners also
// where the points turn most near each of `corners_at` (cornerNear), and the tolerance
// `first_tolerance` where this is a rerun (0: the first fit, whose tolerance is the one
// asked for, raised to the points' noise floor); `budget` ends it: the user's deadline
// (fitStroke's, counted from `start`) and a share of the work, on the stroke's meter.
FitResult fitOnce(const Stroke& stroke, const FitOptions& options, double hook_tolerance, RadiusBound radius_bound,
                  Clock::time_point start, const Budget& budget, const std::vector<Vec2>& corners_at = {},
                  double first_tolerance = 0.0) {
  FitResult r;
  const auto cleanup_start = Clock::now();  // (a rerun's start is the first run's)
  r.cleaned = cleanStroke(stroke, options.cleanup, hook_tolerance);
  if (!r.cleaned.straight)
    for (const Vec2& q : corners_at) addCorner(r.cleaned, cornerNear(r.cleaned, q));
  r.timings.cleanup_ms = msSince(cleanup_start);
  const double diag = r.cleaned.diagonal;
  r.requested_tolerance = options.tolerance > 0.0 ? options.tolerance : options.tolerance_fraction * diag;
  const Noise noise = noiseOf(r.cleaned.points, r.cleaned.corners);
  // A rerun keeps the first fit's tolerance: the noise is the stroke's, and the corners a
  // rerun adds change its reading either way. Its parts are shorter, and read lower (a
  // noisy 8-point stroke's tolerance fell from 0.66 to 0.11, and 6 segments followed its
  // noise); a closed stroke's points start at the first corner, so the differences across
  // the drawn seam count, and read higher (a drawn circle under a cap of 2 extrema: 1.54
  // -> 3.73, its capped curve then measured against a tolerance 2.4 times looser).
  r.tolerance = first_tolerance > 0.0 ? first_tolerance : std::max(r.requested_tolerance, noise.floor);
  r.smoothing = {SolveStatus::kConverged, 0, 0.0, "ok"};
  r.g2 = {SolveStatus::kConverged, 0, 0.0, "ok"};
  FitContext context{options, r.tolerance, noise, diag, r.timings};
  context.radius_bound = radius_bound;
  context.budget = budget;  // (the user's deadline in it: fitStroke's)

  if (r.cleaned.straight) {
    fitStraight(r);
    measureLeftOut(r, stroke);
    r.timings.total_ms = msSince(start);
    return r;
  }

  std::vector<Part> parts = splitAtCorners(r.cleaned);
  const bool polishing = options.polishes();  // (stage 7 makes the chain G2)
  // (stage 7 fits a part's whole chain at once, at a cost growing with the cube of its
  // segments: it spends a budget of segments, the stages 1-6 chains it starts from)
  std::size_t polish_room = options.max_polish_segments, repair_room = options.max_polish_segments;
  // (a refit of a part's chain past stage 7's room strays no further than the warning's
  // bound and that chain)
  auto straysNoFurther = [&](PartFit& refit, PartFit& f, const Part& part) {
    return strayOfFit(refit, part, diag) <= std::max(kStrayWarning * r.tolerance, strayOfFit(f, part, diag));
  };
  // A one-LA-segment fit that misses the tolerance (oneSegmentPart) is kept where the
  // chains of several miss it by more (`others`: their largest deviation or stray).
  auto oneBeats = [&](PartFit& one, const Part& part, double others) {
    return one.g2.usable() && !(others <= r.tolerance) && worstOf(one, part, diag) < others;
  };
  // (a part's chain outside the tolerance by at most kBoundsMiss)
  auto missesByLittle = [&](PartFit& f, const Part& part) {
    const double miss = worstOf(f, part, diag);
    return miss > r.tolerance && miss <= kBoundsMiss * r.tolerance;
  };
  // A part's chain that misses the tolerance, by at most kBoundsMiss, with a joint on the
  // bound of the radius (fitOneBounded fits it again without the bound).
  auto missesOnTheBound = [&](PartFit& f, const Part& part) {
    return missesByLittle(f, part) && largestKappa(f.segments) * r.tolerance > kOnTheBound;
  };
  // One LA segment whose points miss the tolerance, by at most kBoundsMiss, only near its
  // tight end (every point beyond the tolerance within kTightEndReach tolerances of it): a
  // spiral's centre tighter than the bound on the radius lets it follow, which a corner
  // there mends (fitStroke's corner at the farthest point), not a chain. (At 5% of the
  // diagonal a noisy spiral of 2.5 turns spent 0.2 s on chains of 17-29 segments under
  // the bound, before that corner kept the tolerance in 9 ms.)
  auto missesAtTightEnd = [&](PartFit& f, const Part& part) {
    if (f.segments.size() != 1 || !missesByLittle(f, part)) return false;
    const LaSegment& seg = f.segments.front();
    const Vec2 tight_end = std::abs(seg.kappaEnd()) >= std::abs(seg.kappaStart()) ? seg.end() : seg.start();
    const std::vector<double> d = distancesToCurve(curveOf(f.segments), part.points, diag);
    bool beyond = false;  // (a miss by the stray alone is not the points')
    for (std::size_t k = 0; k < d.size(); ++k) {
      if (!(d[k] > r.tolerance)) continue;
      if ((part.points[k] - tight_end).norm() > kTightEndReach * r.tolerance) return false;
      beyond = true;
    }
    return beyond;
  };
  // (`other_starts`: where stage 7's chain misses, stages 2-6's chains as starts too)
  auto fitOneWith = [&](const Part& part, bool other_starts, const FitContext& given) {
    FitContext context = given;
    if (polishing && context.budget.spent()) {
      // Out of time before this part: the paper's G2 chain (stages 2-6, a fraction of
      // stage 7's time) rather than the spline's shot chain, unfitted, which stage 7 would
      // leave (a glyph's second part came out 39 times the tolerance off).
      PartFit paper = fitPart(part, context, false);
      paper.max_dev = maxDeviationOf(paper.segments, part.points, diag);
      return paper;
    }
    // (one LA segment that misses the tolerance, or its split (splitOneSegment: stage 7
    // from it, split where it misses): kept if within the tolerance, else where the
    // chains from stages 2-6 miss it by more; a noisy spiral's chain path went 41
    // tolerances astray where its one segment missed by a tenth)
    std::optional<PartFit> one, split;
    if (polishing) {
      const auto tp = Clock::now();
      const std::int64_t work_before = context.budget.done();
      one = oneSegmentPart(part, context);
      if (one && one->max_dev > r.tolerance) split = splitOneSegment(*one, part, context);
      r.timings.polish_ms += msSince(tp);
      if (one && one->max_dev <= r.tolerance) return std::move(*one);
      if (split && split->max_dev <= r.tolerance) return std::move(*split);
      // (one segment that misses by no more than kBoundsMiss, with a bend on the bound of
      // the radius, where fitOneBounded fits the part again without the bound, or only at
      // its tight end, where fitStroke puts a corner. The points need a tighter bend
      // there, which no chain under the bound follows either, so the chains from stages
      // 2-6 are not tried: on a logarithmic spiral of three turns at a tolerance of 8%
      // they took 180 ms, to end 93 tolerances off.)
      if (one && context.radius_bound == RadiusBound::kBoundThenFree && (missesOnTheBound(*one, part) || missesAtTightEnd(*one, part)))
        return split && worstOf(*split, part, diag) < worstOf(*one, part, diag) ? std::move(*split) : std::move(*one);
      // (the chains from stages 2-6 are worth only what beats it, and get a few times the
      // work it took, as much where it misses by a little: a noisy spiral whose true
      // curve missed the tolerance by a few percent, as its one segment did, spent 1.3 s
      // on chains that missed by more, and spirals drawn from their very centre up to 6 s)
      if (one) {
        const bool near = std::min(one->max_dev, split ? split->max_dev : INFINITY) <= kNearMiss * r.tolerance;
        const std::int64_t share = (near ? kNearMissTimes : kChainPathTimes) * (context.budget.done() - work_before);
        context.budget.work_limit = std::min(context.budget.work_limit, context.budget.done() + share);
      }
    }
    auto orOne = [&](PartFit&& fit) {
      if (split && worstOf(*split, part, diag) < worstOf(fit, part, diag)) fit = std::move(*split);
      return one && oneBeats(*one, part, worstOf(fit, part, diag)) ? std::move(*one) : std::move(fit);
    };
    // (stage 7 on a part's chain, timed; without `choose_segments`, its fit alone)
    auto polish = [&](PartFit& f, bool choose_segments, SplineStart spline_start = SplineStart::kShotThenHalved) {
      const auto tp = Clock::now();
      polishPart(f, part, context, choose_segments, spline_start);
      r.timings.polish_ms += msSince(tp);
    };
    PartFit fit = fitPart(part, context, polishing);
    if (polishing && fit.segments.size() > polish_room) {
      if (!r.over_polish_limit)
        r.warnings.push_back("stage 7 left parts with the chain of stages 1-6: the stroke's chains have more than " +
                             std::to_string(options.max_polish_segments) +
                             " segments in all (FitOptions::max_polish_segments; lafit --max-polish-segments); "
                             "where that chain has gaps, stage 7 fits it without choosing its segments; where an "
                             "open part's still has gaps or bends tighter than the tolerance, in pieces");
      r.over_polish_limit = true;
      // The chain left for stage 7 to complete has gaps where no LA segment fits a
      // piece (straight lines there: kinks where the user drew none). Stage 7's fit of it
      // without its choice of segments (a fraction of the selection's work) makes it G2,
      // in a room of its own as large; past that room, the paper's stages 2-6 cut those
      // pieces, which closes some gaps. (Slow mouse strokes walked pixel by pixel, whose
      // many wiggles fill the room: 26 of 610 came out with kinks of up to 1.1 rad.)
      if (!fit.g2.usable()) {
        if (fit.segments.size() <= repair_room) {
          repair_room -= fit.segments.size();
          polish(fit, false);
        } else {
          if (PartFit paper = fitPart(part, context, false); paper.g2.usable()) fit = std::move(paper);
          // A closed part's chain that still has gaps: that fit past the room (stage 7 in
          // pieces fits open parts only), kept where it is G2 and strays no further. A
          // walked closed stroke of 59 segments: kinked, 1.3 tolerances off, in 21 ms; G2,
          // 1.9 off, in 1.1 s.
          if (part.closed && !fit.g2.usable()) {
            PartFit whole = fit;
            polish(whole, false);
            if (whole.g2.usable() && straysNoFurther(whole, fit, part)) fit = std::move(whole);
          }
        }
      }
      // Where that leaves gaps, or the chain bends tighter than the tolerance, stage 7 in
      // pieces (an open part's, at a cost that grows with its pieces): kept where it
      // strays no further and is no further from the points, or within twice the
      // tolerance of them.
      if (!part.closed && (!fit.g2.usable() || !keepsTheBound(fit.segments, context))) {
        const auto tp = Clock::now();
        PartFit pieces = fit;
        if (polishInPieces(pieces, part, context)) {
          const double worst_pieces = worstOf(pieces, part, diag), worst = worstOf(fit, part, diag);
          // (the pieces are G2: over a kinked chain, G2 comes first, as among a part's starts)
          if (straysNoFurther(pieces, fit, part) &&
              (!fit.g2.usable() || worst_pieces <= worst || worst_pieces <= kAstrayFit * r.tolerance))
            fit = std::move(pieces);
        }
        r.timings.polish_ms += msSince(tp);
      }
      return fit;
    }
    if (polishing) polish_room -= fit.segments.size();
    if (!polishing) {
      // (the paper's chain over the cap on extrema: the cap's merges, by stage 7's fit)
      if (options.g2 != G2Method::kOff && overCap(fit.segments, part.closed, context)) polishPart(fit, part, context, false);
      return fit;
    }
    // (the spline's halved spans only after the paper's chain, below: where the shot
    // spans end astray, that is usually closer, and it costs a fraction of them)
    const PartFit unpolished = other_starts ? fit : PartFit{};
    polish(fit, true, other_starts ? SplineStart::kShot : SplineStart::kShotThenHalved);
    // Where that leaves a gap, a miss or a stray, other starts: the better result stays
    // (G2 first, then the larger of the deviation from the part's points and the stray).
    auto measure = [&](PartFit& f) { return worstOf(f, part, diag); };
    auto misses = [&] { return !fit.g2.usable() || !(measure(fit) <= r.tolerance); };
    auto consider = [&](PartFit other, SplineStart spline_start = SplineStart::kShotThenHalved) {
      polish(other, true, spline_start);
      // (G2 first, then the cap on extrema, then the bound on the radius where it is
      // promised, then the deviation: stage 6's chain, unpolished, can be closer and bend
      // 21 times tighter than the tolerance)
      const bool other_kept = !overCap(other.segments, part.closed, context);
      const bool kept = !overCap(fit.segments, part.closed, context);
      const bool other_bounded = keepsTheBound(other.segments, context);
      const bool bounded = keepsTheBound(fit.segments, context);
      const bool better = other.g2.usable() != fit.g2.usable() ? other.g2.usable()
                          : other_kept != kept                 ? other_kept
                          : other_bounded != bounded           ? other_bounded
                                                               : measure(other) < measure(fit);
      if (better) fit = std::move(other);
    };
    if (!other_starts) return orOne(std::move(fit));
    // Stages 2-6 as the paper has them (cutting pieces that stray or have no LA
    // segment): a chain close to the points. (Also out of time: stage 7's chain may have
    // been cut short far from the points, and the paper's costs a fraction of it.)
    if (misses()) consider(fitPart(part, context, false));
    if (misses() && !context.budget.spent()) consider(unpolished, SplineStart::kHalved);
    // Pixel-quantized strokes: a spline through the stairs has an extremum at every
    // step and the chain from it strays; stages 2-6 on the points with their stairs
    // smoothed (stage 7 still fits the points themselves).
    if (misses() && noise.on_grid && !context.budget.spent()) {
      Part smoothed = part;
      smoothed.points = withoutStairs(part.points, part.closed);
      consider(fitPart(smoothed, context, true));
    }
    // A short noisy side between corners: the chains can all loop away from it (6 points,
    // 23 units astray, where the tolerance is 5), and one segment between its ends is
    // closer.
    if (misses())
      if (std::optional<PartFit> arc = oneArcPart(part, context, "one LA segment, where the chains miss")) consider(std::move(*arc));
    return orOne(std::move(fit));
  };
  // A part whose chain misses the tolerance with a joint on the bound of the radius (the
  // points need a bend tighter than it that the clean-up took for no corner): fitted
  // again without the bound, kept if closer. (Part by part: the other parts keep it, and
  // the merges and the fit across corners below see a part that keeps the tolerance.)
  auto fitOneBounded = [&](const Part& part, bool other_starts) {
    const std::size_t room = polish_room;
    PartFit fit = fitOneWith(part, other_starts, context);
    if (!polishing || context.radius_bound != RadiusBound::kBoundThenFree || context.budget.spent() || r.over_polish_limit) return fit;
    if (!missesOnTheBound(fit, part)) return fit;
    const auto worst = [&](PartFit& f) { return worstOf(f, part, diag); };
    const std::size_t bounded_room = polish_room;
    polish_room = room;
    FitContext unbounded = context;
    unbounded.radius_bound = RadiusBound::kFree;
    PartFit other = fitOneWith(part, other_starts, unbounded);
    if (other.g2.usable() && worst(other) < worst(fit)) return other;
    polish_room = bounded_room;
    return fit;
  };
  // (the cap on extrema wins, whichever start or stage the part's chain came from)
  auto fitOne = [&](const Part& part, bool other_starts) {
    PartFit fit = fitOneBounded(part, other_starts);
    if (options.g2 != G2Method::kOff) keepTheCap(fit, part, context);
    return fit;
  };
  std::vector<PartFit> fits;
  // (the parts' chains as one curve, each part's first segment after its corner)
  auto curveOfParts = [&] {
    Curve curve;
    curve.closed = r.cleaned.closed;
    for (std::size_t k = 0; k < parts.size(); ++k)
      for (std::size_t i = 0; i < fits[k].segments.size(); ++i)
        curve.pieces.push_back({fits[k].segments[i], i == 0 && parts[k].starts_at_corner});
    return curve;
  };
  // An open stroke that one LA segment, or its split, follows within the tolerance is
  // that chain, whatever corners the clean-up read in it (fewest extrema, then fewest
  // segments: one segment comes first; the tight inner turns of a spiral pass for
  // corners). One that misses it is kept for the end, in case the parts miss it by more
  // (below). (Not in a fit again with corners at the first fit's tight bends: the first
  // fit tried the whole stroke as one segment under the same bound.)
  std::optional<PartFit> one;
  Part whole;  // (the whole stroke as one part: only where it is tried so)
  if (polishing && parts.size() > 1 && !r.cleaned.closed && !context.budget.spent() && corners_at.empty()) {
    const auto tp = Clock::now();
    whole.points = r.cleaned.points;
    one = oneSegmentPart(whole, context);
    if (one && one->max_dev > r.tolerance)
      if (auto split = splitOneSegment(*one, whole, context); split && split->max_dev <= r.tolerance) one = std::move(split);
    r.timings.polish_ms += msSince(tp);
    if (one && one->max_dev <= r.tolerance) {
      parts = {std::move(whole)};
      fits.push_back(std::move(*one));
      r.cleaned.corners.clear();
      one.reset();
    }
  }
  if (fits.empty())
    for (const Part& part : parts) fits.push_back(fitOne(part, true));
  // A corner is the clean-up's reading of the stroke, and a tight bend can pass for one.
  // Where a part beside a corner misses the tolerance and the two parts fitted as one
  // smooth part keep it, the corner goes. Not where each part that misses has a chain
  // the cap on extrema shaped (PartFit::capped): that miss is the cap's, and one smooth
  // part has the cap of one (under caps of 0, 1 and 2 on the shared data, --variants=2,
  // none of 346 such merges was kept; without them the capped fits take 12-16% less
  // time). (The corner after part k: corners[k] of an open stroke, corners[k + 1] of a
  // closed one, whose corners[0] is its start; a closed stroke's only corner joins its
  // one part to itself.)
  const bool closed = r.cleaned.closed;
  // (a closed stroke's one part has a seam corner only if the clean-up found corners:
  // without, its points do not end with the start again)
  const bool seam_corner = closed && parts.size() == 1 && !r.cleaned.corners.empty();
  auto withinOrCapped = [&](const PartFit& f) { return f.max_dev <= r.tolerance || f.capped; };
  for (std::size_t k = 0; polishing && (k + 1 < parts.size() || (seam_corner && k == 0)) && !context.budget.spent();) {
    const bool seam = k + 1 == parts.size();
    const PartFit& next = seam ? fits[0] : fits[k + 1];
    if (withinOrCapped(fits[k]) && withinOrCapped(next)) {
      ++k;
      continue;
    }
    Part merged = parts[k];
    if (seam) {
      merged.points.pop_back();  // the corner again
      merged.closed = true;
      merged.starts_at_corner = merged.ends_at_corner = false;
    } else {
      merged.points.insert(merged.points.end(), parts[k + 1].points.begin() + 1, parts[k + 1].points.end());
      merged.ends_at_corner = parts[k + 1].ends_at_corner;
    }
    // (a merge is tried from stage 7's own start only: the other starts rescue a part
    // that misses, which the two parts apart do not need)
    // (nor where the two as one bend tighter than the tolerance: that is a corner; nor
    // where they stray: a noisy stroke's two parts as one looped 29 tolerances away)
    PartFit smooth = fitOne(merged, false);
    if (!smooth.g2.usable() || !(worstOf(smooth, merged, diag) <= r.tolerance) || bendsTighterThan(smooth.segments, r.tolerance)) {
      ++k;
      continue;
    }
    parts[k] = std::move(merged);
    fits[k] = std::move(smooth);
    if (seam) {
      r.cleaned.corners.clear();
      break;
    }
    parts.erase(parts.begin() + static_cast<std::ptrdiff_t>(k) + 1);
    fits.erase(fits.begin() + static_cast<std::ptrdiff_t>(k) + 1);
    r.cleaned.corners.erase(r.cleaned.corners.begin() + static_cast<std::ptrdiff_t>(closed ? k + 1 : k));
  }
  joinAtCorners(fits, parts, context.g2());
  std::size_t segments = 0;
  for (const PartFit& fit : fits) segments += fit.segments.size();
  if (polishing && !context.budget.spent() && !r.over_polish_limit && segments <= options.max_polish_segments) {
    const auto tp = Clock::now();
    if (fitAcrossCorners(fits, parts, closed, context))
      joinAtCorners(fits, parts, context.g2());  // (a closed chain's seam, to rounding)
    r.timings.polish_ms += msSince(tp);
  }
  // Fewest extrema first (the objective, pipeline.h): a part whose chain has several
  // segments and a curvature extremum gives way to one LA segment between the chain's
  // ends (where the fit across corners put its corners), where that keeps the
  // selection's tolerance and the bound. The selection merges only at weak extrema, and a short noisy side's
  // chain has strong ones: 5 points came out as 4 segments through them. (After the fit
  // across corners, which moves the corners with the sides' freedom: done per part
  // before it, a drawn star's side as one segment left its neighbour outside.)
  if (polishing && !context.budget.spent()) {
    const double within = stage7Selection(context).tolerance;
    // (part k with its ends at its chain's corners)
    auto betweenCorners = [&](std::size_t k) {
      Part between = parts[k];
      if (between.starts_at_corner) between.points.front() = fits[k].segments.front().start();
      if (between.ends_at_corner) between.points.back() = fits[k].segments.back().end();
      return between;
    };
    for (std::size_t k = 0; k < parts.size(); ++k) {
      PartFit& fit = fits[k];
      if (parts[k].closed || fit.segments.size() < 2 || !overExtremaCap(curveOf(fit.segments, false), diag, 0)) continue;
      std::optional<PartFit> arc =
          oneArcPart(betweenCorners(k), context, "one LA segment, for fewer extrema", kArcStartMiss * r.tolerance);
      if (arc && arc->g2.usable() && worstOf(*arc, parts[k], diag) <= within && !bendsTighterThan(arc->segments, r.tolerance))
        fit = std::move(*arc);
    }
    // Then each open part's chain gives way to the circular arc between its ends that
    // passes closest to its points, where that keeps the selection's tolerance and the
    // bound, and the curve's curvature reverses no more often (QualityFigures::
    // extrema_dense). An arc has no trend: a drawn polygon's sides, each an LA segment
    // with a slight one, reversed it at every other corner. Each arc is taken where it
    // adds no reversal (one that removes none can let the next one remove some); all are
    // kept only where together they remove a reversal or a segment.
    auto reversals = [&] { return curvatureReversals(curveOfParts(), diag); };
    const int before = reversals();
    int now = before;
    bool fewer_segments = false;
    std::vector<std::pair<std::size_t, PartFit>> replaced;  // (each arc's part and the chain it replaced)
    for (std::size_t k = 0; k < parts.size(); ++k) {
      PartFit& fit = fits[k];
      if (parts[k].closed || (fit.segments.size() == 1 && fit.segments[0].isCircular())) continue;  // (a line or an arc)
      std::optional<PartFit> arc = closestArcPart(betweenCorners(k), context, "a circular arc, for fewer extrema", within);
      if (!arc || !(worstOf(*arc, parts[k], diag) <= within) || bendsTighterThan(arc->segments, r.tolerance)) continue;
      std::swap(fit, *arc);
      const int with_arc = reversals();
      if (with_arc > now) {
        std::swap(fit, *arc);
        continue;
      }
      now = with_arc;
      fewer_segments = fewer_segments || arc->segments.size() > 1;
      replaced.emplace_back(k, std::move(*arc));
    }
    if (now == before && !fewer_segments)
      for (auto& [k, chain] : replaced) fits[k] = std::move(chain);
  }
  // The stroke's one segment that missed the tolerance, where the parts miss it by more
  // (their deviation or stray), as a part's near miss is kept (fitOneWith's orOne): a
  // noisy spiral of four turns, whose tight inner turns the clean-up read as two corners,
  // came out of its parts 17 tolerances astray, where its one segment missed by the chain
  // fit's own measure of its distances only (0.91 of the tolerance by the quality figures').
  if (one) {
    double parts_worst = 0.0;
    for (std::size_t k = 0; k < parts.size(); ++k) parts_worst = std::max(parts_worst, worstOf(fits[k], parts[k], diag));
    if (oneBeats(*one, whole, parts_worst)) {
      parts = {std::move(whole)};
      fits = {std::move(*one)};
      r.cleaned.corners.clear();
    }
  }
  r.curve = curveOfParts();
  for (std::size_t k = 0; k < parts.size(); ++k) {
    PartFit& fit = fits[k];
    r.warnings.insert(r.warnings.end(), fit.warnings.begin(), fit.warnings.end());
    for (std::size_t i = 0; i < fit.segments.size(); ++i) {
      fit.reports[i].part = static_cast<int>(k);
      fit.reports[i].spline = fit.spline ? static_cast<int>(r.splines.size()) : -1;
      r.pieces.push_back(fit.reports[i]);
    }
    if (fit.spline) r.splines.push_back(*fit.spline);
    r.splits.push_back(fit.splits);
    if (!fit.smoothing.usable()) r.smoothing = fit.smoothing;
    if (!fit.g2.usable()) r.g2 = fit.g2;
  }
  const auto tq = Clock::now();
  r.quality = measureQuality(r.curve, r.cleaned.points);
  measureLeftOut(r, stroke);
  r.timings.quality_ms = msSince(tq);
  // Said from the measured figures, whichever stage or start the curve came from.
  double stray = 0.0;  // (fitOne measured most parts already)
  for (std::size_t k = 0; k < parts.size(); ++k) stray = std::max(stray, strayOfFit(fits[k], parts[k], diag));
  r.stray = stray;
  if (stray > kStrayWarning * r.tolerance)
    r.warnings.push_back("the curve strays up to " + std::to_string(stray) + " from the stroke, where no point is");
  const int cap = options.segmentation.max_extrema, most = r.quality.max_extrema_per_part;
  if (cap >= 0 && most > cap)
    r.warnings.push_back("a smooth part keeps " + std::to_string(most) + " curvature extrema, more than the cap of " +
                         std::to_string(cap) + ": no merge of its segments brings it lower");
  if (r.quality.max_dev > r.tolerance)
    r.warnings.push_back("the curve misses the tolerance: it passes up to " + std::to_string(r.quality.max_dev) +
                         " from the points, the tolerance is " + std::to_string(r.tolerance) +
                         (cap >= 0 ? " (the cap of " + std::to_string(cap) + " extrema per smooth part comes first)" : ""));
  // (stage 7 bounds the radius: a curve that still bends tighter, from a chain stage 7
  // could not replace, breaks DESIGN.md section 6's promise, and says so)
  if (polishing && bendsTighterThanTolerance(r))
    r.warnings.push_back("the curve bends tighter than the tolerance: its tightest radius is " +
                         std::to_string(r.quality.min_radius) + ", the tolerance is " + std::to_string(r.tolerance));
  r.out_of_time = context.budget.spent();  // (fitStroke says so: the budget may be a refit's share)
  r.timings.total_ms = msSince(start);
  return r;
}

}  // namespace

FitResult fitStroke(const Stroke& stroke, const FitOptions& options) {
  const auto start = Clock::now();
  if (stroke.samples.size() > options.max_points)
    throw StrokeError("the stroke has " + std::to_string(stroke.samples.size()) + " samples, more than " +
                      std::to_string(options.max_points) + " (FitOptions::max_points; lafit --max-points raises it)");
  const double hook_tolerance = hookTolerance(stroke, options);
  WorkMeter work;
  // (the user's time budget, whichever fit spends it: the refits' shares keep its deadline)
  Budget budget{.meter = &work};
  if (options.time_budget_ms > 0.0)
    budget.deadline = start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double, std::milli>(options.time_budget_ms));
  FitResult r = fitOnce(stroke, options, hook_tolerance, RadiusBound::kBoundThenFree, start, budget);
  const double first_tolerance = r.tolerance;
  // A bend the points need tighter than the tolerance is a corner, which the clean-up
  // and the corners stage 7 adds do not always find: where the bound on the radius
  // costs the tolerance, the fit without it, if that keeps the tolerance. (fitOnce does
  // so part by part; this is for what only the whole stroke shows: a part fitted after
  // a merge or across corners, a miss beyond kBoundsMiss, a stray.)
  const bool polishing = options.polishes();
  // (missed: a point outside the tolerance, or the curve further than twice it, and a
  // sample step, from the stroke's polyline: a loop, or a corner run past its tip)
  auto misses = [](const FitResult& f) {
    const double allowed = kStrayWarning * f.tolerance + medianStep(f.cleaned.points);
    return f.quality.max_dev > f.tolerance || strayBeyond(f.curve, f.cleaned.points, f.quality.diagonal, allowed) > 0.0;
  };
  // (a curve bending tighter than the tolerance that another fit may mend; also one past
  // stage 7's room, whose parts' chains keep the bound only where stage 7 or its pieces
  // fitted them: slow mouse strokes walked pixel by pixel bent up to 3,500 times tighter
  // than the tolerance, in a part whose chain the fit without the bound had made)
  auto mendable = [&](const FitResult& f) {
    return polishing && !f.cleaned.straight && !f.out_of_time && bendsTighterThanTolerance(f);
  };
  // The stroke fitted again with corners at `bends` as well as at `earlier` ones, with
  // the bound, in about the work the fit took so far, and the first fit's tolerance
  // (fitOnce); nullopt where no corner can go there.
  auto corneredAt = [&](const FitResult& from, const std::vector<Vec2>& earlier,
                        const std::vector<Vec2>& bends) -> std::optional<FitResult> {
    if (bends.empty()) return std::nullopt;
    CleanStroke with = from.cleaned;  // (where no corner can go, no fit is tried)
    if (std::none_of(bends.begin(), bends.end(), [&](const Vec2& q) { return addCorner(with, cornerNear(with, q)); }))
      return std::nullopt;
    std::vector<Vec2> at = earlier;
    at.insert(at.end(), bends.begin(), bends.end());
    Budget share = budget;
    share.work_limit = 2 * work.done;
    return fitOnce(stroke, options, hook_tolerance, RadiusBound::kBoundThenFree, start, share, at, first_tolerance);
  };
  // (a refit that strays further than the warning's bound and than the curve it would
  // replace: a loop where the stroke has none is no mend for a tight bend)
  auto strays = [&](const FitResult& f) { return f.stray > std::max(kStrayWarning * f.tolerance, r.stray); };
  // (a refit that mends a tight bend: in time, not straying, and G2 where the curve is
  // kinked, else bending less; a refit with a kink replaces only a curve with one: past
  // stage 7's room, a walked stroke's kinked curve 3.3 tolerances off stayed so, where the
  // refit was 1.2 off and the next one G2)
  auto mendsTheKink = [&](const FitResult& f) { return f.g2.usable() && !r.g2.usable(); };
  auto mendsTheBend = [&](const FitResult& f) {
    return !f.out_of_time && (f.g2.usable() || !r.g2.usable()) && !strays(f) &&
           (mendsTheKink(f) || f.quality.max_abs_kappa < r.quality.max_abs_kappa);
  };
  std::vector<Vec2> corners_at;
  // (a miss by the stray alone is fitted again only where some joint is on the bound, as
  // every miss was before: measuring the stray is a pass over the curve, which for every
  // stroke cost about 5% of the data's time)
  const bool bounded = r.quality.max_abs_kappa * r.tolerance > kOnTheBound;
  if (polishing && (bounded || r.quality.max_dev > r.tolerance) && !r.cleaned.straight && !r.out_of_time &&
      !r.over_polish_limit && misses(r)) {
    // The bends on the bound made corners first: where that fit keeps the tolerance and
    // bends no tighter than it, the fit without the bound is not needed. It would bend
    // tighter than the tolerance where the bound held, and the rounds below would make
    // those bends corners, a whole fit later (the shared data's slowest fit, a drawn
    // star: 224 -> 176 ms, the same curve). A miss with no bend on the bound, or whose
    // corners there do not mend it, has its corner tried at the point farthest from the
    // curve, then the fit without the bound: a part can miss with one segment that bends
    // nowhere near the bound, kept over chains that bend tighter or stray (12 noisy
    // samples: 1.25 tolerances off, where a corner at the free fit's tight bend keeps the
    // tolerance), and a bend on the bound can be the fit's answer to a miss elsewhere (a
    // noisy crossbar's chain bent on the bound beside its end hook, 2.3 tolerances off at
    // a kink in its middle, where a corner keeps the tolerance, 0.20 off).
    // (a refit that ran out of its share of the work, not of the user's time, is kept as
    // one that did not where its chain, the best it found, keeps the tolerance, G2 and the
    // bound: a noisy spiral whose one segment missed the tolerance by 2% at its centre
    // came within it (0.97, 8 segments) with a corner there, past its share)
    auto mends = [&](const std::optional<FitResult>& f) {
      const bool in_users_time = f && (!f->out_of_time || !budget.spent());
      return in_users_time && f->g2.usable() && !misses(*f) && !bendsTighterThanTolerance(*f);
    };
    // (each refit judged once: misses() measures its stray, a pass over the curve)
    std::vector<Vec2> at = tightBends(r, kOnTheBound);
    std::optional<FitResult> cornered = corneredAt(r, {}, at);
    bool mended = mends(cornered);
    if (!mended && r.quality.max_dev > r.tolerance) {
      at = {farthestPoint(r)};
      cornered = corneredAt(r, {}, at);
      mended = mends(cornered);
      // (where that misses too, with a corner at its own farthest point as well: a noisy
      // crossbar's farthest point was beside the kink that needed the corner, whose fit
      // with both kept the tolerance, 0.53 off. Not under a cap on extrema, whose misses
      // are the cap's: a drawn ellipse capped at 2 came back as 5 segments between two
      // such corners, where it is the circle closest to its points.)
      if (options.segmentation.max_extrema < 0 && !mended && cornered && cornered->quality.max_dev > cornered->tolerance) {
        const Vec2 next = farthestPoint(*cornered);
        if (next != at.front()) {
          at.push_back(next);
          cornered = corneredAt(r, {}, at);
          mended = mends(cornered);
        }
      }
    }
    if (mended) {
      r = std::move(*cornered);
      r.out_of_time = false;
      corners_at = at;
    } else if (options.segmentation.max_extrema < 0 || r.quality.max_dev <= kCappedMiss * r.tolerance) {
      FitResult free = fitOnce(stroke, options, hook_tolerance, RadiusBound::kFree, start, budget);
      if (!misses(free)) r = std::move(free);
    }
  }
  // Where the curve still bends tighter than the tolerance (the clean-up saw no corner
  // there, and the bound cost the tolerance), a corner at the bend, and the stroke fitted
  // again with the bound, in about the work the fit took so far: kept where it bends less
  // tightly (mendsTheBend) and keeps the tolerance (or misses it by no more, or by
  // kCorneredMiss).
  for (int round = 0; round < kTightBendRounds && mendable(r); ++round) {
    const std::vector<Vec2> more = tightBends(r);
    std::optional<FitResult> cornered = corneredAt(r, corners_at, more);
    if (!cornered) break;
    corners_at.insert(corners_at.end(), more.begin(), more.end());
    if (!mendsTheBend(*cornered) || (!mendsTheKink(*cornered) && cornered->quality.max_dev >
                                                                       std::max(kCorneredMiss * cornered->tolerance, r.quality.max_dev)))
      break;
    r = std::move(*cornered);
  }
  // Where it still does (a part that missed the tolerance on the bound was fitted again
  // without it, as above, also after its tight bends became corners: a capped stroke),
  // the stroke with those corners and the bound kept everywhere: no bend tighter than
  // the tolerance comes first, as the cap on extrema does, and the warnings say what it
  // costs. Also where no corner could go (a bend within two samples of a corner: a walked
  // star's side curled into its tip with a radius of a third of the tolerance).
  if (mendable(r)) {
    FitResult strict =
        fitOnce(stroke, options, hook_tolerance, RadiusBound::kStrict, start, budget, corners_at, first_tolerance);
    if (mendsTheBend(strict)) r = std::move(strict);
  }
  if (r.out_of_time)
    r.warnings.push_back("the time budget of " + std::to_string(options.time_budget_ms) + " ms ran out: " +
                         (r.g2.usable() ? "the best G2 chain found by then"
                                        : "the chain of stages 1-6 as it stood, not G2 (no G2 chain was found by then)"));
  r.timings.total_ms = msSince(start);
  return r;
}


}  // namespace la
