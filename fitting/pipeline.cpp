#include "fitting/pipeline.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "core/lcg.h"
#include "core/three_point_segment.h"
#include "fitting/chain_fit.h"
#include "fitting/model_selection.h"

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
constexpr double kPolishStartAlpha = 0.5;
// Stage 7's fit: points it iterates on (bins of the points, ChainFitOptions::max_points)
// and Levenberg-Marquardt steps per fit. Measured on the ground-truth chains
// (tests/pipeline_test.cpp) and the shared data: fewer points lose alpha accuracy on
// clean strokes (where nothing is binned); 8 more steps on the chosen chain bring its sum
// of squares to the optimum (alphas more than 0.3 off the truth: 27 of 78 instead of
// 32) but cost about 1 ms on a 1,000-point stroke, half the time budget.
constexpr std::size_t kFitPoints = 250;
constexpr int kFitIterations = 8;
// Stage 7 selects its segments for this much inside the tolerance: its model (~1e-6 of
// a segment's length) and the move onto a corner (below) shift the exact chain a little.
constexpr double kSelectionMargin = 0.01;
// Stage 7's chain is moved onto its corner by a similarity where that moves no point by
// more than this fraction of the tolerance, else by stage 6's joint rotation, which
// fails on nearly straight segments (see snapToJoints).
constexpr double kSnapReach = 0.1;
// A step longer than this many median steps is a gap the fit fills (fillGaps).
constexpr double kGapSteps = 10.0;
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
// Passes that split pieces which fail (no LA segment) or stray from the points, or merge
// them (see below); halving a piece without an LA segment is tried in the first half of
// them, and only on pieces holding this many points.
constexpr int kMaxRefinePasses = 16;
constexpr std::size_t kMinPointsToHalve = 2;
// A curve further than this many tolerances from the stroke's polyline (a loop between
// two points) is reported as straying: between sparse points a fair curve may leave
// the chords by about a tolerance.
constexpr double kStrayWarning = 2.0;
// A part's stage 7 fit from the spline's chain that ends further than this many
// tolerances from its points has set off astray: it is tried again from a finer start.
constexpr double kAstrayFit = 2.0;
// A part's curve is measured for straying (fitStroke's alternative starts) where it is
// longer than the part's polyline by this factor.
constexpr double kStrayLength = 1.02;
// A closed part keeps at least this many pieces (each turns less than pi).
constexpr std::size_t kMinClosedPieces = 3;
// Resolution of the deviations that decide those splits (relative to the diagonal;
// 500 times below the default tolerance; the reported figures use 1e-6).
constexpr double kRefineResolution = 1e-5;
// Points on a grid (pixels) are off the true stroke by up to sqrt(2)/2 of a step; no
// curve can be closer to all of them than about this, so the tolerance is not set below
// this many steps.
constexpr double kQuantizationFloor = 0.75;
// A pointer that moves at most this many grid steps per sample stays on a pixel row or
// column for several samples (stairs), so its noise repeats over neighbouring samples;
// see noiseOf.
constexpr double kStairSteps = 2.0;

// The noise floor of the tolerance is this many standard deviations of the points'
// estimated noise: a 2D Gaussian exceeds 4 sigma with probability e^-8 ~ 3e-4.
constexpr double kNoiseSigmas = 4.0;
constexpr double kSplineToleranceFraction = 0.2;

using Clock = std::chrono::steady_clock;

// The smallest tolerance the points allow: their noise level and, for points on an
// integer grid (pixels), the quantization. The noise is estimated robustly from the
// fourth differences p[i-2] - 4p[i-1] + 6p[i] - 4p[i+1] + p[i+2] across the stroke
// (along the normal of the chord p[i-2]p[i+2], so uneven spacing along the stroke does
// not count): they cancel any cubic, i.e. the curve's own bending, and for independent
// noise sigma have standard deviation sigma sqrt(70); the median ignores corners. With
// `lag`, the differences of every lag-th point: noise that repeats over up to `lag`
// neighbouring samples cancels partly in the differences of neighbours, not in these.
double noiseSigma(const std::vector<Vec2>& p, std::size_t lag = 1) {
  if (p.size() < 4 * lag + 3) return 0.0;
  std::vector<double> d;
  for (std::size_t i = 2 * lag; i + 2 * lag < p.size(); ++i) {
    const Vec2 chord = p[i + 2 * lag] - p[i - 2 * lag];
    const double len = chord.norm();
    if (!(len > 0.0)) continue;
    const Vec2 normal(-chord.y() / len, chord.x() / len);
    d.push_back(std::abs(normal.dot(p[i - 2 * lag] - 4.0 * p[i - lag] + 6.0 * p[i] - 4.0 * p[i + lag] + p[i + 2 * lag])));
  }
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2] / 0.6745 / std::sqrt(70.0);  // median of |N(0,s)| = 0.6745 s
}

// The points' noise: sigma per coordinate (the estimate above, plus the quantization
// of a grid of step h: uniform on a step, variance h^2/12 per coordinate) and the floor
// of the tolerance it implies.
struct Noise {
  double sigma = 0.0;
  double floor = 0.0;
  bool on_grid = false;  // the points lie on a pixel grid
};

