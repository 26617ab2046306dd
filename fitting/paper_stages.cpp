#include "fitting/paper_stages.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "core/three_point_segment.h"
#include "fitting/quality.h"

namespace la {
namespace {

// LCG samples per piece, and the fraction dropped at each end: next to a curvature
// extremum d kappa/ds -> 0 and log(rho |ds/drho|) runs off to infinity, which would
// dominate the regression (seed 003 fits the LCG "of the segment"; we fit its interior).
constexpr int kLcgSamples = 48;
constexpr double kLcgTrim = 0.1;
// Alpha used when the LCG says nothing (a piece of constant curvature: any alpha gives
// the same near-circular segment), and the alpha with the widest reachable range,
// towards which an infeasible alpha is moved.
constexpr double kDefaultAlpha = -1.0;
constexpr double kWidestAlpha = 0.5;
constexpr int kAlphaBisections = 12;
constexpr int kMaxAlphaRelaxations = 3;
// A piece turning less than this (radians) counts as straight: no turning direction.
constexpr double kStraightTurning = 1e-9;
// Alpha by least squares: scan points over [min_alpha, max_alpha], golden-section steps
// after (0.618^6 of two scan steps: ~0.17 in alpha), at most this many points per piece
// and samples of the segment for the distances.
constexpr int kAlphaScan = 5;
constexpr int kAlphaRefinements = 6;
constexpr std::size_t kAlphaPoints = 24;
constexpr std::size_t kMinPointsForAlphaFit = 24;
constexpr int kDeviationSamples = 24;
// Where stage 7 follows, a spline that misses by more than this many tolerances with its
// ends free is fitted again through the stroke's end points (see fitPart).
constexpr double kFarSplineMiss = 3.0;
// Passes that split pieces which fail (no LA segment) or stray from the points, or merge
// them (see below); halving a piece without an LA segment is tried in the first half of
// them, and only on pieces holding this many points.
constexpr int kMaxRefinePasses = 16;
constexpr std::size_t kMinPointsToHalve = 2;
// A closed part keeps at least this many pieces (each turns less than pi).
constexpr std::size_t kMinClosedPieces = 3;
// Resolution of the deviations that decide those splits (relative to the diagonal;
// 500 times below the default tolerance; the reported figures use 1e-6).
constexpr double kRefineResolution = 1e-5;
// The spline is fitted to this fraction of the tolerance where the points are clean
// (its curvature feeds the segmentation and alpha), unless stage 7 follows.
constexpr double kSplineToleranceFraction = 0.2;

// The alpha nearest `wanted` for which the triangle is reachable (bisection on
// reachability between `wanted` and the widest-range alpha); NaN if none is.
double nearestFeasibleAlpha(double wanted, const Vec2& q0, const Vec2& q1, const Vec2& q2) {
  ThreePointOptions quick;
  quick.report_reachable = false;
  auto ok = [&](double a) { return solveThreePointSegment(a, q0, q1, q2, quick).report.usable(); };
  if (ok(wanted)) return wanted;
  double good = NAN;
  for (double a : {kWidestAlpha, 0.0, 0.9}) {
    if (ok(a)) {
      good = a;
      break;
    }
  }
  if (std::isnan(good)) return NAN;
  double bad = wanted;
  for (int k = 0; k < kAlphaBisections; ++k) {
    const double mid = 0.5 * (good + bad);
    (ok(mid) ? good : bad) = mid;
  }
  return good;
}

// The points of each piece, by their spline parameter (a closed spline's last piece
// runs through the seam: its t1 exceeds tMax by up to a period).
std::vector<std::vector<std::size_t>> pointsOfPieces(const std::vector<PieceReport>& pieces,
                                                     const SmoothingResult& smooth, double period) {
  std::vector<std::vector<std::size_t>> members(pieces.size());
  for (std::size_t k = 0; k < smooth.parameters.size(); ++k) {
    const double t = smooth.parameters[k];
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const double tt = (t < pieces[i].t0 && smooth.spline.isPeriodic()) ? t + period : t;
      if (tt >= pieces[i].t0 && tt <= pieces[i].t1) {
        members[i].push_back(k);
        break;
      }
    }
  }
  return members;
}

// Largest distance from the points of each piece to its LA segment; with no segments,
// to the spline itself (the smoothing's own error there).
std::vector<double> pieceDeviations(const std::vector<LaSegment>& segments,
                                    const std::vector<std::vector<std::size_t>>& members,
                                    const std::vector<Vec2>& points, const SmoothingResult& smooth, double diag) {
  std::vector<double> out(members.size(), 0.0);
  for (std::size_t i = 0; i < members.size(); ++i) {
    if (segments.empty()) {
      for (std::size_t k : members[i])
        out[i] = std::max(out[i], (smooth.spline.point(smooth.parameters[k]) - points[k]).norm());
      continue;
    }
    std::vector<Vec2> mine;
    for (std::size_t k : members[i]) mine.push_back(points[k]);
    if (mine.empty()) continue;
    Curve one;
    one.pieces.push_back({segments[i], false});
    for (double d : distancesToCurve(one, mine, diag, kRefineResolution)) out[i] = std::max(out[i], d);
  }
  return out;
}

// An inflection end needs the curve to bend late (chord angle at the inflection end
// below half the turning); a nearly straight piece from a noisy spline may miss that by
// a hair. Such a piece gets the tangent at its other end turned just enough (the G2
// solve moves that joint anyway).
void openInflectionTriangles(Chain& chain) {
  constexpr double kMargin = 1.1;  // the chord angle ends at 1/kMargin of half the turning
  const std::size_t n = chain.size();
  auto set = [&](std::size_t joint, double value) {
    const double delta = value - chain.angles[joint];
    chain.angles[joint] = value;
    if (chain.closed && (joint == 0 || joint == n)) chain.angles[joint == 0 ? n : 0] += delta;
  };
  for (std::size_t i = 0; i < n; ++i) {
    const PieceKind kind = chain.pieces[i].kind;
    if (kind == PieceKind::kThreePoint || solvePiece(chain, i).report.usable()) continue;
    const Vec2 chord = chain.joints[i + 1] - chain.joints[i];
    const double turning = chain.angles[i + 1] - chain.angles[i];
    const double sign = turning < 0 ? -1.0 : 1.0;
    if (kind == PieceKind::kInflectionStart) {
      const double phi = std::abs(signedAngle(unitVector(chain.angles[i]), chord));
      if (2.0 * kMargin * phi < std::numbers::pi) set(i + 1, chain.angles[i] + sign * std::max(std::abs(turning), 2.0 * kMargin * phi));
    } else {
      const double phi = std::abs(signedAngle(chord, unitVector(chain.angles[i + 1])));
      if (2.0 * kMargin * phi < std::numbers::pi) set(i, chain.angles[i + 1] - sign * std::max(std::abs(turning), 2.0 * kMargin * phi));
    }
  }
}

// Sum of squared distances from `points` to the segment (a polyline of it).
double squaredDeviation(const LaSegment& seg, const std::vector<Vec2>& points) {
  const CurveSamples smp = seg.sample(kDeviationSamples);
  double sum = 0.0;
  for (const Vec2& p : points) {
    double best = INFINITY;
    for (std::size_t e = 0; e + 1 < smp.point.size(); ++e) best = std::min(best, distanceToSegment(p, smp.point[e], smp.point[e + 1]));
    sum += best * best;
  }
  return sum;
}

// The alpha whose LA segment through the triangle lies closest to the points (least
// squares). The LCG of a cubic spline is a poor witness of alpha (its curvature
// derivative jumps at every knot), so the LCG slope only starts this search: a coarse
// scan of [min_alpha, max_alpha], then golden-section refinement around the best.
double fitAlphaToPoints(double start, const Vec2& q0, const Vec2& q1, const Vec2& q2, const std::vector<Vec2>& points,
                        double min_alpha, double max_alpha) {
  ThreePointOptions quick;
  quick.report_reachable = false;
  auto cost = [&](double a) {
    const SegmentSolve s = solveThreePointSegment(a, q0, q1, q2, quick);
    return s.report.usable() ? squaredDeviation(*s.segment, points) : INFINITY;
  };
  double best = start, best_cost = cost(start);
  for (int k = 0; k < kAlphaScan; ++k) {
    const double a = min_alpha + (max_alpha - min_alpha) * k / (kAlphaScan - 1);
    const double c = cost(a);
    if (c < best_cost) best = a, best_cost = c;
  }
  if (!std::isfinite(best_cost)) return start;
  const double step = (max_alpha - min_alpha) / (kAlphaScan - 1);
  double lo = std::max(min_alpha, best - step), hi = std::min(max_alpha, best + step);
  constexpr double kGolden = 0.6180339887498949;
  double x1 = hi - kGolden * (hi - lo), x2 = lo + kGolden * (hi - lo);
  double c1 = cost(x1), c2 = cost(x2);
  for (int k = 0; k < kAlphaRefinements; ++k) {
    if (c1 <= c2) {
      hi = x2, x2 = x1, c2 = c1;
      x1 = hi - kGolden * (hi - lo), c1 = cost(x1);
    } else {
      lo = x1, x1 = x2, c1 = c2;
      x2 = lo + kGolden * (hi - lo), c2 = cost(x2);
    }
  }
  const double refined = c1 <= c2 ? x1 : x2;
  return std::min(c1, c2) <= best_cost ? refined : best;
}

}  // namespace

// LCG slope of the spline between t0 and t1 (analytic curvature and its derivative).
std::vector<LcgPoint> lcgPointsOfPiece(const CubicBSpline& s, double t0, double t1) {
  std::vector<double> kappa, dkappa;
  const int first = static_cast<int>(kLcgTrim * kLcgSamples), last = kLcgSamples - first;
  for (int k = first; k < last; ++k) {
    double k_t, dk_t;
    s.curvatureAndSlope(t0 + (t1 - t0) * (k + 0.5) / kLcgSamples, k_t, dk_t);
    kappa.push_back(k_t);
    dkappa.push_back(dk_t);
  }
  return lcgFromDerivative(kappa, dkappa);
}

LcgFit lcgOfPiece(const CubicBSpline& s, double t0, double t1) { return fitLcg(lcgPointsOfPiece(s, t0, t1)); }


// Where to cut a piece that failed: at the spline's curvature zero nearest its middle
// when it has one (an S-shaped piece whose inflection was dropped as noise: the cut
// makes it two inflection pieces), else at its middle.
SplitPoint halvingPoint(const CubicBSpline& spline, double t0, double t1) {
  constexpr int kSamples = 32;
  const double mid = 0.5 * (t0 + t1);
  double best = NAN;
  double prev_t = t0, prev_k = spline.curvature(spline.wrap(t0));
  for (int k = 1; k <= kSamples; ++k) {
    const double t = t0 + (t1 - t0) * k / kSamples, kappa = spline.curvature(spline.wrap(t));
    if ((kappa < 0.0) != (prev_k < 0.0)) {
      double a = prev_t, b = t, ka = prev_k;
      for (int it = 0; it < 40; ++it) {  // bisection on the sign of the curvature
        const double m = 0.5 * (a + b), km = spline.curvature(spline.wrap(m));
        if ((km < 0.0) == (ka < 0.0)) a = m, ka = km;
        else b = m;
      }
      const double z = 0.5 * (a + b);
      const bool inside = std::abs(z - mid) < 0.45 * (t1 - t0);  // not on top of an existing split
      if (inside && (std::isnan(best) || std::abs(z - mid) < std::abs(best - mid))) best = z;
    }
    prev_t = t;
    prev_k = kappa;
  }
  if (!std::isnan(best)) return {spline.wrap(best), SplitKind::kInflection, 0.0};
  return {spline.wrap(mid), SplitKind::kTurning, spline.curvature(spline.wrap(mid))};
}