// The step of the grid the points lie on along one coordinate (every value an integer
// number of steps from the smallest: pixels, possibly shifted and scaled, as Omniglot's
// canvas units are), or 0 if they do not. The step is the smallest change between
// consecutive points.
double gridStep(const std::vector<Vec2>& p, int axis) {
  constexpr double kRounding = 1e-3;  // in steps (the files print 6 decimals)
  double step = INFINITY, lo = p.front()[axis], hi = lo;
  for (std::size_t i = 1; i < p.size(); ++i) {
    const double d = std::abs(p[i][axis] - p[i - 1][axis]);
    if (d > 0.0) step = std::min(step, d);
    lo = std::min(lo, p[i][axis]), hi = std::max(hi, p[i][axis]);
  }
  if (!std::isfinite(step)) return 0.0;
  step = (hi - lo) / std::round((hi - lo) / step);  // the printed step's rounding spread over the range
  for (const Vec2& q : p) {
    const double k = (q[axis] - lo) / step;
    if (std::abs(k - std::round(k)) > kRounding) return 0.0;
  }
  return step;
}

// On a grid walked a pixel or two per sample (a mouse), the pointer's tremor and
// rounding repeat over neighbouring samples (stairs): the noise is taken at lag 2 as
// well, the larger estimate kept. Larger lags, and sparser samples, would span the
// curve's own bends (its share grows as lag^4): at lag 3 small glyphs' tolerances rose
// up to 4x, and lag 2 on strokes sampled every 3-8 pixels 1.6-3x.
Noise noiseOf(const std::vector<Vec2>& p) {
  const double hx = gridStep(p, 0), hy = gridStep(p, 1);
  const bool on_grid = hx > 0.0 && hy > 0.0;
  const double h = std::max(hx, hy);
  const bool stairs = on_grid && medianStep(p) <= kStairSteps * h;
  const double sigma = stairs ? std::max(noiseSigma(p), noiseSigma(p, 2)) : noiseSigma(p);
  Noise n;
  n.sigma = on_grid ? std::sqrt(sigma * sigma + h * h / 12.0) : sigma;
  n.floor = std::max(kNoiseSigmas * sigma, on_grid ? kQuantizationFloor * h : 0.0);
  n.on_grid = on_grid;
  return n;
}
// Stage 6's options (also for closing stage 7's chain and the user's edits).
G2Options g2OptionsOf(const FitOptions& options, double diagonal) {
  G2Options g2;
  g2.method = options.g2;
  g2.threshold = options.g2_threshold;
  g2.diagonal = diagonal;
  return g2;
}

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

struct Part {
  std::vector<Vec2> points;
  bool closed = false;
  bool starts_at_corner = false;  // its first point is a corner (stage 7 pins the curve's start to it)
  bool ends_at_corner = false;    // its last point is a corner (stage 7 pins the curve's end to it)
};

// Points along every step of `p` (and the closing step of a closed part) longer than
// kGapSteps times `spacing`, that far apart. A long step is a straight edge the data
// do not sample (a font outline's closing stem, a polygon's side) or samples the
// digitizer lost: the points' own polyline is the best guess there, and without points
// along it a fit may loop through the gap. Fits use these; quality is measured on the
// data alone.
std::vector<Vec2> fillGaps(const std::vector<Vec2>& p, bool closed, double spacing) {
  std::vector<Vec2> out;
  const std::size_t steps = closed ? p.size() : p.size() - 1;
  for (std::size_t i = 0; i < p.size(); ++i) {
    out.push_back(p[i]);
    if (i >= steps) continue;
    const Vec2 a = p[i], b = p[(i + 1) % p.size()];
    const double length = (b - a).norm();
    if (!(length > kGapSteps * spacing)) continue;
    const int pieces = static_cast<int>(std::ceil(length / spacing));
    for (int k = 1; k < pieces; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / pieces));
  }
  return out;
}

// The points with a binomial filter (1 4 6 4 1)/16 over five neighbours; an open
// part's ends stay. On a pixel grid it turns a one-pixel stair into a slope.
std::vector<Vec2> withoutStairs(const std::vector<Vec2>& p, bool closed) {
  const auto m = static_cast<long>(p.size());
  if (m < 5) return p;
  auto at = [&](long k) { return p[static_cast<std::size_t>(closed ? (k % m + m) % m : std::clamp(k, 0L, m - 1))]; };
  std::vector<Vec2> out = p;
  for (long i = closed ? 0 : 1; i < (closed ? m : m - 1); ++i)
    out[static_cast<std::size_t>(i)] = (at(i - 2) + 4.0 * at(i - 1) + 6.0 * at(i) + 4.0 * at(i + 1) + at(i + 2)) / 16.0;
  return out;
}

std::vector<Part> splitAtCorners(const CleanStroke& c) {
  const auto& p = c.points;
  const double spacing = medianStep(p);
  if (c.corners.empty()) return {Part{fillGaps(p, c.closed, spacing), c.closed, false}};
  std::vector<std::size_t> cuts = c.corners;
  if (!c.closed) {
    cuts.insert(cuts.begin(), 0);
    cuts.push_back(p.size() - 1);
  } else {
    cuts.push_back(p.size());  // back to the start (a corner at index 0)
  }
  std::vector<Part> parts;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    Part part;
    for (std::size_t i = cuts[k]; i <= cuts[k + 1]; ++i) part.points.push_back(p[i % p.size()]);
    part.points = fillGaps(part.points, false, spacing);
    part.starts_at_corner = c.closed || k > 0;
    part.ends_at_corner = c.closed || k + 2 < cuts.size();
    parts.push_back(std::move(part));
  }
  return parts;
}

bool withinChord(const std::vector<Vec2>& pts, double tol) {
  const Vec2 a = pts.front(), b = pts.back();
  const Vec2 d = b - a;
  const double len = d.norm();
  if (!(len > 0.0)) return false;
  for (const Vec2& p : pts) {
    const double along = (p - a).dot(d) / len;
    if (along < -tol || along > len + tol || std::abs(cross(d, p - a)) / len > tol) return false;
  }
  return true;
}

// LCG slope of the spline between t0 and t1 (analytic curvature and its derivative).
LcgFit lcgOfPiece(const CubicBSpline& s, double t0, double t1) {
  std::vector<double> kappa, dkappa;
  const int first = static_cast<int>(kLcgTrim * kLcgSamples), last = kLcgSamples - first;
  for (int k = first; k < last; ++k) {
    double k_t, dk_t;
    s.curvatureAndSlope(t0 + (t1 - t0) * (k + 0.5) / kLcgSamples, k_t, dk_t);
    kappa.push_back(k_t);
    dkappa.push_back(dk_t);
  }
  return fitLcg(lcgFromDerivative(kappa, dkappa));
}

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

struct PartFit {
  std::vector<LaSegment> segments;
  std::vector<PieceReport> reports;
  std::optional<CubicBSpline> spline;
  std::vector<SplitPoint> splits;
  std::vector<PieceReport> spans;  // every piece of the final segmentation (segments may differ after a failed G2)
  std::vector<ChainFoot> feet;     // of the part's points on `spans` (from their spline parameters)
  std::vector<double> parameters;  // the points' spline parameters
  std::vector<std::string> warnings;
  double max_dev = NAN;            // largest distance of the part's points from `segments`, once known
  double stray = NAN;              // largest distance of `segments` from the part's polyline, once known
  SolveReport smoothing, g2;
};

}  // namespace