// Each point's foot on pieces spanning the spline parameters [t0, t1] (a closed spline's
// last piece runs through the seam): the piece its parameter falls in, and where.
std::vector<ChainFoot> feetOnSpans(const std::vector<PieceReport>& spans, const std::vector<double>& parameters,
                                   bool periodic, double period) {
  std::vector<ChainFoot> feet(parameters.size());
  for (std::size_t k = 0; k < parameters.size(); ++k) {
    for (std::size_t i = 0; i < spans.size(); ++i) {
      const double t = (parameters[k] < spans[i].t0 && periodic) ? parameters[k] + period : parameters[k];
      if (t >= spans[i].t0 && t <= spans[i].t1) {
        feet[k] = {i, std::clamp((t - spans[i].t0) / (spans[i].t1 - spans[i].t0), 0.0, 1.0)};
        break;
      }
    }
  }
  return feet;
}

PartFit fitPart(const Part& part, const FitContext& context, bool stage7_follows) {
  const FitOptions& options = context.options;
  const double tol = context.tolerance, diag = context.diagonal;
  const Noise& noise = context.noise;
  StageTimings& timings = context.timings;
  PartFit out;
  std::vector<std::string>& warnings = out.warnings;
  out.smoothing = {SolveStatus::kConverged, 0, 0.0, "straight"};
  out.g2 = {SolveStatus::kConverged, 0, 0.0, "straight"};
  if (!part.closed && (part.points.size() < 4 || withinChord(part.points, tol))) {
    const Vec2 a = part.points.front(), b = part.points.back();
    out.segments.push_back(LaSegment::arc((b - a).norm(), a, angleOf(b - a), 0.0));
    PieceReport rep;
    rep.kind = PieceKind::kThreePoint;
    rep.alpha = rep.lcg_alpha = INFINITY;
    rep.lcg_r2 = NAN;
    out.reports.push_back(rep);
    return out;
  }
  auto t0 = Clock::now();
  SmoothingOptions so;
  // The spline's curvature feeds segmentation and alpha, so it is fitted tighter than the
  // user's tolerance where the data allow: down to their noise floor, or a fraction of
  // the tolerance for clean data.
  so.tolerance = stage7_follows ? tol : std::min(tol, std::max(noise.floor, kSplineToleranceFraction * tol));
  so.noise_sigma = noise.sigma;
  // (where stage 7 follows in this fit, it fits the points themselves: a spline's near
  // miss is its to close, a far one starts it astray. Through their ends at any miss, 24
  // of the shared data's 1,840 variants changed, 22 segments fewer and 3 extrema more;
  // their splines miss by under 2.1 tolerances. 6,400 exact samples of a sine at 0.05%
  // of the diagonal missed by 400 tolerances, and stage 7 from there put a corner on the
  // sine, in half a second; from the spline through its ends, 5 segments and no corner,
  // in 30 ms. Stages 1-6 alone keep the tolerance more often through the ends at any
  // miss: 63 -> 61 shared strokes over it.)
  so.through_ends_beyond = options.polishes() ? kFarSplineMiss : 1.0;
  SmoothingResult smooth = smoothWithBSpline(part.points, part.closed, so);
  timings.smoothing_ms += msSince(t0);
  out.smoothing = smooth.report;
  if (!smooth.report.usable()) warnings.push_back("smoothing: " + smooth.report.message);
  const CubicBSpline& spline = smooth.spline;
  out.spline = spline;

  t0 = Clock::now();
  const auto [t_first, t_last] = std::minmax_element(smooth.parameters.begin(), smooth.parameters.end());
  Segmentation seg = part.closed ? segmentSpline(spline, options.segmentation)
                                 : segmentSpline(spline, *t_first, *t_last, options.segmentation);
  timings.segmentation_ms += msSince(t0);

  const double period = spline.tMax() - spline.tMin();
  // Pieces a refinement pass leaves alone keep the alpha fitted to them before.
  std::map<std::pair<double, double>, double> fitted_alpha;
  // The best G2 chain seen (least deviation beyond the tolerance): what the part gets if
  // the passes run out on a worse one.
  struct Snapshot {
    G2Result res;
    std::vector<PieceReport> reports;
    std::vector<SplitPoint> splits;
    double excess = INFINITY;
  };
  std::optional<Snapshot> best;
  for (int pass = 0;; ++pass) {
    // Stage 4-5: chain of pieces with alpha from the LCG.
    t0 = Clock::now();
    const std::size_t n = seg.pieceCount();
    Chain chain;
    chain.closed = seg.closed;
    std::vector<double> piece_t0(n), piece_t1(n);
    for (std::size_t i = 0; i <= n; ++i) {
      const SplitPoint& sp = seg.splits[i % seg.splits.size()];
      chain.joints.push_back(spline.point(sp.t));
      const double raw = splineTangentAngle(spline, sp.t);
      chain.angles.push_back(i == 0 ? raw : chain.angles.back() + wrapAngle(raw - chain.angles.back()));
    }
    if (seg.closed) {
      chain.joints.back() = chain.joints.front();
      // the closing angle keeps the total turning; the direction is the start's
      chain.angles.back() = chain.angles.front() + 2.0 * std::numbers::pi *
                                                       std::round((chain.angles.back() - chain.angles.front()) / (2.0 * std::numbers::pi));
    }
    // Curvature must be zero where the turning direction changes from one piece to the
    // next (a sign change the segmentation dropped as noise, or one a halving exposed):
    // such ends are inflection ends too. A piece that would have two needs halving.
    std::vector<int> turn(n);
    for (std::size_t i = 0; i < n; ++i) {
      const double d = chain.angles[i + 1] - chain.angles[i];
      turn[i] = std::abs(d) < kStraightTurning ? 0 : (d > 0 ? 1 : -1);
    }
    auto flips = [&](std::size_t a, std::size_t b) { return turn[a] != 0 && turn[b] != 0 && turn[a] != turn[b]; };
    std::vector<bool> inflect_start(n), inflect_end(n);
    bool split_needed = false;
    std::vector<SplitPoint> refined;
    for (std::size_t i = 0; i < n; ++i) {
      const bool has_prev = seg.closed || i > 0, has_next = seg.closed || i + 1 < n;
      inflect_start[i] = seg.splits[i].kind == SplitKind::kInflection || (has_prev && flips((i + n - 1) % n, i));
      inflect_end[i] = seg.splits[(i + 1) % seg.splits.size()].kind == SplitKind::kInflection ||
                       (has_next && flips(i, (i + 1) % n));
      refined.push_back(seg.splits[i]);
      if (inflect_start[i] && inflect_end[i]) {
        split_needed = true;
        const double t1 = seg.splits[(i + 1) % seg.splits.size()].t;
        const double tm = spline.wrap(0.5 * (seg.splits[i].t + (t1 > seg.splits[i].t ? t1 : t1 + period)));
        refined.push_back({tm, SplitKind::kTurning, spline.curvature(tm)});
      }
    }
    if (split_needed && pass < kMaxRefinePasses) {
      if (!seg.closed) refined.push_back(seg.splits.back());
      seg.splits = std::move(refined);
      continue;
    }
    std::vector<PieceReport> reports(n);
    for (std::size_t i = 0; i < n; ++i) {
      const SplitPoint& a = seg.splits[i];
      const SplitPoint& b = seg.splits[(i + 1) % seg.splits.size()];
      reports[i].t0 = a.t;
      reports[i].t1 = (b.t > a.t) ? b.t : b.t + period;
      reports[i].start_kind = a.kind;
      reports[i].end_kind = b.kind;
    }
    const std::vector<std::vector<std::size_t>> members = pointsOfPieces(reports, smooth, period);
    for (std::size_t i = 0; i < n; ++i) {
      PieceReport& rep = reports[i];
      ChainPiece piece;
      const LcgFit lcg = lcgOfPiece(spline, rep.t0, rep.t1);
      rep.lcg_alpha = lcg.alpha;
      rep.lcg_r2 = lcg.r2;
      if (inflect_start[i] && !inflect_end[i]) {
        piece.kind = PieceKind::kInflectionStart;
      } else if (inflect_end[i] && !inflect_start[i]) {
        piece.kind = PieceKind::kInflectionEnd;
      } else {
        piece.kind = PieceKind::kThreePoint;
        // The fit of stage 7 finds alpha from the points; it starts from the prior of its
        // alphas, which also keeps the joint solve quick (a wild LCG slope can cost it
        // many Newton steps).
        double alpha = stage7_follows ? kStage7StartAlpha : lcg.report.usable() ? std::clamp(lcg.alpha, options.min_alpha, options.max_alpha) : kDefaultAlpha;
        Vec2 q0, q1, q2;
        chain.pieces.push_back(piece);  // controlTriangle reads only joints and angles
        if (controlTriangle(chain, i, q0, q1, q2)) {
          const double feasible = nearestFeasibleAlpha(alpha, q0, q1, q2);
          if (!std::isnan(feasible) && feasible != alpha) {
            rep.alpha_moved = true;
            alpha = feasible;
          }
          const auto cached = fitted_alpha.find({rep.t0, rep.t1});
          if (cached != fitted_alpha.end()) {
            alpha = cached->second;
          } else if (!stage7_follows && members[i].size() >= kMinPointsForAlphaFit) {
            std::vector<Vec2> sample;
            const std::size_t m = members[i].size(), take = std::min(m, kAlphaPoints);
            for (std::size_t k = 0; k < take; ++k) sample.push_back(part.points[members[i][k * (m - 1) / std::max<std::size_t>(take - 1, 1)]]);
            alpha = fitAlphaToPoints(alpha, q0, q1, q2, sample, options.min_alpha, options.max_alpha);
            fitted_alpha[{rep.t0, rep.t1}] = alpha;
          }
        }
        chain.pieces.pop_back();
        piece.alpha = alpha;
      }
      rep.kind = piece.kind;
      rep.alpha = piece.alpha;
      chain.pieces.push_back(piece);
    }
    openInflectionTriangles(chain);
    timings.alpha_ms += msSince(t0);

    // Stage 6.
    t0 = Clock::now();
    const G2Options g2 = context.g2();
    G2Result res = makeG2(chain, g2);
    // A joint whose gap no tangent angle closes sits between pieces whose alphas reach
    // too few triangle shapes: move those alphas halfway towards the widest-range alpha
    // and solve again (recorded as alpha_moved).
    for (int retry = 0; retry < kMaxAlphaRelaxations && !res.segments.empty() && !res.report.usable(); ++retry) {
      bool moved = false;
      for (std::size_t k = 0; k < res.gaps.size(); ++k) {
        if (res.gaps[k] <= options.g2_threshold) continue;
        const std::size_t joint = chain.closed ? k : k + 1;
        for (std::size_t i : {(joint + n - 1) % n, joint % n}) {
          if (chain.pieces[i].kind != PieceKind::kThreePoint || chain.pieces[i].alpha == kWidestAlpha) continue;
          chain.pieces[i].alpha = 0.5 * (chain.pieces[i].alpha + kWidestAlpha);
          reports[i].alpha_moved = moved = true;
        }
      }
      if (!moved) break;
      res = makeG2(chain, g2);
    }
    timings.g2_ms += msSince(t0);
    // Pieces to halve: those with no LA segment (tangents not forming a convex
    // triangle, or no alpha reaching it), else those whose segment strays from the
    // points further than the tolerance (or the spline's own error there). Joints to
    // drop (merging the pieces either side): where a piece without an LA segment holds
    // too few points for halving to help (a near-cusp of the spline between close
    // splits: halving it only makes smaller failing pieces). (Merging where G2 fails was
    // tried too: on the shared data it traded the G2 failures for deviations of up to
    // 15x the tolerance, the merged piece being split again at the same joint.)
    std::vector<bool> halve(n, false), drop(n + 1, false);
    bool any = false;
    const std::size_t joints = seg.splits.size();
    // Interior joints of an open part; any joint of a closed one that keeps enough pieces.
    auto droppable = [&](std::size_t j) { return seg.closed ? joints > kMinClosedPieces : (j > 0 && j < n); };
    if (stage7_follows) {
      // With stage 7 to follow, no piece is cut here: where stages 5-6 find no G2 chain
      // the fit starts from the spline (chainFromSpline), and its model selection adds
      // the segments the points need (cutting here leaves slivers where the spline
      // wiggles); it measures and corrects the deviations itself.
    } else if (res.segments.empty()) {
      for (std::size_t i = 0; i < n; ++i) {
        if (solvePiece(chain, i).report.usable()) continue;
        any = true;
        if (members[i].size() >= kMinPointsToHalve && pass < kMaxRefinePasses / 2) {
          halve[i] = true;
        } else if (droppable(i + 1) && !drop[i]) {
          drop[i + 1] = true;
        } else if (droppable(i)) {
          drop[i] = true;
        } else {
          halve[i] = true;
        }
      }
    } else {
      const std::vector<double> dev = pieceDeviations(res.segments, members, part.points, smooth, diag);
      const std::vector<double> own = pieceDeviations({}, members, part.points, smooth, diag);
      double excess = 0.0;  // largest deviation beyond what is allowed
      for (std::size_t i = 0; i < n; ++i) {
        const double allowed = std::max(tol, 1.05 * own[i]);
        any |= halve[i] = dev[i] > allowed;
        excess = std::max(excess, dev[i] - allowed);
      }
      if (res.report.usable() && (!best || excess < best->excess)) best = Snapshot{res, reports, seg.splits, excess};
      if (any && pass >= kMaxRefinePasses && best && best->excess < excess) {
        res = best->res;
        reports = best->reports;
        seg.splits = best->splits;
        any = best->excess > 0.0;
      }
    }
    if (any && pass < kMaxRefinePasses) {
      if (seg.closed && drop[n]) drop[0] = true;  // joint n of a closed chain is joint 0
      std::vector<SplitPoint> splits;
      for (std::size_t i = 0; i < n; ++i) {
        if (!drop[i]) splits.push_back(seg.splits[i]);
        if (halve[i]) splits.push_back(halvingPoint(spline, reports[i].t0, reports[i].t1));
      }
      if (!seg.closed) splits.push_back(seg.splits.back());
      seg.splits = std::move(splits);
      continue;
    }
    out.g2 = res.report;
    std::vector<PieceReport> spans = reports;  // before the fallback below drops pieces
    if (res.segments.empty()) {
      // Last resort: the pieces that have an LA segment keep it, the others become
      // straight lines between their joints. G2 (and G1 at the lines) is lost there and
      // the quality figures say so.
      warnings.push_back("part without a full LA chain, straight pieces used where none fits (" +
                         res.report.message + ")");
      std::vector<PieceReport> kept;
      for (std::size_t i = 0; i < n; ++i) {
        const SegmentSolve s = solvePiece(chain, i);
        const Vec2 chord = chain.joints[i + 1] - chain.joints[i];
        if (s.report.usable()) {
          res.segments.push_back(*s.segment);
        } else if (chord.norm() > 0.0) {
          res.segments.push_back(LaSegment::arc(chord.norm(), chain.joints[i], angleOf(chord), 0.0));
        } else {
          continue;  // two splits on one point: no piece between them
        }
        kept.push_back(reports[i]);
      }
      reports = std::move(kept);
    }
    if (!res.report.usable()) warnings.push_back("G2: " + res.report.message);
    for (std::size_t i = 0; i < reports.size(); ++i) {
      reports[i].alpha = res.segments[i].alpha();  // inflection pieces solved theirs; lines are inf
    }
    out.segments = std::move(res.segments);
    out.reports = std::move(reports);
    out.splits = seg.splits;
    out.feet = feetOnSpans(spans, smooth.parameters, smooth.spline.isPeriodic(), period);
    out.parameters = smooth.parameters;
    out.spans = std::move(spans);
    return out;
  }
}


}  // namespace la