namespace {

// Stages 2-6 for one corner-free part.
PartFit fitPart(const Part& part, double tol, const Noise& noise, double diag, const FitOptions& options,
                StageTimings& timings) {
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
  so.tolerance = options.polish ? tol : std::min(tol, std::max(noise.floor, kSplineToleranceFraction * tol));
  so.noise_sigma = noise.sigma;
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
        double alpha = options.polish ? kPolishStartAlpha : lcg.report.usable() ? std::clamp(lcg.alpha, options.min_alpha, options.max_alpha) : kDefaultAlpha;
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
          } else if (!options.polish && members[i].size() >= kMinPointsForAlphaFit) {
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
    const G2Options g2 = g2OptionsOf(options, diag);
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
    if (options.polish) {
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

// The largest distance from the points to a part's chain.
double maxDeviationOf(const std::vector<LaSegment>& segments, const std::vector<Vec2>& points, double diag) {
  Curve curve;
  for (const LaSegment& s : segments) curve.pieces.push_back({s, false});
  double worst = 0.0;
  for (double d : distancesToCurve(curve, points, diag, kRefineResolution)) worst = std::max(worst, d);
  return worst;
}

// The chain stage 7 starts from where stages 5-6 found none (a piece whose tangents form
// no control triangle, a joint no tangent angle makes G2): read off the spline in
// intrinsic form. A piece turning against both its neighbours (between two inflections)
// is cut at its largest curvature first (`spans` is updated). Each piece turns as the
// spline does between its splits; a joint's curvature is 0 where the turning direction
// changes (an inflection), else the spline's (a small value of the piece's sign where the
// spline's has the other) to start with, then adjusted as each segment is shot towards
// the next split point (below). G2 by construction; empty if some piece has no LA
// segment. `length`: the spline's length between each piece's splits.
std::vector<LaSegment> shotChain(const CubicBSpline& spline, std::vector<PieceReport>& spans, bool closed,
                                 double min_alpha, double max_alpha, std::vector<double>& length) {
  constexpr int kSteps = 16;           // per piece, for its turning and length
  constexpr double kSmallKappa = 0.3;  // of the piece's mean curvature, where the spline's has the wrong sign
  auto measure = [&](double t0, double t1, double& turning, double& length) {
    double prev = splineTangentAngle(spline, spline.wrap(t0));
    Vec2 p = spline.point(spline.wrap(t0));
    turning = length = 0.0;
    for (int k = 1; k <= kSteps; ++k) {
      const double t = spline.wrap(t0 + (t1 - t0) * k / kSteps);
      const double a = splineTangentAngle(spline, t);
      turning += wrapAngle(a - prev);
      prev = a;
      const Vec2 q = spline.point(t);
      length += (q - p).norm();
      p = q;
    }
  };
  auto sign = [](double v) { return v < 0.0 ? -1.0 : 1.0; };
  std::vector<double> turning;
  for (bool again = true; again;) {
    again = false;
    const std::size_t n = spans.size();
    turning.assign(n, 0.0);
    length.assign(n, 0.0);
    for (std::size_t i = 0; i < n; ++i) measure(spans[i].t0, spans[i].t1, turning[i], length[i]);
    for (std::size_t i = 0; i < n && n >= 3; ++i) {
      const bool has_before = closed || i > 0, has_after = closed || i + 1 < n;
      if (!has_before || !has_after) continue;
      const double s = sign(turning[i]);
      if (sign(turning[(i + n - 1) % n]) == s || sign(turning[(i + 1) % n]) == s) continue;
      double best_t = 0.5 * (spans[i].t0 + spans[i].t1), best = 0.0;
      for (int k = 1; k < kSteps; ++k) {
        const double t = spans[i].t0 + (spans[i].t1 - spans[i].t0) * k / kSteps;
        const double kappa = std::abs(spline.curvature(spline.wrap(t)));
        if (kappa > best) best = kappa, best_t = t;
      }
      PieceReport second = spans[i];
      spans[i].t1 = second.t0 = best_t;
      spans[i].end_kind = second.start_kind = SplitKind::kExtremum;
      spans.insert(spans.begin() + static_cast<std::ptrdiff_t>(i) + 1, second);
      again = true;
      break;
    }
  }
  const std::size_t n = spans.size(), joints = closed ? n : n + 1;
  std::vector<double> kappa(joints, 0.0);
  for (std::size_t j = 0; j < joints; ++j) {
    const bool has_before = closed || j > 0, has_after = closed || j < n;
    const std::size_t before = (j + n - 1) % n, after = j % n;
    if (has_before && has_after && sign(turning[before]) != sign(turning[after])) continue;  // inflection: 0
    const std::size_t piece = has_after ? after : before;
    const double s = sign(turning[piece]);
    const double k = spline.curvature(spline.wrap(has_after ? spans[after].t0 : spans[before].t1));
    const double mean = std::abs(turning[piece]) / std::max(length[piece], 1e-300);
    kappa[j] = sign(k) == s && std::abs(k) > kSmallKappa * mean ? k : s * kSmallKappa * mean;
  }
  // Shoot segment by segment: each starts where the previous ended (tangent and
  // curvature continuous), turns as the spline does between its splits, and takes the
  // end curvature and alpha that bring its end closest to the next split point (Gauss-
  // Newton on two unknowns, one at an inflection joint, numeric derivatives): the chain
  // then follows the spline's joints instead of drifting with its curvature errors.
  std::vector<LaSegment> chain;
  Vec2 start = spline.point(spline.wrap(spans.front().t0));
  double theta = splineTangentAngle(spline, spline.wrap(spans.front().t0));
  for (std::size_t i = 0; i < n; ++i) {
    const double k0 = i == 0 ? kappa[0] : chain.back().kappaEnd();
    const bool free_end = kappa[(i + 1) % joints] != 0.0;
    const double end_sign = sign(turning[i]);
    const Vec2 target = spline.point(spline.wrap(spans[i].t1));
    // unknowns: y = log|kappa_end| (when not an inflection), alpha
    double y = free_end ? std::log(std::abs(kappa[(i + 1) % joints])) : 0.0;
    const bool zero_end = k0 == 0.0 || !free_end;
    const double hi = zero_end ? std::min(kInflectionAlphaCap, max_alpha) : max_alpha, lo = std::min(min_alpha, hi);
    double alpha = zero_end ? -1.0 : kPolishStartAlpha;
    auto build = [&](double yy, double aa) -> std::optional<LaSegment> {
      const double k1 = free_end ? end_sign * std::exp(yy) : 0.0;
      try {
        return LaSegment::withTurning(aa, turning[i], start, theta, k0, k1);
      } catch (const std::invalid_argument&) {
        return std::nullopt;
      }
    };
    auto miss = [&](double yy, double aa) -> std::optional<Vec2> {
      const auto seg = build(yy, aa);
      if (!seg) return std::nullopt;
      return Vec2(seg->end() - target);
    };
    constexpr int kShootingSteps = 8;
    constexpr double kStep = 1e-4;
    for (int it = 0; it < kShootingSteps; ++it) {
      const auto r = miss(y, alpha);
      if (!r) break;
      Eigen::Matrix<double, 2, 2> jac = Eigen::Matrix<double, 2, 2>::Zero();
      const auto ra = miss(y, alpha + kStep);
      if (!ra) break;
      jac.col(1) = (*ra - *r) / kStep;
      if (free_end) {
        const auto ry = miss(y + kStep, alpha);
        if (!ry) break;
        jac.col(0) = (*ry - *r) / kStep;
      }
      // least-squares step, damped a little, both unknowns limited in size
      Eigen::Matrix2d a = jac.transpose() * jac;
      a.diagonal() += Eigen::Vector2d::Constant(1e-9 * std::max(1.0, a.trace()));
      const Eigen::Vector2d step = a.ldlt().solve(-jac.transpose() * *r);
      if (!step.allFinite()) break;
      const double ny = y + std::clamp(step[0], -1.0, 1.0), na = std::clamp(alpha + std::clamp(step[1], -1.0, 1.0), lo, hi);
      const auto rn = miss(ny, na);
      if (!rn || rn->norm() >= r->norm()) break;
      y = ny;
      alpha = na;
    }
    const auto seg = build(y, alpha);
    if (!seg) return {};
    chain.push_back(*seg);
    start = chain.back().end();
    theta = chain.back().theta(chain.back().length());
  }
  return chain;
}

// shotChain; with `halve`, where a shot segment is far longer or shorter than the
// spline between its splits, it has set off away from the points (its start curvature,
// the previous one's end, does not suit it): its span is halved (at an inflection
// inside if any) and the chain shot again, at most kMaxHalvings times.
std::vector<LaSegment> chainFromSpline(const CubicBSpline& spline, std::vector<PieceReport>& spans, bool closed,
                                       double min_alpha, double max_alpha, bool halve) {
  constexpr double kShotLengthRatio = 2.0;
  constexpr int kMaxHalvings = 6;
  for (int halvings = 0;; ++halvings) {
    std::vector<double> length;
    const std::vector<LaSegment> chain = shotChain(spline, spans, closed, min_alpha, max_alpha, length);
    const std::size_t n = chain.size();
    std::size_t astray = n;
    for (std::size_t i = 0; i < n && astray == n; ++i)
      if (!(chain[i].length() < kShotLengthRatio * length[i] && kShotLengthRatio * chain[i].length() > length[i])) astray = i;
    if (!halve || astray == n || halvings >= kMaxHalvings) return chain;
    const double t0 = spans[astray].t0, t1 = spans[astray].t1;
    double t = halvingPoint(spline, t0, t1).t;
    if (t < t0) t += spline.tMax() - spline.tMin();  // (wrapped past a closed spline's seam)
    if (!(t > t0 && t < t1)) return chain;
    PieceReport second = spans[astray];
    spans[astray].t1 = second.t0 = t;
    spans[astray].end_kind = second.start_kind = SplitKind::kTurning;
    spans.insert(spans.begin() + static_cast<std::ptrdiff_t>(astray) + 1, second);
  }
}

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

// Stage 7's selection options, for `parts` parts' points: the tolerance less its margin,
// the alpha range, the points and iterations per fit, the noise (for the bins and the
// priors); closure, fixed ends and corners are the caller's.
SelectionOptions stage7Selection(double tol, double noise, const FitOptions& options, std::size_t parts = 1) {
  SelectionOptions so;
  so.tolerance = (1.0 - kSelectionMargin) * tol;
  ChainFitOptions& co = so.fit;
  co.min_alpha = options.min_alpha;
  co.max_alpha = options.max_alpha;
  co.max_points = kFitPoints * parts;
  co.max_iterations = kFitIterations;
  co.noise = noise;
  return so;
}

// Stage 7 on one part: fits its chain to the points and selects its segments
// (fitting/model_selection.h), from stage 6's chain or, where that has no G2 chain, from
// the spline. The result replaces the part's chain where it is within the tolerance,
// closer to the points than that chain, or that chain has gaps; fit.max_dev is then
// known.
void polishPart(PartFit& fit, const Part& part, double tol, double noise, double diag,
                const FitOptions& options) {
  if (!fit.spline) return;  // a straight part
  SelectionOptions so = stage7Selection(tol, noise, options);
  ChainFitOptions& co = so.fit;
  co.closed = part.closed;
  co.fix_start = part.starts_at_corner;
  co.fix_end = part.ends_at_corner;
  std::vector<LaSegment> start = fit.segments;
  const bool straight = std::any_of(start.begin(), start.end(), [](const LaSegment& s) { return s.isStraight(); });
  std::vector<ChainFoot> feet = fit.feet;
  const bool from_spline = !fit.g2.usable() || straight || start.size() != fit.spans.size();
  // (with `halve`, the spline's spans where a shot segment sets off astray are halved)
  auto startFromSpline = [&](bool halve) {
    std::vector<PieceReport> spans = fit.spans;
    start = chainFromSpline(*fit.spline, spans, part.closed, options.min_alpha, options.max_alpha, halve);
    feet = feetOnSpans(spans, fit.parameters, part.closed, fit.spline->tMax() - fit.spline->tMin());
  };
  if (from_spline) startFromSpline(false);
  if (start.empty()) return;
  SelectionResult selected = selectChain(start, part.points, feet, so);
  if (from_spline && selected.fit.max_distance > kAstrayFit * tol) {
    // Far outside the tolerance from the spline's chain: again from its spans halved
    // where it set off astray, the closer kept. (Within twice the tolerance, the fit
    // across corners usually closes the gap, and the halved start only adds segments.)
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
    const G2Options g2 = g2OptionsOf(options, diag);
    segments = snapToJoints(segments, co.closed, part.points.back(), g2, kSnapReach * tol);
    if (segments.empty()) return;
  }
  if (polished.max_distance > tol && fit.g2.usable()) {
    // Outside the tolerance: kept if closer to the points than the G2 chain it started
    // from. A chain with curvature or tangent gaps is always replaced: G2 is the promise
    // (a kink where the user drew none is worse than a miss, which the figures report).
    fit.max_dev = maxDeviationOf(fit.segments, part.points, diag);
    if (polished.max_distance >= fit.max_dev) return;
  }
  fit.max_dev = polished.max_distance;
  fit.warnings.clear();
  fit.segments = segments;
  fit.g2 = {SolveStatus::kConverged, polished.report.iterations, 0.0, "G2 by construction (stage 7)"};
  fit.reports = reportsOf(fit.segments, polished.feet, fit.parameters, *fit.spline, part.closed);
  for (std::size_t i = 0; i < fit.reports.size() && i < polished.alpha_standard_error.size(); ++i)
    fit.reports[i].alpha_standard_error = polished.alpha_standard_error[i];
}

// How far a part's chain goes from the part's polyline (strayFromPoints), measured only
// where the chain is longer than the polyline (kStrayLength; else 0): a loop adds
// length, noise only to the polyline, and the measure costs a grid of the points. With
// `tip_allowance` (world units), measured always, and counted where above it: a sharp
// corner running past the rounded tip of a drawn corner adds almost no length.
double strayOf(const std::vector<LaSegment>& segments, const Part& part, double diag, double tip_allowance = INFINITY) {
  double curve_length = 0.0, stroke_length = 0.0;
  for (const LaSegment& s : segments) curve_length += s.length();
  for (std::size_t i = 1; i < part.points.size(); ++i) stroke_length += (part.points[i] - part.points[i - 1]).norm();
  if (part.closed) stroke_length += (part.points.front() - part.points.back()).norm();
  const bool longer = curve_length > kStrayLength * stroke_length;
  if (!longer && tip_allowance == INFINITY) return 0.0;
  Curve c;
  c.closed = part.closed;
  for (const LaSegment& s : segments) c.pieces.push_back({s, false});
  const double stray = strayFromPoints(c, part.points, diag);
  return longer || stray > tip_allowance ? stray : 0.0;
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
// (selectChain; else only hooks beside corners are collapsed). A straight part stays a
// line unless the selection bends it. Kept where it brings the curve closer to the
// points, counting the stray, or keeps it within the tolerance. True if it changed the
// chains; false where a part has no G2 chain.
bool fitAcrossCorners(std::vector<PartFit>& fits, const std::vector<Part>& parts, bool closed, double tol,
                      double noise, double diag, const FitOptions& options) {
  const std::size_t n = parts.size();
  if (n == 0 || !(parts.front().starts_at_corner || parts.front().ends_at_corner)) return false;
  std::vector<LaSegment> chain;
  std::vector<Vec2> points;
  SelectionOptions so = stage7Selection(tol, noise, options, n);
  ChainFitOptions& co = so.fit;
  co.closed = closed;
  std::vector<std::size_t> first_point;
  for (std::size_t k = 0; k < n; ++k) {
    const PartFit& fit = fits[k];
    if (!fit.g2.usable() || fit.segments.empty()) return false;
    first_point.push_back(points.empty() ? 0 : points.size() - 1);  // (the corner is both parts')
    if (parts[k].starts_at_corner) co.corners.push_back({chain.size(), first_point.back()});
    if (fit.spline) chain.insert(chain.end(), fit.segments.begin(), fit.segments.end());
    else chain.push_back(fit.segments.front());  // a line
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
  // hooks beside corners)
  so.refine = before > tol;
  std::vector<PartFit> out, held;
  const SelectionResult free = selectChain(chain, points, {}, so);
  double after = split(free, out);
  if (after > tol) {
    // (from the free fit where it improved: its hooks are gone and its corners near)
    co.hold_corner_points = true;
    SelectionResult held_fit;
    if (free.fit.improved) {
      co.corners = free.corners;
      held_fit = selectChain(free.fit.segments, points, free.fit.feet, so);
    } else {
      held_fit = selectChain(chain, points, {}, so);
    }
    const double after_held = split(held_fit, held);
    if (after_held < after) after = after_held, out = std::move(held);
  }
  // (within the tolerance, the least-squares corners are the better estimate)
  if (!(after < before) && !(after <= tol)) return false;
  fits = std::move(out);
  return true;
}

}  // namespace

FitResult fitStroke(const Stroke& stroke, const FitOptions& options) {
  const auto start = Clock::now();
  FitResult r;
  r.cleaned = cleanStroke(stroke, options.cleanup);
  r.timings.cleanup_ms = msSince(start);
  const double diag = r.cleaned.diagonal;
  r.tolerance = options.tolerance > 0.0 ? options.tolerance : options.tolerance_fraction * diag;
  const Noise noise = noiseOf(r.cleaned.points);
  const double floor = noise.floor;
  if (r.tolerance < floor) {
    r.warnings.push_back("tolerance raised from " + std::to_string(r.tolerance) + " to " + std::to_string(floor) +
                         ": the noise floor of the points (their estimated noise and pixel grid)");
    r.tolerance = floor;
  }
  r.smoothing = {SolveStatus::kConverged, 0, 0.0, "ok"};
  r.g2 = {SolveStatus::kConverged, 0, 0.0, "ok"};

  std::vector<Part> parts = splitAtCorners(r.cleaned);
  r.curve.closed = r.cleaned.closed;
  const bool polishing = options.polish && options.g2 != G2Method::kOff;  // (stage 7 makes the chain G2)
  auto fitOne = [&](const Part& part) {
    PartFit fit = fitPart(part, r.tolerance, noise, diag, options, r.timings);
    if (!polishing) return fit;
    auto polish = [&](PartFit& f) {
      const auto tp = Clock::now();
      polishPart(f, part, r.tolerance, noise.sigma, diag, options);
      r.timings.polish_ms += msSince(tp);
    };
    polish(fit);
    // Where that leaves a gap, a miss or a stray (the curve going where the stroke did
    // not: a loop between two points), other starts: the better result stays (G2 first,
    // then the larger of the deviation from the part's points and the stray).
    auto measure = [&](PartFit& f) {
      if (std::isnan(f.max_dev)) f.max_dev = maxDeviationOf(f.segments, part.points, diag);
      if (std::isnan(f.stray)) f.stray = strayOf(f.segments, part, diag);
      return std::max(f.max_dev, f.stray);
    };
    auto misses = [&] { return !fit.g2.usable() || !(measure(fit) <= r.tolerance); };
    auto consider = [&](PartFit other) {
      polish(other);
      const bool better = other.g2.usable() != fit.g2.usable() ? other.g2.usable() : measure(other) < measure(fit);
      if (better) fit = std::move(other);
    };
    // Stages 2-6 as the paper has them (cutting pieces that stray or have no LA
    // segment): a chain close to the points.
    FitOptions plain = options;
    plain.polish = false;
    if (misses()) consider(fitPart(part, r.tolerance, noise, diag, plain, r.timings));
    // Pixel-quantized strokes: a spline through the stairs has an extremum at every
    // step and the chain from it strays; stages 2-6 on the points with their stairs
    // smoothed (stage 7 still fits the points themselves).
    if (misses() && noise.on_grid) {
      Part smoothed = part;
      smoothed.points = withoutStairs(part.points, part.closed);
      consider(fitPart(smoothed, r.tolerance, noise, diag, options, r.timings));
    }
    measure(fit);
    return fit;
  };
  std::vector<PartFit> fits;
  for (const Part& part : parts) fits.push_back(fitOne(part));
  // A corner is the clean-up's reading of the stroke, and a tight bend can pass for one.
  // Where a part beside a corner misses the tolerance and the two parts fitted as one
  // smooth part keep it, the corner goes. (The corner after part k: corners[k] of an
  // open stroke, corners[k + 1] of a closed one, whose corners[0] is its start; a
  // closed stroke's only corner joins its one part to itself.)
  const bool closed = r.cleaned.closed;
  // (a closed stroke's one part has a seam corner only if the clean-up found corners:
  // without, its points do not end with the start again)
  const bool seam_corner = closed && parts.size() == 1 && !r.cleaned.corners.empty();
  for (std::size_t k = 0; polishing && (k + 1 < parts.size() || (seam_corner && k == 0));) {
    const bool seam = k + 1 == parts.size();
    const PartFit& next = seam ? fits[0] : fits[k + 1];
    if (fits[k].max_dev <= r.tolerance && next.max_dev <= r.tolerance) {
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
    PartFit smooth = fitOne(merged);
    if (!smooth.g2.usable() || !(smooth.max_dev <= r.tolerance)) {
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
  joinAtCorners(fits, parts, g2OptionsOf(options, diag));
  if (polishing) {
    const auto tp = Clock::now();
    if (fitAcrossCorners(fits, parts, closed, r.tolerance, noise.sigma, diag, options))
      joinAtCorners(fits, parts, g2OptionsOf(options, diag));  // (a closed chain's seam, to rounding)
    r.timings.polish_ms += msSince(tp);
  }
  for (std::size_t k = 0; k < parts.size(); ++k) {
    PartFit& fit = fits[k];
    r.warnings.insert(r.warnings.end(), fit.warnings.begin(), fit.warnings.end());
    for (std::size_t i = 0; i < fit.segments.size(); ++i) {
      r.curve.pieces.push_back({fit.segments[i], i == 0 && parts[k].starts_at_corner});
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
  r.timings.quality_ms = msSince(tq);
  // Said from the measured figures, whichever stage or start the curve came from.
  double stray = 0.0;  // (fitOne measured most parts already)
  for (std::size_t k = 0; k < parts.size(); ++k) {
    if (std::isnan(fits[k].stray)) fits[k].stray = strayOf(fits[k].segments, parts[k], diag);
    stray = std::max(stray, fits[k].stray);
  }
  if (stray > kStrayWarning * r.tolerance)
    r.warnings.push_back("the curve strays up to " + std::to_string(stray) + " from the stroke, where no point is");
  if (r.quality.max_dev > r.tolerance)
    r.warnings.push_back("the curve misses the tolerance: it passes up to " + std::to_string(r.quality.max_dev) +
                         " from the points, the tolerance is " + std::to_string(r.tolerance));
  r.timings.total_ms = msSince(start);
  return r;
}

}  // namespace la

namespace la {

namespace {

// Re-solves G2 over the corner-to-corner part holding `piece`, its chain taken from
// the fitted segments, after `edit` changed the chain (index of the piece in the chain;
// it returns why the edit makes no sense, or "").
std::optional<FitResult> resolvePart(const FitResult& fit, std::size_t piece, const FitOptions& options,
                                     const std::function<std::string(Chain&, std::size_t)>& edit, std::string* why) {
  const int part = fit.pieces[piece].part;
  std::size_t first = piece, last = piece;
  while (first > 0 && fit.pieces[first - 1].part == part) --first;
  while (last + 1 < fit.pieces.size() && fit.pieces[last + 1].part == part) ++last;
  Chain chain;
  chain.closed = fit.curve.closed && first == 0 && last + 1 == fit.curve.pieces.size() &&
                 !fit.curve.pieces.front().corner;
  for (std::size_t i = first; i <= last; ++i) {
    const LaSegment& seg = fit.curve.pieces[i].segment;
    chain.joints.push_back(seg.start());
    chain.angles.push_back(i == first ? seg.theta0() : chain.angles.back() + wrapAngle(seg.theta0() - chain.angles.back()));
    chain.pieces.push_back({fit.pieces[i].kind, seg.alpha()});
  }
  const LaSegment& end = fit.curve.pieces[last].segment;
  chain.joints.push_back(chain.closed ? chain.joints.front() : end.end());
  chain.angles.push_back(chain.angles.back() + wrapAngle(end.theta(end.length()) - chain.angles.back()));
  if (std::string refused = edit(chain, piece - first); !refused.empty()) {
    if (why) *why = refused;
    return std::nullopt;
  }
  const G2Options g2 = g2OptionsOf(options, fit.quality.diagonal);
  const G2Result res = makeG2(chain, g2);
  if (res.segments.empty() || !res.report.usable()) {
    if (why) *why = "no G2 curve through that change: " + res.report.message;
    return std::nullopt;
  }
  FitResult out = fit;
  for (std::size_t i = first; i <= last; ++i) {
    out.curve.pieces[i].segment = res.segments[i - first];
    out.pieces[i].alpha = res.segments[i - first].alpha();
  }
  out.g2 = res.report;
  out.quality = measureQuality(out.curve, out.cleaned.points);
  return out;
}

}  // namespace

std::optional<FitResult> withSegmentAlpha(const FitResult& fit, std::size_t piece, double alpha,
                                          const FitOptions& options, std::string* why) {
  if (piece >= fit.pieces.size() || piece >= fit.curve.pieces.size()) {
    if (why) *why = "no such segment";
    return std::nullopt;
  }
  if (fit.pieces[piece].kind != PieceKind::kThreePoint || std::isinf(fit.curve.pieces[piece].segment.alpha())) {
    if (why) *why = "this segment's alpha is fixed (an inflection end or a straight piece)";
    return std::nullopt;
  }
  return resolvePart(fit, piece, options, [&](Chain& c, std::size_t i) {
    c.pieces[i].alpha = alpha;
    return std::string();
  }, why);
}

std::optional<FitResult> withJointMoved(const FitResult& fit, std::size_t joint, const Vec2& position,
                                        const FitOptions& options, std::string* why) {
  const std::size_t n = fit.curve.pieces.size();
  if (joint > n || (joint == n && fit.curve.closed) || n == 0 || fit.pieces.size() != n || !allFinite(position)) {
    if (why) *why = "no such joint";
    return std::nullopt;
  }
  FitResult out = fit;
  // The part that ends here: the open curve's last part, or the part before a corner
  // (parts meet only at corners, G0, so each is solved on its own).
  const bool corner = joint < n && fit.curve.pieces[joint].corner;
  if (joint == n || (corner && (joint > 0 || fit.curve.closed))) {
    auto ended = resolvePart(out, joint == 0 ? n - 1 : joint - 1, options, [&](Chain& c, std::size_t i) {
      c.joints[i + 1] = position;
      return std::string();
    }, why);
    if (!ended) return std::nullopt;
    out = std::move(*ended);
  }
  if (joint == n) return out;
  return resolvePart(out, joint, options, [&](Chain& c, std::size_t i) {
    c.joints[i] = position;
    if (c.closed && i == 0) c.joints.back() = position;
    return std::string();
  }, why);
}

std::optional<FitResult> withApexMoved(const FitResult& fit, std::size_t piece, const Vec2& apex,
                                       const FitOptions& options, std::string* why) {
  if (piece >= fit.pieces.size() || piece >= fit.curve.pieces.size() || !allFinite(apex)) {
    if (why) *why = "no such segment";
    return std::nullopt;
  }
  return resolvePart(fit, piece, options, [&](Chain& c, std::size_t i) -> std::string {
    const std::size_t n = c.size();
    const Vec2 a = c.joints[i], b = c.joints[i + 1];
    if ((apex - a).norm() == 0.0 || (b - apex).norm() == 0.0) return "the apex must differ from the segment's ends";
    c.sliding.assign(c.joints.size(), false);
    // Each end's tangent now points along the triangle's side (kept within a turn of the
    // old angle); an end that has a curvature equation slides along that side.
    auto fix = [&](std::size_t j, const Vec2& direction) {
      const double angle = c.angles[j] + wrapAngle(std::atan2(direction.y(), direction.x()) - c.angles[j]);
      if (c.closed && (j == 0 || j == n)) {  // joint 0 is joint n, one turn apart
        const double shift = angle - c.angles[j];
        c.angles[0] += shift;
        c.angles[n] += shift;
        c.sliding[0] = c.sliding[n] = true;
      } else {
        c.angles[j] = angle;
        c.sliding[j] = j > 0 && j < n;
      }
    };
    fix(i, apex - a);
    fix(i + 1, b - apex);
    return std::string();
  }, why);
}

}  // namespace la
