// Tests of the whole fitting pipeline (fitting/pipeline.h, fitStroke) against
// independent truth.
//
// The truth is a G2 chain of 1 to 5 LA segments with known alphas and joints, built
// here segment by segment from the intrinsic form (core/la_segment.h): segment k + 1
// starts at the end of segment k with its tangent angle and its end curvature. Every
// joint is one the fitter can see: a curvature extremum (|kappa| increases on one side
// and decreases on the other) or an inflection (kappa = 0 on both sides, alpha < 0 on
// both, opposite signs). The chain is sampled like a tablet would: uniformly in arc
// length at unit spacing (LaSegment::sample with integer lengths), plus Gaussian noise
// of 0.1% of the bounding-box diagonal from std::mt19937 (seed stated per case;
// std::normal_distribution of libstdc++).
//
// Checks (the thresholds come from the issue unless a comment says otherwise):
//  - deviation from the noise-free truth, both ways: the fitted curve (densely sampled)
//    to the truth curve, and the truth's samples to the fitted curve, at most
//    FitResult::tolerance (the tolerance the pipeline used: the default 0.5% of the
//    diagonal, or the points' noise floor if that is larger; how often the floor was
//    used is printed at the end);
//  - segment count: the truth's, or at most one more;
//  - alpha of every fitted segment within 0.3 of the alpha of the truth segment its
//    midpoint falls on, when that truth segment has at least 100 samples (the error
//    distribution is printed at the end);
//  - g1 gap below 1e-9 rad and g2 gap below 1e-6 (G2 on, the default Newton solve);
//  - the same under rotation (1.1 rad), scaling (0.01 and 100), reversal of the points
//    and translation by (1e6, -2e6): deviation from the transformed truth within the fit's tolerance (so
//    relative to the diagonal), the same segment count as the untransformed fit, gaps
//    below the thresholds;
//  - the G2 methods: bisection and Newton both reach g2 < 1e-6 with g1 < 1e-9; with G2
//    off only g1 < 1e-9 holds (and the curvature gaps are really left open).

#include "fitting/pipeline.h"
#include "fitting/user_edits.h"
#include "tests/shared_data_sets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/curve.h"
#include "core/la_segment.h"
#include "fitting/chain_fit.h"
#include "fitting/quality.h"
#include "fitting/stage7.h"

namespace la {
namespace {

constexpr double kPi = std::numbers::pi;

// From the issue.
constexpr double kNoiseFraction = 1e-3;       // noise standard deviation / diagonal
constexpr double kG1Threshold = 1e-9;         // radians
constexpr double kG2Threshold = 1e-6;         // relative gap (DESIGN.md section 6)
constexpr double kAlphaTolerance = 0.3;
// Ours: an alpha whose standard error is at most this is determined to kAlphaTolerance
// at three standard errors (see AlphaMatchesTheTruthAsFarAsThePointsDetermineIt).
constexpr double kIdentifiable = 0.1;
constexpr std::size_t kAlphaMinSamples = 100;  // truth segments shorter than this are not compared
constexpr int kMaxExtraSegments = 1;

// Ours. The fitted curve is sampled for the deviation check every kDenseStepFraction
// of the diagonal (0.1%: the noise level, a fifth of the default tolerance).
constexpr double kDenseStepFraction = 1e-3;
// Resolution of the deviation measurement relative to the diagonal: the polyline sagitta
// asked of distancesToCurve (fitting/quality.h; finer than the quality figures' 1e-5)
// with a factor 2 to spare.
constexpr double kPolylineSagitta = 1e-6;
constexpr double kMeasurementResolution = 2 * kPolylineSagitta;
// Random chains: turning per segment 0.4..1.7 rad (the issue: 0.3..2.0, well below pi;
// we stay 0.3 inside the pipeline's max_piece_turning = 2.0 so that noise in the
// smoothed turning does not split a segment by itself), lengths 100..400 units (so
// every segment has >= 100 samples at unit spacing).
constexpr double kMinTurning = 0.4, kMaxTurning = 1.7;
constexpr double kMinLength = 100.0, kMaxLength = 400.0;
// Curvature ratio across an extremum segment: large enough that the extremum is far
// above the segmentation's significance (8% of the largest |kappa|).
constexpr double kMinRatio = 2.5, kMaxRatio = 4.0;
// A generated stroke must not look closed or self-approaching (the clean-up would cut
// it or close it: close_fraction 6% of the diagonal, crossing reach twice that), nor
// have curvature so high that the corner detector (1 rad within 3% of the length)
// could fire: the truth has neither corners nor a closure.
constexpr double kMinEndGapFraction = 0.3;
constexpr double kMinSelfGapFraction = 0.06;
constexpr double kMaxTurnInCornerWindow = 0.6;  // radians within 3% of the stroke length

// ---------------------------------------------------------------------------------
// Truth chains.

struct SegmentSpec {
  double alpha, length, kappa_start, kappa_end;  // signed curvatures
};

struct Truth {
  std::string name;
  unsigned seed = 0;                    // of the chain (random cases) and of the noise
  Curve curve;                          // noise-free
  std::vector<Vec2> samples;            // unit spacing in arc length, noise-free
  std::vector<int> segment_of;          // truth segment of each sample
  std::vector<std::size_t> samples_per_segment;
  double diagonal = 0.0;
  std::vector<Vec2> noisy;              // the stroke given to the fitter
};

Curve buildChain(const std::vector<SegmentSpec>& specs, Vec2 start, double theta0) {
  Curve curve;
  for (const SegmentSpec& s : specs) {
    const LaSegment seg = std::isinf(s.alpha) ? LaSegment::arc(s.length, start, theta0, s.kappa_start)
                                              : LaSegment(s.alpha, s.length, start, theta0, s.kappa_start, s.kappa_end);
    start = seg.end(1e-14);
    theta0 = seg.theta(seg.length());
    curve.pieces.push_back({seg, false});
  }
  return curve;
}

double boxDiagonal(const std::vector<Vec2>& p) {
  Vec2 lo = p.front(), hi = p.front();
  for (const Vec2& q : p) lo = lo.cwiseMin(q), hi = hi.cwiseMax(q);
  return (hi - lo).norm();
}

// Samples at unit spacing (segment lengths are integers), the joints once.
void sampleTruth(Truth& t) {
  t.samples.clear();
  t.segment_of.clear();
  t.samples_per_segment.assign(t.curve.pieces.size(), 0);
  for (std::size_t k = 0; k < t.curve.pieces.size(); ++k) {
    const LaSegment& seg = t.curve.pieces[k].segment;
    const int n = static_cast<int>(std::lround(seg.length())) + 1;
    const CurveSamples smp = seg.sample(std::max(n, 2));
    for (std::size_t i = (k == 0 ? 0 : 1); i < smp.size(); ++i) {
      t.samples.push_back(smp.point[i]);
      t.segment_of.push_back(static_cast<int>(k));
    }
    t.samples_per_segment[k] = smp.size();
  }
  t.diagonal = boxDiagonal(t.samples);
}

void addNoise(Truth& t) {
  std::mt19937 rng(t.seed);
  std::normal_distribution<double> noise(0.0, kNoiseFraction * t.diagonal);
  t.noisy.clear();
  for (const Vec2& p : t.samples) t.noisy.push_back(p + Vec2(noise(rng), noise(rng)));
}

// The generated stroke must be a fair open test: ends apart, no near self-approach,
// curvature below what the corner detector would take for a corner.
bool acceptable(const Truth& t) {
  const auto& p = t.samples;
  const double diag = t.diagonal;
  if ((p.front() - p.back()).norm() < kMinEndGapFraction * diag) return false;
  const std::size_t far = p.size() / 4;  // samples this far apart along the stroke must stay apart
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = i + far; j < p.size(); ++j)
      if ((p[i] - p[j]).norm() < kMinSelfGapFraction * diag) return false;
  double kmax = 0.0, total = 0.0;
  for (const CurvePiece& piece : t.curve.pieces) {
    kmax = std::max({kmax, std::abs(piece.segment.kappaStart()), std::abs(piece.segment.kappaEnd())});
    total += piece.segment.length();
  }
  return kmax * 0.03 * total <= kMaxTurnInCornerWindow;
}

// A random chain of n segments whose curvature alternates between increasing and
// decreasing |kappa|; a decreasing segment that is not the last ends in an inflection
// with probability 1/2 (then it and the next segment get alpha in [-2, -0.4]: alpha < 0
// is required, and alpha near 0- puts all the turning at the far end).
std::vector<SegmentSpec> randomSpecs(int n, std::mt19937& rng) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  auto uni = [&](double a, double b) { return a + (b - a) * u01(rng); };
  for (;;) {
    std::vector<SegmentSpec> specs;
    double sign = u01(rng) < 0.5 ? 1.0 : -1.0;
    bool increasing = u01(rng) < 0.5;
    double k_prev = uni(0.003, 0.01);  // |kappa| at the start of the segment
    bool ok = true;
    for (int k = 0; k < n && ok; ++k) {
      const bool from_zero = k_prev == 0.0;
      const bool to_inflection = !increasing && k + 1 < n && u01(rng) < 0.5;
      ok = false;
      for (int attempt = 0; attempt < 200 && !ok; ++attempt) {
        const double alpha = (from_zero || to_inflection) ? uni(-2.0, -0.4) : uni(-2.0, 3.0);
        double k_end;
        if (to_inflection) k_end = 0.0;
        else if (from_zero) k_end = uni(0.004, 0.015);
        else if (increasing) k_end = k_prev * uni(kMinRatio, kMaxRatio);
        else k_end = k_prev / uni(kMinRatio, kMaxRatio);
        const double turning = uni(kMinTurning, kMaxTurning);
        const double k0 = from_zero ? 0.0 : sign * k_prev, k1 = to_inflection ? 0.0 : sign * k_end;  // no -0.0
        const double unit = std::abs(LaSegment(alpha, 1.0, Vec2::Zero(), 0.0, k0, k1).turning());
        const double length = std::round(turning / unit);
        if (length < kMinLength || length > kMaxLength) continue;
        const double real_turning = unit * length;
        if (real_turning < kMinTurning - 0.05 || real_turning > kMaxTurning + 0.05) continue;
        specs.push_back({alpha, length, k0, k1});
        k_prev = k_end;
        ok = true;
      }
      if (to_inflection) sign = -sign;
      increasing = !increasing;
    }
    if (ok) return specs;
  }
}

Truth randomTruth(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  for (int attempt = 0;; ++attempt) {
    if (attempt > 10000) throw std::runtime_error("no acceptable chain for seed " + std::to_string(seed));
    Truth t;
    t.seed = seed;
    t.name = "chain" + std::to_string(n) + "_seed" + std::to_string(seed);
    const std::vector<SegmentSpec> specs = randomSpecs(n, rng);
    t.curve = buildChain(specs, Vec2(100.0 * u01(rng), 100.0 * u01(rng)), 2.0 * kPi * u01(rng));
    sampleTruth(t);
    if (!acceptable(t)) continue;
    addNoise(t);
    return t;
  }
}

Truth fixedTruth(const std::string& name, const std::vector<SegmentSpec>& specs, unsigned seed) {
  Truth t;
  t.name = name;
  t.seed = seed;
  t.curve = buildChain(specs, Vec2(20.0, -30.0), 0.3);
  sampleTruth(t);
  addNoise(t);
  return t;
}

// The cases: random chains of 1..5 segments, 5 seeds each, and three classics. The seed
// of chain n, repetition k is 1000 n + k; it seeds both the chain's parameters and (in
// a fresh std::mt19937) the noise. The classics' noise seeds are 71, 72, 73.
constexpr int kSeedsPerSize = 5;
constexpr int kMaxSegments = 5;
constexpr int kRandomCases = kSeedsPerSize * kMaxSegments;
constexpr int kCaseCount = kRandomCases + 3;

Truth makeCase(int index) {
  if (index < kRandomCases) {
    const int n = 1 + index / kSeedsPerSize;
    const unsigned seed = 1000u * n + index % kSeedsPerSize;
    return randomTruth(n, seed);
  }
  switch (index - kRandomCases) {
    case 0:  // a circular arc: radius 200, 1.5 rad
      return fixedTruth("circle_arc", {{std::numeric_limits<double>::infinity(), 300.0, 0.005, 0.005}}, 71);
    case 1:  // a clothoid through an inflection: kappa 0.008 -> 0 -> -0.008, 1.2 rad each side
      return fixedTruth("clothoid_inflection", {{-1.0, 300.0, 0.008, 0.0}, {-1.0, 300.0, 0.0, -0.008}}, 72);
    default:  // a logarithmic spiral (rho linear in s), rho 250 -> 83.3: turning ln(3) * 167 / 166.7 = 1.10 rad
      return fixedTruth("log_spiral", {{1.0, 167.0, 0.004, 0.012}}, 73);
  }
}

const Truth& truthCase(int index) {
  static std::map<int, Truth> cache;
  auto it = cache.find(index);
  if (it == cache.end()) it = cache.emplace(index, makeCase(index)).first;
  return it->second;
}

// ---------------------------------------------------------------------------------
// Transforms of the stroke (and of the truth with it).

enum class Transform { kNone, kRotate, kScaleSmall, kScaleLarge, kReverse, kTranslate };
constexpr double kRotation = 1.1;
const Vec2 kFarAway(1e6, -2e6);  // a scan's coordinates in micrometres, say

const char* toName(Transform t) {
  switch (t) {
    case Transform::kNone: return "plain";
    case Transform::kRotate: return "rotated";
    case Transform::kScaleSmall: return "scaled0_01";
    case Transform::kScaleLarge: return "scaled100";
    case Transform::kReverse: return "reversed";
    case Transform::kTranslate: return "moved_far";
  }
  return "?";
}

struct Similarity {
  double angle = 0.0, scale = 1.0;
  Vec2 shift = Vec2::Zero();
  Vec2 apply(const Vec2& p) const {
    const double c = std::cos(angle), s = std::sin(angle);
    return scale * Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y()) + shift;
  }
};

Similarity similarityOf(Transform t) {
  switch (t) {
    case Transform::kRotate: return {kRotation, 1.0};
    case Transform::kScaleSmall: return {0.0, 0.01};
    case Transform::kScaleLarge: return {0.0, 100.0};
    case Transform::kTranslate: return {0.0, 1.0, kFarAway};
    default: return {};
  }
}

Truth transformed(const Truth& in, Transform t) {
  Truth out = in;
  if (t == Transform::kNone) return out;
  if (t == Transform::kReverse) {
    out.curve.pieces.clear();
    for (auto it = in.curve.pieces.rbegin(); it != in.curve.pieces.rend(); ++it)
      out.curve.pieces.push_back({it->segment.reversed(), false});
    std::reverse(out.samples.begin(), out.samples.end());
    std::reverse(out.segment_of.begin(), out.segment_of.end());
    for (int& k : out.segment_of) k = static_cast<int>(in.curve.pieces.size()) - 1 - k;
    std::reverse(out.samples_per_segment.begin(), out.samples_per_segment.end());
    std::reverse(out.noisy.begin(), out.noisy.end());
    return out;
  }
  const Similarity sim = similarityOf(t);
  out.curve.pieces.clear();
  for (const CurvePiece& piece : in.curve.pieces) {
    const LaSegment& s = piece.segment;
    const LaSegment moved = std::isinf(s.alpha())
                                ? LaSegment::arc(s.length() * sim.scale, sim.apply(s.start()), s.theta0() + sim.angle,
                                                 s.kappaStart() / sim.scale)
                                : LaSegment(s.alpha(), s.length() * sim.scale, sim.apply(s.start()), s.theta0() + sim.angle,
                                            s.kappaStart() / sim.scale, s.kappaEnd() / sim.scale);
    out.curve.pieces.push_back({moved, false});
  }
  for (Vec2& p : out.samples) p = sim.apply(p);
  for (Vec2& p : out.noisy) p = sim.apply(p);
  out.diagonal = boxDiagonal(out.samples);
  return out;
}

Stroke strokeOf(const std::vector<Vec2>& points) {
  Stroke stroke;
  for (std::size_t i = 0; i < points.size(); ++i) {
    StrokeSample s;
    s.p = points[i];
    s.t = 8.0 * static_cast<double>(i);  // a 125 Hz tablet
    stroke.samples.push_back(s);
  }
  return stroke;
}

// ---------------------------------------------------------------------------------
// Measurements.

// Dense samples of a curve, with the fitted segment and arc-length fraction of each.
struct Dense {
  std::vector<Vec2> point;
  std::vector<int> segment;
  std::vector<double> fraction;
};

Dense denseSamples(const Curve& curve, double step) {
  Dense out;
  for (std::size_t k = 0; k < curve.pieces.size(); ++k) {
    const LaSegment& seg = curve.pieces[k].segment;
    const int n = std::max(8, static_cast<int>(std::ceil(seg.length() / step)) + 1);
    const CurveSamples smp = seg.sample(n);
    for (std::size_t i = 0; i < smp.size(); ++i) {
      out.point.push_back(smp.point[i]);
      out.segment.push_back(static_cast<int>(k));
      out.fraction.push_back(smp.s[i] / seg.length());
    }
  }
  return out;
}

// Largest value and where it is; infinite if any value is not finite.
std::pair<double, std::size_t> maxOf(const std::vector<double>& v) {
  double m = 0.0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) return {std::numeric_limits<double>::infinity(), i};
    if (v[i] > m) m = v[i], at = i;
  }
  return {m, at};
}

// Both-way deviation between the fitted curve and the noise-free truth, and where the
// largest of each is (fitted segment and fraction of its length; truth sample index).
struct Deviation {
  double fit_to_truth = 0.0, truth_to_fit = 0.0;
  int worst_segment = -1;
  double worst_fraction = 0.0;
  std::size_t worst_truth_sample = 0, truth_samples = 0;
  double max() const { return std::max(fit_to_truth, truth_to_fit); }
  std::string where() const {
    char buf[200];
    std::snprintf(buf, sizeof buf, "fitted->truth worst at fitted segment %d, %.2f of its length; truth->fitted worst at truth sample %zu of %zu",
                  worst_segment, worst_fraction, worst_truth_sample, truth_samples);
    return buf;
  }
};

Deviation deviationFromTruth(const Curve& fitted, const Truth& truth) {
  Deviation d;
  if (fitted.pieces.empty()) {
    d.fit_to_truth = d.truth_to_fit = std::numeric_limits<double>::infinity();
    return d;
  }
  const Dense dense = denseSamples(fitted, kDenseStepFraction * truth.diagonal);
  const auto [a, at_a] = maxOf(distancesToCurve(truth.curve, dense.point, truth.diagonal, kPolylineSagitta));
  const auto [b, at_b] = maxOf(distancesToCurve(fitted, truth.samples, truth.diagonal, kPolylineSagitta));
  d.fit_to_truth = a;
  d.truth_to_fit = b;
  d.worst_segment = dense.segment[at_a];
  d.worst_fraction = dense.fraction[at_a];
  d.worst_truth_sample = at_b;
  d.truth_samples = truth.samples.size();
  return d;
}

// The truth segment under the midpoint of each fitted segment (nearest truth sample).
std::vector<int> matchSegments(const Curve& fitted, const Truth& truth) {
  std::vector<int> match;
  for (const CurvePiece& piece : fitted.pieces) {
    const Vec2 mid = piece.segment.position(0.5 * piece.segment.length());
    std::size_t best = 0;
    double best_d = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < truth.samples.size(); ++i) {
      const double d = (truth.samples[i] - mid).squaredNorm();
      if (d < best_d) best_d = d, best = i;
    }
    match.push_back(truth.segment_of[best]);
  }
  return match;
}

std::string describeTruth(const Truth& t) {
  std::string s = t.name + " (seed " + std::to_string(t.seed) + ", diagonal " + std::to_string(t.diagonal) + "):";
  for (const CurvePiece& p : t.curve.pieces) {
    char buf[160];
    std::snprintf(buf, sizeof buf, " [alpha %.3g L %.0f kappa %.4g->%.4g turn %.2f]", p.segment.alpha(),
                  p.segment.length(), p.segment.kappaStart(), p.segment.kappaEnd(), p.segment.turning());
    s += buf;
  }
  return s;
}

std::string describeFit(const FitResult& r) {
  std::string s = "fit: " + std::to_string(r.curve.pieces.size()) + " segments, tolerance " + std::to_string(r.tolerance);
  for (const CurvePiece& p : r.curve.pieces) {
    char buf[160];
    std::snprintf(buf, sizeof buf, " [alpha %.3g L %.4g kappa %.4g->%.4g]", p.segment.alpha(), p.segment.length(),
                  p.segment.kappaStart(), p.segment.kappaEnd());
    s += buf;
  }
  for (const std::string& w : r.warnings) s += "\n  warning: " + w;
  return s;
}

// ---------------------------------------------------------------------------------
// Statistics over the whole run, printed once at the end.

struct RunStats {
  int fits = 0, tolerance_raised = 0;
  std::vector<double> alpha_errors;
  std::vector<double> identifiable_alpha_errors;  // of segments whose standard error is at most kIdentifiable
  std::vector<double> optimum_alpha_errors;       // of the least-squares optimum nearest the truth (same segments)
  std::vector<double> deviation_ratios;  // max deviation from truth / tolerance
  std::vector<double> ssr_ratios;        // sum of squared distances of the points: fitted chain / truth
};
RunStats& stats() {
  static RunStats s;
  return s;
}

class StatsPrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    RunStats& s = stats();
    std::printf("[ stats    ] fits against truth: %d; tolerance raised to the noise floor in %d\n", s.fits,
                s.tolerance_raised);
    auto quantiles = [](std::vector<double> v, const char* what) {
      if (v.empty()) return;
      std::sort(v.begin(), v.end());
      auto q = [&](double f) { return v[std::min(v.size() - 1, static_cast<std::size_t>(f * (v.size() - 1) + 0.5))]; };
      std::printf("[ stats    ] %s: n %zu, median %.3g, 90%% %.3g, max %.3g\n", what, v.size(), q(0.5), q(0.9),
                  v.back());
    };
    quantiles(s.alpha_errors, "|alpha - truth| (segments with >= 100 samples)");
    quantiles(s.identifiable_alpha_errors, "|alpha - truth| (of those, standard error <= 0.1)");
    quantiles(s.optimum_alpha_errors, "|alpha - truth| of the least-squares optimum started from the truth");
    for (const auto& [errors, what] : {std::pair{&s.alpha_errors, "fitted"}, std::pair{&s.identifiable_alpha_errors, "fitted, standard error <= 0.1"},
                                        std::pair{&s.optimum_alpha_errors, "least-squares optimum from the truth"}}) {
      const std::size_t over = std::count_if(errors->begin(), errors->end(), [](double e) { return !(e <= kAlphaTolerance); });
      if (!errors->empty())
        std::printf("[ stats    ] alpha errors above %.2g (%s): %zu of %zu\n", kAlphaTolerance, what, over, errors->size());
    }
    quantiles(s.deviation_ratios, "max deviation from truth / tolerance");
    quantiles(s.ssr_ratios, "sum of squared distances of the points, fitted / truth");
  }
};
[[maybe_unused]] ::testing::Environment* const kStatsPrinter = ::testing::AddGlobalTestEnvironment(new StatsPrinter);

bool raisedTolerance(const FitResult& r) { return r.tolerance > r.requested_tolerance; }

FitResult fit(const std::vector<Vec2>& points, const FitOptions& options = {}) {
  FitResult r = fitStroke(strokeOf(points), options);
  ++stats().fits;
  if (raisedTolerance(r)) ++stats().tolerance_raised;
  return r;
}

void expectGaps(const FitResult& r) {
  EXPECT_LT(r.quality.g1_gap, kG1Threshold) << "g1 gap (rad)";
  EXPECT_LT(r.quality.g2_gap, kG2Threshold) << "g2 gap (relative)";
}

void expectNoCornersOpen(const FitResult& r) {
  EXPECT_FALSE(r.curve.closed) << "an open truth stroke was closed";
  EXPECT_EQ(r.cleaned.corners.size(), 0u) << "corners found on a smooth truth stroke";
  EXPECT_EQ(r.cleaned.trimmed_start + r.cleaned.trimmed_end, 0u)
      << "hooks trimmed from a smooth truth stroke (start " << r.cleaned.trimmed_start << ", end "
      << r.cleaned.trimmed_end << ")";
}

// Where the fitted curve's ends are relative to the stroke's end points (a dangling end
// is a typical source of deviation: the points can be close to a curve that runs on).
std::string describeEnds(const FitResult& r, const Truth& truth) {
  if (r.curve.pieces.empty()) return "";
  const LaSegment& first = r.curve.pieces.front().segment;
  const LaSegment& last = r.curve.pieces.back().segment;
  const Vec2 a = first.start(), b = last.end();
  auto along = [](const Vec2& from, const Vec2& to, double theta) { return unitVector(theta).dot(to - from); };
  char buf[400];
  std::snprintf(buf, sizeof buf,
                "fitted start: %.3g from the first input point, %.3g from the truth start (%.3g along the truth tangent); "
                "fitted end: %.3g from the last input point, %.3g from the truth end (%.3g along the truth tangent)",
                (a - truth.noisy.front()).norm(), (a - truth.samples.front()).norm(),
                along(truth.samples.front(), a, truth.curve.pieces.front().segment.theta0()),
                (b - truth.noisy.back()).norm(), (b - truth.samples.back()).norm(),
                along(truth.samples.back(), b,
                      truth.curve.pieces.back().segment.theta(truth.curve.pieces.back().segment.length())));
  return buf;
}

Deviation expectDeviation(const FitResult& r, const Truth& truth) {
  const Deviation d = deviationFromTruth(r.curve, truth);
  EXPECT_LE(d.max(), r.tolerance) << "deviation from the noise-free truth: fitted->truth " << d.fit_to_truth
                                  << ", truth->fitted " << d.truth_to_fit << " (relative to diagonal "
                                  << d.max() / truth.diagonal << ") > tolerance " << r.tolerance << " ("
                                  << r.tolerance / truth.diagonal << " of the diagonal)\n" << d.where()
                                  << "\n" << describeEnds(r, truth);
  return d;
}

// ---------------------------------------------------------------------------------
// The tests.

std::string caseName(int index, Transform transform) {
  std::string name;
  if (index < kRandomCases) {
    name = "chain" + std::to_string(1 + index / kSeedsPerSize) + "_seed" + std::to_string(index % kSeedsPerSize);
  } else {
    const char* names[] = {"circle_arc", "clothoid_inflection", "log_spiral"};
    name = names[index - kRandomCases];
  }
  return name + "_" + toName(transform);
}

using CaseParam = std::tuple<int, Transform>;

class PipelineTruthTest : public ::testing::TestWithParam<CaseParam> {};

TEST_P(PipelineTruthTest, FitsTheTruthWithinToleranceAndG2) {
  const auto [index, transform] = GetParam();
  const Truth& base = truthCase(index);
  const Truth truth = transformed(base, transform);
  const FitResult r = fit(truth.noisy);
  ASSERT_FALSE(r.curve.pieces.empty()) << describeTruth(base) << "\n" << describeFit(r);
  const Deviation dev = expectDeviation(r, truth);
  stats().deviation_ratios.push_back(dev.max() / r.tolerance);
  expectGaps(r);
  expectNoCornersOpen(r);
  std::printf("[ case     ] %-28s segments %zu/%zu  dev/tol %.3f  tol/diag %.4f%s  g1 %.1e g2 %.1e\n",
              caseName(index, transform).c_str(), r.curve.pieces.size(), truth.curve.pieces.size(),
              dev.max() / r.tolerance, r.tolerance / truth.diagonal, raisedTolerance(r) ? " (raised)" : "",
              r.quality.g1_gap, r.quality.g2_gap);
  if (HasFailure()) std::printf("%s\n%s\n", describeTruth(base).c_str(), describeFit(r).c_str());
}

// Segment count: the truth's, or at most one more (the issue), and under every transform
// the same count as the untransformed fit.
TEST_P(PipelineTruthTest, SegmentCountMatchesTheTruth) {
  const auto [index, transform] = GetParam();
  const Truth& base = truthCase(index);
  const Truth truth = transformed(base, transform);
  const FitResult r = fit(truth.noisy);
  ASSERT_FALSE(r.curve.pieces.empty()) << describeTruth(base) << "\n" << describeFit(r);
  const std::size_t n_truth = truth.curve.pieces.size(), n_fit = r.curve.pieces.size();
  EXPECT_GE(n_fit, n_truth) << "segment count: truth " << n_truth << ", fitted " << n_fit;
  EXPECT_LE(n_fit, n_truth + kMaxExtraSegments) << "segment count: truth " << n_truth << ", fitted " << n_fit;
  if (transform != Transform::kNone) {
    const FitResult plain = fit(base.noisy);
    EXPECT_EQ(n_fit, plain.curve.pieces.size()) << "segment count changed by the transform " << toName(transform)
                                                << ": plain fit " << plain.curve.pieces.size() << ", transformed "
                                                << n_fit << "\nplain " << describeFit(plain);
  }
  std::printf("[ case     ] %-28s segments %zu/%zu\n", caseName(index, transform).c_str(), n_fit, n_truth);
  if (HasFailure()) std::printf("%s\n%s\n", describeTruth(base).c_str(), describeFit(r).c_str());
}

// Alpha of every fitted segment whose truth segment has 100 or more points, against the
// truth's. The issue asks for 0.3; at 0.1% noise the points do not always determine
// alpha that well: a segment whose curvature changes by a factor 2.5 over a turn of
// half a radian looks nearly the same for alphas a whole unit apart (measured: the sum
// of squared distances of the fitted chain is no larger than the truth's, with alpha off
// by 1; and fitChain run to convergence on all the points from the truth itself ends
// more than 0.3 from the truth on 28 of the 78 segments, printed at the end as the
// "least-squares optimum from the truth"). The fit reports each alpha's standard error (FitResult::pieces, from the
// least-squares covariance); where it is at most kIdentifiable the points determine
// alpha to 0.3 at three standard errors, and that is asked; elsewhere, three standard
// errors. The counts of both kinds are printed at the end (stats).
// (alpha is compared on the untransformed chains only: its own suite)
class PipelineAlphaTest : public ::testing::TestWithParam<CaseParam> {};

TEST_P(PipelineAlphaTest, AlphaMatchesTheTruthAsFarAsThePointsDetermineIt) {
  const auto [index, transform] = GetParam();
  const Truth& truth = truthCase(index);
  FitOptions options;
  options.alpha_standard_errors = true;
  const FitResult r = fit(truth.noisy, options);
  ASSERT_EQ(r.curve.pieces.size(), truth.curve.pieces.size()) << describeFit(r);
  std::string alphas;
  auto ssr = [&](const Curve& c) {
    double sum = 0.0;
    for (double d : distancesToCurve(c, truth.noisy, truth.diagonal, kPolylineSagitta)) sum += d * d;
    return sum;
  };
  const double ssr_ratio = ssr(r.curve) / ssr(truth.curve);
  stats().ssr_ratios.push_back(ssr_ratio);
  // What the points say, independently of the pipeline: least squares on all the points
  // run to convergence from the truth itself (the estimate nearest the truth).
  std::vector<LaSegment> truth_chain;
  for (const CurvePiece& p : truth.curve.pieces) truth_chain.push_back(p.segment);
  ChainFitOptions converged;
  converged.max_iterations = 200;
  converged.min_alpha = -10.0, converged.max_alpha = 10.0;
  const ChainFitResult optimum = fitChain(truth_chain, truth.noisy, {}, converged);
  const std::vector<int> match = matchSegments(r.curve, truth);
  for (std::size_t i = 0; i < r.curve.pieces.size(); ++i) {
    const LaSegment& truth_seg = truth.curve.pieces[match[i]].segment;
    if (truth.samples_per_segment[match[i]] < kAlphaMinSamples || std::isinf(truth_seg.alpha())) continue;
    const double got = r.curve.pieces[i].segment.alpha(), want = truth_seg.alpha();
    const double se = r.pieces[i].alpha_standard_error, err = std::abs(got - want);
    ASSERT_TRUE(std::isfinite(se)) << "segment " << i << " has no standard error";
    stats().alpha_errors.push_back(err);
    if (se <= kIdentifiable) stats().identifiable_alpha_errors.push_back(err);
    stats().optimum_alpha_errors.push_back(std::abs(optimum.segments[match[i]].alpha() - want));
    const double allowed = se <= kIdentifiable ? kAlphaTolerance : std::max(kAlphaTolerance, 3.0 * se);
    EXPECT_LE(err, allowed) << "alpha of fitted segment " << i << ": got " << got << " (standard error " << se
                            << "), truth segment " << match[i] << " has " << want;
    char buf[80];
    std::snprintf(buf, sizeof buf, " %zu->%d:%.2f/%.2f(%.2f)", i, match[i], got, want, se);
    alphas += buf;
  }
  std::printf("[ case     ] %-28s SSR fit/truth %.3f, alpha fit/truth(standard error)%s\n", caseName(index, transform).c_str(),
              ssr_ratio, alphas.c_str());
  if (HasFailure()) std::printf("%s\n%s\n", describeTruth(truth).c_str(), describeFit(r).c_str());
}

// 6,400 exact samples of a sine (amplitude 10, 60 long), fitted at 0.05% of the
// diagonal: the B-spline with its ends free ran its start away, 400 tolerances off.
Stroke denselySampledSine() {
  Stroke stroke;
  for (int k = 0; k < 6400; ++k) {
    const double x = 60.0 * k / 6399.0;
    stroke.samples.push_back({Vec2(x, 10.0 * std::sin(x / 10.0))});
  }
  return stroke;
}

// Stages 1-6 alone: the spline is fitted through the stroke's ends where its free ends
// miss (SmoothingOptions::through_ends_beyond), and the paper's chain keeps the
// tolerance, G2 (from the spline astray: 75 tolerances off, kinked).
TEST(PipelinePaperOnly, ADenselySampledExactSineKeepsATightTolerance) {
  FitOptions paper;
  paper.polish = false;
  paper.tolerance_fraction = 0.0005;
  const FitResult r = fitStroke(denselySampledSine(), paper);
  ASSERT_FALSE(r.curve.pieces.empty());
  EXPECT_LE(r.quality.max_dev, r.tolerance);
  EXPECT_LT(r.quality.g1_gap, kG1Threshold);
  EXPECT_LT(r.quality.g2_gap, kG2Threshold);
}

// The whole fit: stage 7 starts from the spline through the ends where its free ends
// miss by far, and the sine comes back smooth: 5 segments, 2 reversals (from the spline
// astray: a corner where none was drawn, 7 segments, 4 reversals, in half a second).
TEST(PipelinePolish, ADenselySampledExactSineHasNoCorner) {
  FitOptions options;
  options.tolerance_fraction = 0.0005;
  const FitResult r = fitStroke(denselySampledSine(), options);
  ASSERT_FALSE(r.curve.pieces.empty());
  EXPECT_EQ(r.quality.corners, 0);
  EXPECT_LE(r.quality.max_dev, r.tolerance);
  EXPECT_LE(r.quality.extrema_dense, 2);
}

// Stage 7 against stages 1-6 alone (FitOptions::polish false: the paper's pipeline) on
// every truth chain: it stays within the tolerance of the noise-free truth and G2, and
// its alphas are, summed over the chains, much closer to the truth's (printed with the
// paper's).
TEST(PipelinePolish, StaysWithinToleranceG2AndBringsAlphaCloser) {
  FitOptions paper;
  paper.polish = false;
  double error_paper = 0.0, error_fit = 0.0;
  int counted = 0;
  for (int index = 0; index < kCaseCount; ++index) {
    const Truth& truth = truthCase(index);
    const FitResult plain = fit(truth.noisy, paper), r = fit(truth.noisy);
    SCOPED_TRACE(caseName(index, Transform::kNone));
    ASSERT_FALSE(r.curve.pieces.empty());
    expectDeviation(r, truth);
    expectGaps(r);
    if (r.curve.pieces.size() != plain.curve.pieces.size()) continue;
    const std::vector<int> match = matchSegments(r.curve, truth), match_plain = matchSegments(plain.curve, truth);
    for (std::size_t i = 0; i < r.curve.pieces.size(); ++i) {
      const LaSegment& want = truth.curve.pieces[match[i]].segment;
      if (truth.samples_per_segment[match[i]] < kAlphaMinSamples || std::isinf(want.alpha()) || match[i] != match_plain[i])
        continue;
      error_fit += std::abs(r.curve.pieces[i].segment.alpha() - want.alpha());
      error_paper += std::abs(plain.curve.pieces[i].segment.alpha() - want.alpha());
      ++counted;
    }
  }
  std::printf("[ polish   ] mean |alpha - truth| over %d segments: %.3f stages 1-6, %.3f with stage 7\n", counted,
              error_paper / counted, error_fit / counted);
  ASSERT_GT(counted, 20);
  EXPECT_LT(error_fit, 0.75 * error_paper);
}

// A closed outline whose one straight edge is not sampled (as font outlines come: the
// closing stem of DejaVu's g): up the right side from a corner, three quarters of a
// circle, and back along the bottom edge, which meets the circle tangentially and has
// no points. The fitted contour must follow that edge too, G2, with no loop in the gap.
TEST(PipelineGaps, FollowsAnOutlinesUnsampledStraightEdge) {
  constexpr double kRadius = 100.0, kSpacing = 2.0;
  const double quarter = 0.5 * std::numbers::pi;
  Curve truth;
  truth.closed = true;
  truth.pieces.push_back({LaSegment::arc(kRadius, {kRadius, -kRadius}, quarter, 0.0), true});
  truth.pieces.push_back({LaSegment::arc(3.0 * quarter * kRadius, {kRadius, 0.0}, quarter, 1.0 / kRadius), false});
  truth.pieces.push_back({LaSegment::arc(kRadius, {0.0, -kRadius}, 0.0, 0.0), true});
  std::vector<Vec2> points;
  for (std::size_t k = 0; k < 2; ++k) {  // the last edge unsampled
    const LaSegment& s = truth.pieces[k].segment;
    const int n = static_cast<int>(std::round(s.length() / kSpacing));
    for (int i = 0; i < n; ++i) points.push_back(s.position(s.length() * i / n));
  }
  points.push_back(truth.pieces[1].segment.end());
  FitOptions options;
  options.cleanup.assume_closed = true;
  const FitResult r = fit(points, options);
  ASSERT_FALSE(r.curve.pieces.empty());
  EXPECT_TRUE(r.curve.closed);
  expectGaps(r);
  EXPECT_LE(r.quality.max_dev, r.tolerance);
  const double diagonal = boxDiagonal(points);
  const Dense dense = denseSamples(r.curve, kDenseStepFraction * diagonal);
  const auto [worst, at] = maxOf(distancesToCurve(truth, dense.point, diagonal, kPolylineSagitta));
  EXPECT_LE(worst, r.tolerance) << "at fitted segment " << dense.segment[at] << " of " << r.curve.pieces.size() << "\n"
                                << describeFit(r);
}

// An arc drawn with a mouse: the pointer moves about a pixel per sample, its position
// rounded to whole pixels, with hand tremor of 0.5 pixel that lasts two samples (a
// moving average). Such noise repeats over neighbouring samples, so differences of
// neighbours cancel much of it, and a noise floor taken from them alone leaves the
// tolerance below the tremor: the fit then follows it with 3-4 segments (4 of these 16
// strokes). One arc is what was drawn, and the noise floor must let the fit say so
// without straying from the true arc or raising the tolerance far beyond the noise.
TEST(PipelineNoise, MouseArcOnPixelsIsFittedAsAnArc) {
  constexpr double kRadius = 120.0, kSpacing = 1.2, kTremor = 0.5;
  constexpr int kTremorSamples = 2, kPoints = 120;
  const Vec2 origin(10.3, 20.7);
  Curve truth;
  truth.pieces.push_back({LaSegment::arc(kPoints * kSpacing, origin, 0.0, 1.0 / kRadius), false});
  // per coordinate: the tremor's deviation and the rounding's (uniform on a pixel)
  const double sigma = std::sqrt(kTremor * kTremor + 1.0 / 12.0);
  for (unsigned seed = 0; seed < 16; ++seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    std::vector<Vec2> shakes(kPoints + kTremorSamples);
    for (Vec2& v : shakes) v = {gauss(rng), gauss(rng)};
    std::vector<Vec2> points;
    for (int i = 0; i < kPoints; ++i) {
      Vec2 tremor = Vec2::Zero();
      for (int k = 0; k < kTremorSamples; ++k) tremor += shakes[i + k];
      const Vec2 p = truth.pieces[0].segment.position(i * kSpacing) + kTremor / std::sqrt(kTremorSamples) * tremor;
      points.emplace_back(std::round(p.x()), std::round(p.y()));
    }
    const FitResult r = fit(points, FitOptions{});
    ASSERT_FALSE(r.curve.pieces.empty()) << "seed " << seed;
    EXPECT_LE(r.curve.pieces.size(), 2u) << "seed " << seed << "\n" << describeFit(r);
    EXPECT_LE(r.quality.max_dev, r.tolerance) << "seed " << seed;
    EXPECT_LE(r.tolerance, 6.0 * sigma) << "seed " << seed;
    const double diagonal = boxDiagonal(points);
    const Dense dense = denseSamples(r.curve, kDenseStepFraction * diagonal);
    EXPECT_LE(maxOf(distancesToCurve(truth, dense.point, diagonal, kPolylineSagitta)).first, r.tolerance)
        << "seed " << seed;
  }
}

// A bowed polyline of three sides whose bends (about 1 rad each, spread over sparse
// samples 5.6 units apart) are not taken for corners, from a fuzzer of random strokes
// (its seed 32). Stages 5-6 find no G2 chain, and the chain read off the spline set off
// astray: a segment shot from the previous one's end curvature came out 408 units long
// where the spline ran 74, and the fit ended 25 units (20 tolerances) from the points.
// Started again from the spline's spans halved where the shot went astray, the curve is
// within the tolerance.
TEST(PipelineStarts, ASplineChainThatSetsOffAstrayIsStartedAgain) {
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int vertices = 3 + static_cast<int>(rng() % 5);
  ASSERT_NE(rng() % 3, 0u) << "the generator changed: this stroke is open";
  std::vector<Vec2> corner_points;
  Vec2 p(0, 0);
  double angle = uniform(rng) * 6.28;
  for (int i = 0; i < vertices; ++i) {
    corner_points.push_back(p);
    const double length = 30.0 + 150.0 * uniform(rng);
    angle += (uniform(rng) - 0.5) * 5.5;
    p += length * Vec2(std::cos(angle), std::sin(angle));
  }
  corner_points.push_back(p);
  const double spacing = 1.0 + 6.0 * uniform(rng), bow = (uniform(rng) - 0.5) * 0.6, sigma = 0.05 + 0.5 * uniform(rng);
  std::normal_distribution<double> noise(0.0, sigma);
  std::vector<Vec2> points;
  for (std::size_t i = 0; i + 1 < corner_points.size(); ++i) {
    const Vec2 d = corner_points[i + 1] - corner_points[i];
    const Vec2 normal(-d.y(), d.x());
    const int m = std::max(2, static_cast<int>(d.norm() / spacing));
    const double offset = uniform(rng);
    for (int k = 0; k < m; ++k) {
      const double t = (k + (i == 0 ? 0.0 : offset)) / m;
      const Vec2 q = corner_points[i] + t * d + bow * t * (1 - t) * normal;
      points.push_back(q + Vec2(noise(rng), noise(rng)));
    }
  }
  points.push_back(corner_points.back());
  ASSERT_EQ(points.size(), 56u) << "the generator changed";
  const FitResult r = fit(points, FitOptions{});
  ASSERT_FALSE(r.curve.pieces.empty());
  EXPECT_TRUE(r.cleaned.corners.empty());
  EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
  expectGaps(r);
}

// Two straight strokes meeting at a bend of 0.9 rad, under the corner angle (1 rad), so
// one smooth part: sampled every 5.6 units with noise 0.07, 12 seeds. Least squares
// followed the points' sharp vertex with a bend a fraction of the tolerance long (down
// to zero on 5 of the seeds), which no point can place: a spike in the curvature plot.
// Segments shorter than the tolerance are penalized (ChainFitOptions::min_length), so
// the bend spreads over at least half the tolerance, within the tolerance.
TEST(PipelineFairness, ABendUnderTheCornerAngleIsNoTighterThanTheToleranceTells) {
  constexpr double kSpacing = 5.6, kAngle = 0.9;
  const Vec2 a(0, 0), vertex(100, 0);
  const Vec2 b = vertex + 100.0 * Vec2(std::cos(kAngle), std::sin(kAngle));
  const int per_side = static_cast<int>(100.0 / kSpacing);
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.07);
    std::vector<Vec2> points;
    for (int k = 0; k <= 2 * per_side; ++k) {
      const Vec2 p = k <= per_side ? a + (static_cast<double>(k) / per_side) * (vertex - a)
                                   : vertex + (static_cast<double>(k - per_side) / per_side) * (b - vertex);
      points.push_back(p + Vec2(noise(rng), noise(rng)));
    }
    const FitResult r = fit(points, FitOptions{});
    ASSERT_FALSE(r.curve.pieces.empty());
    EXPECT_TRUE(r.cleaned.corners.empty());
    EXPECT_LE(r.quality.max_dev, r.tolerance);
    for (const CurvePiece& piece : r.curve.pieces) EXPECT_GE(piece.segment.length(), 0.5 * r.tolerance) << describeFit(r);
    expectGaps(r);
  }
}

// A pointed arch: two circular arcs of radius kArchRadius meeting at its apex, 12 samples
// a side, with noise of 0.5 units (seed `seed`).
constexpr double kArchRadius = 100.0;
std::vector<Vec2> pointedArch(unsigned seed) {
  constexpr int kPerSide = 12;
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.5);
  std::vector<Vec2> points;
  for (int k = 0; k < 2 * kPerSide - 1; ++k) {
    // (the left side about (kArchRadius, 0) from angle pi to 2 pi / 3, the right one
    // about the origin from pi / 3 to 0)
    const double s = static_cast<double>(k < kPerSide ? k : k - kPerSide + 1) / (kPerSide - 1);
    const Vec2 p = k < kPerSide ? Vec2(Vec2(kArchRadius, 0.0) + kArchRadius * unitVector(std::numbers::pi * (1.0 - s / 3.0)))
                                : Vec2(kArchRadius * unitVector(std::numbers::pi / 3.0 * (1.0 - s)));
    points.push_back(p + Vec2(noise(rng), noise(rng)));
  }
  return points;
}

// Each side of the arch (12 seeds) is one arc: no curvature extremum. The selection merges
// only at weak extrema, and a side's chain kept a strong one where the noise bent it
// (seed 2 here; 3 of 12 with numpy's noise): a side curling into its corner. Now each side
// is one LA segment.
TEST(PipelineFairness, APointedArchsSidesHaveNoCurvatureExtremum) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const FitResult r = fit(pointedArch(seed), FitOptions{});
    ASSERT_FALSE(r.curve.pieces.empty());
    EXPECT_EQ(r.quality.corners, 1) << describeFit(r);
    EXPECT_EQ(r.quality.max_extrema_per_part, 0) << describeFit(r);
    EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
    expectGaps(r);
  }
}

// The same arches: each side becomes the circular arc it was drawn as, so that the
// curvature never reverses (extrema_dense 0: the one jump at the apex is no reversal).
// As LA segments, the sides' slight trends reversed the curvature at the apex for every
// one of the 12 seeds (checked against the pipeline without the arcs).
TEST(PipelineFairness, APointedArchsSidesAreArcsWhoseCurvatureNeverReverses) {
  for (unsigned seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const FitResult r = fit(pointedArch(seed), FitOptions{});
    ASSERT_EQ(r.curve.pieces.size(), 2u) << describeFit(r);
    for (const CurvePiece& piece : r.curve.pieces) {
      EXPECT_TRUE(piece.segment.isCircular()) << describeFit(r);
      // (the arcs' radius within the noise's reach)
      EXPECT_NEAR(1.0 / std::abs(piece.segment.kappaStart()), kArchRadius, 0.2 * kArchRadius) << describeFit(r);
    }
    EXPECT_EQ(r.quality.extrema_dense, 0) << describeFit(r);
    EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
    expectGaps(r);
  }
}

// The crossbar of a drawn H (MMG's stylus set, H-01's second stroke) with noise of 1.2
// units: 12 samples, the first a pen-down hook. Fitted with the bound on the radius, it
// missed the tolerance with a joint on the bound; fitted again without the bound it
// missed too, so the curve kept the first miss (1.6 tolerances, warned). The bend on the
// bound made a corner keeps the tolerance, and nothing bends tighter than it. (Where the
// first fit bends on the bound beside the end hook instead, 2.3 tolerances off at the
// kink in the middle, whose corner there does not mend, the corner at the point farthest
// from the curve does; with glibc's FMA paths off that point is beside the kink, and the
// corners at it and at its refit's farthest point do.)
const std::vector<Vec2> kNoisyCrossbar = {{36.057, 99.816}, {58.523, 90.391}, {68.138, 86.135}, {71.919, 89.959},
                                          {79.402, 88.123}, {82.655, 85.613}, {87.014, 84.172}, {93.353, 83.209},
                                          {96.389, 83.349}, {103.054, 84.150}, {109.229, 83.541}, {108.211, 83.554}};
TEST(PipelineCorners, ABendOnTheBoundWhereTheFitMissesBecomesACorner) {
  const FitResult r = fitStroke(strokeOf(kNoisyCrossbar));
  EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
  EXPECT_GE(r.quality.min_radius, (1.0 - 1e-6) * r.tolerance);
  EXPECT_GE(r.quality.corners, 1);
  expectGaps(r);
}

// A noisy Omniglot stroke (Early_Aramaic 0251_13's second, with noise of 1.2 units,
// rounded): tiny parts between the corners the clean-up reads in its noise.
const std::vector<Vec2> kNoisyAramaic = {
    {69.694, -28.138}, {67.315, -30.492}, {66.893, -29.495}, {66.967, -32.449}, {66.352, -31.750}, {64.961, -32.896},
    {63.246, -34.183}, {67.250, -36.216}, {61.018, -36.377}, {59.985, -39.906}, {60.356, -39.374}, {58.792, -41.453},
    {55.971, -43.413}, {55.199, -44.842}, {57.575, -44.298}, {58.450, -47.843}, {54.095, -49.104}, {53.599, -47.077},
    {52.142, -49.695}, {52.550, -49.419}, {52.499, -52.586}, {48.026, -48.269}, {51.390, -53.909}, {49.419, -54.316},
    {46.817, -55.090}, {44.321, -61.004}, {43.595, -58.249}, {46.654, -58.877}, {42.765, -61.164}, {42.565, -59.720},
    {43.694, -64.150}, {44.085, -63.198}, {42.470, -63.701}, {42.993, -65.101}, {43.014, -68.189}, {40.491, -70.326},
    {41.178, -66.259}, {39.649, -69.271}, {38.816, -69.816}, {37.716, -71.650}, {35.199, -72.314}, {38.244, -70.657},
    {36.649, -72.668}, {33.417, -72.230}, {35.926, -72.879}, {34.280, -74.576}, {35.720, -74.020}, {34.982, -74.647},
    {33.187, -76.228}, {35.979, -74.728}, {35.756, -76.055}, {35.915, -75.559}, {37.192, -75.671}, {38.234, -76.536},
    {40.730, -74.597}, {41.573, -76.381}, {42.653, -75.532}, {41.560, -75.952}, {45.712, -77.241}, {45.759, -76.380},
    {45.116, -74.633}, {44.135, -71.707}, {47.884, -72.290}, {49.599, -72.481}, {44.860, -73.558}, {49.177, -70.755},
    {51.211, -73.299}, {52.465, -74.017}, {53.275, -69.455}, {52.061, -72.791}, {57.184, -71.810}, {56.587, -71.499},
    {55.920, -69.131}, {59.897, -69.004}, {60.246, -71.636}, {59.349, -69.478}, {60.784, -69.043}, {61.375, -72.205},
    {64.716, -69.425}, {63.118, -67.833}, {64.175, -67.040}, {64.877, -66.630}, {64.475, -67.022}, {65.252, -67.752},
    {66.473, -67.690}, {65.030, -68.034}, {68.794, -69.398}, {69.424, -65.817}, {67.835, -68.448}, {70.082, -67.532},
    {72.477, -65.045}, {70.960, -67.901}, {72.582, -65.557}, {73.132, -64.760}, {75.124, -66.412}, {75.393, -68.714},
    {76.715, -66.153}, {77.978, -68.401}, {78.417, -64.967}};
std::vector<Vec2> samplesOf(const std::vector<Vec2>& points, std::size_t first, std::size_t count) {
  return {points.begin() + static_cast<std::ptrdiff_t>(first), points.begin() + static_cast<std::ptrdiff_t>(first + count)};
}

// Where its parts' chains bent tighter than the tolerance or looped, the curve did too:
// stage 6's chain of an 8-point side kept as closer than stage 7's (a bend of 0.04
// tolerances), two parts merged into a chain looping 29 tolerances away, a 6-point side's
// chains looping 4.5 tolerances away; warned, or not at all. No bend tighter than the
// tolerance and no loop now, within the tolerance: the whole stroke, its first 29 samples
// (a bend of 0.36 tolerances, a stray of 2.3), and 12 of them (0.18).
TEST(PipelineCorners, ANoisyStrokeBendsNoTighterThanTheToleranceAndDoesNotLoop) {
  const std::vector<std::vector<Vec2>> strokes = {kNoisyAramaic, samplesOf(kNoisyAramaic, 0, 29),
                                                  samplesOf(kNoisyAramaic, 9, 12)};
  for (std::size_t k = 0; k < strokes.size(); ++k) {
    SCOPED_TRACE("stroke " + std::to_string(k));
    const FitResult r = fitStroke(strokeOf(strokes[k]));
    EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
    EXPECT_GE(r.quality.min_radius, (1.0 - 1e-6) * r.tolerance) << describeFit(r);
    EXPECT_LE(r.stray, kStrayWarning * r.tolerance) << describeFit(r);
    EXPECT_TRUE(r.warnings.empty()) << describeFit(r);
    expectGaps(r);
  }
}

// Stage 7 bounds the radius, and a bend tighter than the tolerance becomes a corner; where
// none can go, the curve says it bends tighter, as it says a miss of the tolerance. A
// logarithmic spiral of three turns into its centre, at a tolerance of 8% of its
// diagonal, stays one segment whose inner end bends tighter (radius about 1, tolerance
// 14); the H's crossbar above bends no tighter, unwarned.
TEST(PipelineCorners, ACurveThatBendsTighterThanTheToleranceSaysSo) {
  std::vector<Vec2> spiral;
  for (int i = 0; i < 400; ++i) {
    const double theta = 6.0 * std::numbers::pi * i / 399.0, radius = 100.0 * std::exp(-0.25 * theta);
    spiral.push_back(radius * Vec2(std::cos(theta), std::sin(theta)));
  }
  FitOptions loose;
  loose.tolerance_fraction = 0.08;
  const std::vector<std::pair<std::vector<Vec2>, FitOptions>> strokes = {{spiral, loose}, {kNoisyCrossbar, FitOptions{}}};
  for (std::size_t k = 0; k < strokes.size(); ++k) {
    SCOPED_TRACE("stroke " + std::to_string(k));
    const FitResult r = fitStroke(strokeOf(strokes[k].first), strokes[k].second);
    const bool warned = std::any_of(r.warnings.begin(), r.warnings.end(), [](const std::string& w) {
      return w.find("bends tighter than the tolerance") != std::string::npos;
    });
    EXPECT_EQ(warned, r.quality.min_radius < (1.0 - 1e-6) * r.tolerance) << describeFit(r);
  }
}

// A caret drawn fast: two bowed arms meeting at a corner that falls between samples
// (about 4.7 units apart, the nearest 1.3 to 2 units from the corner, more than the
// tolerance), with noise of 0.1% of the diagonal. Stage 7 fits both arms as one chain
// with the corner free, so the corner lands less than half as far from the true corner
// as the nearest sample (the corner's own sample used to pin it), within the tolerance.
TEST(PipelineCorners, CornerBetweenSamplesLandsWhereTheArmsMeet) {
  const Vec2 corner(100.0, 120.0);
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, 0.23);
    std::vector<Vec2> points;
    constexpr int kPerArm = 40;
    for (int k = 0; k < kPerArm; ++k) {
      const double t = (k + 0.5) / kPerArm;
      points.push_back(Vec2(100.0 * t, 160.0 * t - 40.0 * t * t) + Vec2(noise(rng), noise(rng)));
    }
    for (int k = 0; k < kPerArm; ++k) {
      const double t = (k + 0.5) / kPerArm;
      points.push_back(corner + Vec2(100.0 * t, -160.0 * t + 40.0 * t * t) + Vec2(noise(rng), noise(rng)));
    }
    const FitResult r = fit(points);
    ASSERT_EQ(r.quality.corners, 1) << describeFit(r);
    EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
    expectGaps(r);
    EXPECT_LT(r.quality.g0_gap, 1e-9);
    double nearest_sample = INFINITY;
    for (const Vec2& p : points) nearest_sample = std::min(nearest_sample, (p - corner).norm());
    for (const CurvePiece& piece : r.curve.pieces) {
      if (!piece.corner) continue;
      EXPECT_LT((piece.segment.start() - corner).norm(), 0.5 * nearest_sample) << describeFit(r);
    }
  }
}

// A Z of three straight strokes, each sampled from its start corner on (its end is the
// next side's start), with noise of 0.1% of the diagonal: every side comes out a
// straight line (a straight part is fitted across corners as a line), the corners
// within three noise sigmas of the true ones, the curve within the tolerance.
// A zigzag of amplitude 10 whose legs are three samples each, on the pixel grid: its
// vertices are corners, and the differences across them are not taken for noise (they
// raised the tolerance to 6.2, 60% of the amplitude); the pixels' rounding raises it to
// one pixel at most.
TEST(PipelineCorners, AZigzagOfShortLegsKeepsItsCornersAndTheTolerance) {
  std::vector<Vec2> p;
  for (int leg = 0; leg < 12; ++leg)
    for (int k = 0; k < 3; ++k) {
      const double t = k / 3.0, y0 = leg % 2 ? 10.0 : -10.0;
      p.emplace_back(std::round(8.0 * (leg + t)), std::round(y0 - 2.0 * y0 * t));
    }
  p.emplace_back(96.0, 10.0);
  const FitResult r = fitStroke(strokeOf(p));
  EXPECT_GE(r.cleaned.corners.size(), 10u);  // (of 11: the first leg is as short as a pen-down hook)
  EXPECT_LE(r.tolerance, 1.0);
  EXPECT_LE(r.quality.max_dev, r.tolerance);
}

TEST(PipelineCorners, StraightSidesStayStraight) {
  const std::vector<Vec2> zed = {{0, 0}, {120, 0}, {10, -100}, {130, -100}};
  const double sigma = 0.2;
  for (unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937 rng(seed);
    std::normal_distribution<double> noise(0.0, sigma);
    std::vector<Vec2> points;
    constexpr int kPerSide = 30;
    for (std::size_t side = 0; side + 1 < zed.size(); ++side)
      for (int k = 0; k < kPerSide + (side + 2 == zed.size() ? 1 : 0); ++k)
        points.push_back(zed[side] + (static_cast<double>(k) / kPerSide) * (zed[side + 1] - zed[side]) +
                         Vec2(noise(rng), noise(rng)));
    const FitResult r = fit(points);
    ASSERT_EQ(r.quality.corners, 2) << describeFit(r);
    ASSERT_EQ(r.curve.pieces.size(), 3u) << describeFit(r);
    EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
    EXPECT_LT(r.quality.g0_gap, 1e-9);
    for (std::size_t i = 0; i < 3; ++i) {
      const LaSegment& side = r.curve.pieces[i].segment;
      EXPECT_TRUE(side.kappaStart() == 0.0 && side.kappaEnd() == 0.0) << "side " << i << "\n" << describeFit(r);
      if (i == 0) continue;
      EXPECT_LT((side.start() - zed[i]).norm(), 3.0 * sigma) << "corner " << i << "\n" << describeFit(r);
    }
  }
}

std::string caseParamName(const ::testing::TestParamInfo<CaseParam>& info) {
  const auto [index, transform] = info.param;
  return caseName(index, transform);
}

INSTANTIATE_TEST_SUITE_P(Chains, PipelineTruthTest,
                         ::testing::Combine(::testing::Range(0, kCaseCount),
                                            ::testing::Values(Transform::kNone, Transform::kRotate,
                                                              Transform::kScaleSmall, Transform::kScaleLarge,
                                                              Transform::kTranslate,
                                                              Transform::kReverse)),
                         caseParamName);
INSTANTIATE_TEST_SUITE_P(Chains, PipelineAlphaTest,
                         ::testing::Combine(::testing::Range(0, kCaseCount), ::testing::Values(Transform::kNone)),
                         caseParamName);

// Bounded work (FitOptions::max_points, max_polish_segments): over the sample limit the
// stroke is refused before any work, naming the limit; a stroke whose stages 1-6 chain
// has more segments than stage 7 may fit keeps that chain, G2, with a warning naming
// the limit; under the limit stage 7 runs as before.
TEST(PipelineLimits, TooManySamplesAreRefusedAndTooManySegmentsKeepStageSix) {
  std::vector<Vec2> wave;
  for (int i = 0; i <= 600; ++i) wave.emplace_back(0.5 * i, 20.0 * std::sin(i * 0.08));  // 7.6 periods
  FitOptions options;
  options.max_points = 600;
  try {
    fitStroke(strokeOf(wave), options);
    ADD_FAILURE() << "601 samples over a limit of 600 were fitted";
  } catch (const StrokeError& e) {
    EXPECT_NE(std::string(e.what()).find("601 samples, more than 600"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--max-points"), std::string::npos) << e.what();
  }
  options = {};
  const FitResult full = fitStroke(strokeOf(wave), options);
  EXPECT_FALSE(full.over_polish_limit);
  options.max_polish_segments = 4;  // (7.6 periods: some 15 extrema, a segment or more each)
  const FitResult kept = fitStroke(strokeOf(wave), options);
  EXPECT_TRUE(kept.over_polish_limit);
  EXPECT_GT(kept.curve.pieces.size(), 4u);
  expectGaps(kept);
  const bool warned = std::any_of(kept.warnings.begin(), kept.warnings.end(), [](const std::string& w) {
    return w.find("--max-polish-segments") != std::string::npos;
  });
  EXPECT_TRUE(warned);
}

// A slow mouse stroke over coarse stairs (a half circle rounded to a grid of 24 pixels,
// walked pixel by pixel along a Catmull-Rom path through the stair's vertices:
// test::walkedByPixels at the stair's own scale): stages 1-6 find no LA segment for some
// pieces between the stairs' wiggles, and leave them to stage 7. Past the room of
// max_polish_segments the chain is still G2: before, those pieces were straight lines,
// kinks of 0.6 rad at joints that are no corners.
TEST(PipelineLimits, PartsPastTheRoomOfStageSevenAreG2) {
  FitOptions options;
  options.max_polish_segments = 8;
  std::vector<Vec2> stairs;
  for (int i = 0; i < 60; ++i) {
    const double a = std::numbers::pi * i / 59.0, grid = 24.0;
    const Vec2 q(std::round((400.0 + 300.0 * std::cos(a)) / grid) * grid, std::round((400.0 + 300.0 * std::sin(a)) / grid) * grid);
    if (stairs.empty() || stairs.back() != q) stairs.push_back(q);
  }
  const FitResult r = fitStroke(test::walkedByPixels(strokeOf(stairs), boundingBoxDiagonal(stairs)), options);
  EXPECT_TRUE(r.over_polish_limit);
  expectGaps(r);
  EXPECT_TRUE(r.g2.usable()) << r.g2.message;
}

// The truth generator itself: what the cases claim about themselves.
TEST(PipelineTruthGenerator, ChainsAreG2WithVisibleJoints) {
  for (int index = 0; index < kCaseCount; ++index) {
    const Truth& t = truthCase(index);
    SCOPED_TRACE(describeTruth(t));
    const auto& pieces = t.curve.pieces;
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      const LaSegment& s = pieces[k].segment;
      EXPECT_GE(t.samples_per_segment[k], kAlphaMinSamples);
      EXPECT_LT(std::abs(s.turning()), 2.0);
      if (index < kRandomCases) {
        EXPECT_GE(s.alpha(), -2.0);
        EXPECT_LE(s.alpha(), 3.0);
      }
      if (k == 0) continue;
      const LaSegment& a = pieces[k - 1].segment;
      EXPECT_LT((a.end() - s.start()).norm(), 1e-9 * t.diagonal);
      EXPECT_LT(std::abs(a.theta(a.length()) - s.theta0()), 1e-12);
      EXPECT_EQ(a.kappaEnd(), s.kappaStart());
      // visible joint: an inflection, or |kappa| changes trend
      const bool inflection = a.kappaEnd() == 0.0;
      const bool a_up = std::abs(a.kappaEnd()) > std::abs(a.kappaStart());
      const bool s_up = std::abs(s.kappaEnd()) > std::abs(s.kappaStart());
      EXPECT_TRUE(inflection || a_up != s_up) << "joint " << k << " is not a curvature extremum";
      if (inflection) {
        EXPECT_TRUE(a.alpha() < 0 && s.alpha() < 0 && a.kappaStart() * s.kappaEnd() < 0);
      }
    }
  }
}

// The measurements themselves: the truth is at distance 0 from itself, every transform
// moves the samples with the curve, and the noise has the stated level.
TEST(PipelineTruthGenerator, MeasurementsAndTransformsAreConsistent) {
  for (int index = 0; index < kCaseCount; ++index) {
    for (Transform tr : {Transform::kNone, Transform::kRotate, Transform::kScaleSmall, Transform::kScaleLarge,
                         Transform::kReverse, Transform::kTranslate}) {
      const Truth t = transformed(truthCase(index), tr);
      SCOPED_TRACE(caseName(index, tr));
      // distancesToCurve measures against a polyline whose sagitta is at most
      // kPolylineSagitta of the diagonal: that is the resolution of every deviation here,
      // far below any tolerance (5e-3 of the diagonal).
      const Deviation self = deviationFromTruth(t.curve, t);
      EXPECT_LT(self.max(), kMeasurementResolution * t.diagonal) << self.where();
      EXPECT_LT((t.curve.pieces.front().segment.start() - t.samples.front()).norm(), 1e-9 * t.diagonal);
      const LaSegment& last = t.curve.pieces.back().segment;
      EXPECT_LT((last.end() - t.samples.back()).norm(), 1e-9 * t.diagonal);
      // Noise: the RMS of the offsets is sigma * sqrt(2); with >= 100 samples its estimate is
      // within 25% (about 3.5 standard errors for the shortest stroke).
      double sum = 0.0;
      for (std::size_t i = 0; i < t.samples.size(); ++i) sum += (t.noisy[i] - t.samples[i]).squaredNorm();
      const double sigma = std::sqrt(sum / (2.0 * static_cast<double>(t.samples.size())));
      EXPECT_NEAR(sigma / (kNoiseFraction * t.diagonal), 1.0, 0.25) << "noise level";
    }
  }
}

// G2 methods: bisection and Newton both make curvature continuous; off leaves G1 only.
std::string methodName(int index, G2Method method) {
  return "chain" + std::to_string(1 + index / kSeedsPerSize) + "_seed" + std::to_string(index % kSeedsPerSize) + "_" +
         toString(method);
}

using MethodParam = std::tuple<int, G2Method>;
class PipelineG2MethodTest : public ::testing::TestWithParam<MethodParam> {};

TEST_P(PipelineG2MethodTest, GapsAsPromised) {
  const auto [index, method] = GetParam();
  const Truth& truth = truthCase(index);
  FitOptions options;
  options.g2 = method;
  const FitResult r = fitStroke(strokeOf(truth.noisy), options);
  ASSERT_FALSE(r.curve.pieces.empty()) << describeTruth(truth) << "\n" << describeFit(r);
  EXPECT_LT(r.quality.g1_gap, kG1Threshold);
  if (method == G2Method::kOff) {
    // Off: a joint other than inflection-to-inflection (kappa 0 both sides by
    // construction) keeps the curvature jump of two independent segments.
    bool has_open_joint = false;
    for (std::size_t i = 1; i < r.pieces.size(); ++i)
      has_open_joint |= !(r.pieces[i - 1].kind == PieceKind::kInflectionEnd && r.pieces[i].kind == PieceKind::kInflectionStart);
    if (has_open_joint) {
      EXPECT_GT(r.quality.g2_gap, kG2Threshold) << "G2 off, yet curvature is continuous";
    }
  } else {
    EXPECT_LT(r.quality.g2_gap, kG2Threshold);
    EXPECT_TRUE(r.g2.usable()) << "G2 report: " << r.g2.message;
    // (The deviation of these fits is checked by FitsTheTruth; here only what the G2
    // method is responsible for.)
  }
  std::printf("[ case     ] %-28s segments %zu  g1 %.1e g2 %.1e  G2 report: %s\n",
              methodName(index, method).c_str(), r.curve.pieces.size(),
              r.quality.g1_gap, r.quality.g2_gap, r.g2.message.c_str());
  if (HasFailure()) std::printf("%s\n%s\n", describeTruth(truth).c_str(), describeFit(r).c_str());
}

std::string methodCaseName(const ::testing::TestParamInfo<MethodParam>& info) {
  const auto [index, method] = info.param;
  return methodName(index, method);
}

// Chains of 2 to 5 segments (a single segment has no joint).
INSTANTIATE_TEST_SUITE_P(Chains, PipelineG2MethodTest,
                         ::testing::Combine(::testing::Range(kSeedsPerSize, kRandomCases),
                                            ::testing::Values(G2Method::kBisection, G2Method::kNewton,
                                                              G2Method::kOff)),
                         methodCaseName);

}  // namespace
}  // namespace la

namespace la {
namespace {

// The user's alpha for one segment (withSegmentAlpha): that segment takes it exactly,
// the curve stays G2, and the joint positions do not move.
TEST(SegmentAlpha, SteeredSegmentKeepsG2AndJoints) {
  int checked = 0;
  for (int index = 10; index < 20; ++index) {  // the 3- and 4-segment chains
    const FitResult r = fit(truthCase(index).noisy);
    for (std::size_t i = 0; i < r.pieces.size(); ++i) {
      if (r.pieces[i].kind != PieceKind::kThreePoint) continue;
      const double wanted = std::clamp(r.curve.pieces[i].segment.alpha() + 0.4, -3.0, 3.0);
      std::string why;
      const std::optional<FitResult> s = withSegmentAlpha(r, i, wanted, FitOptions{}, &why);
      if (!s) continue;  // no G2 chain with that alpha: reported, not forced
      ++checked;
      EXPECT_DOUBLE_EQ(s->curve.pieces[i].segment.alpha(), wanted);
      EXPECT_LT(s->quality.g2_gap, 1e-6) << "case " << index << " piece " << i;
      EXPECT_LT(s->quality.g1_gap, 1e-9);
      for (std::size_t k = 0; k < r.curve.pieces.size(); ++k)
        EXPECT_LT((s->curve.pieces[k].segment.start() - r.curve.pieces[k].segment.start()).norm(), 1e-9 * r.quality.diagonal);
      break;
    }
  }
  EXPECT_GE(checked, 5) << "too few steerable segments were found";
}

// Dragging a joint (withJointMoved): the joint lands where it was put, the curve stays
// G2 and the other joints stay.
TEST(SegmentAlpha, MovedJointKeepsG2) {
  int checked = 0;
  for (int index = 10; index < 20; ++index) {
    const FitResult r = fit(truthCase(index).noisy);
    if (r.curve.pieces.size() < 3) continue;
    const std::size_t joint = 1;
    const Vec2 target = r.curve.pieces[joint].segment.start() + Vec2(0.01, -0.005) * r.quality.diagonal;
    std::string why;
    const std::optional<FitResult> s = withJointMoved(r, joint, target, FitOptions{}, &why);
    if (!s) continue;
    ++checked;
    EXPECT_LT((s->curve.pieces[joint].segment.start() - target).norm(), 1e-12 * r.quality.diagonal);
    EXPECT_LT((s->curve.pieces[joint - 1].segment.end() - target).norm(), 1e-9 * r.quality.diagonal);
    EXPECT_LT(s->quality.g2_gap, 1e-6) << "case " << index;
    EXPECT_LT((s->curve.pieces[2].segment.start() - r.curve.pieces[2].segment.start()).norm(), 1e-9 * r.quality.diagonal);
  }
  EXPECT_GE(checked, 5);
}

// Dragging a control triangle's apex (withApexMoved): both end tangents of that segment
// point at the new apex (its two joints slide along them), the other joints stay, and
// the curve stays G2.
TEST(SegmentAlpha, MovedApexFixesBothTangentsAndKeepsG2) {
  int checked = 0;
  for (int index = 10; index < 20; ++index) {
    const FitResult r = fit(truthCase(index).noisy);
    if (r.curve.pieces.size() < 3) continue;
    const std::size_t i = 1;
    const LaSegment& seg = r.curve.pieces[i].segment;
    if (std::abs(seg.turning()) < 0.1) continue;
    // The current apex, moved a little along the chord's normal.
    const Vec2 a = seg.start(), b = seg.end(), u = seg.tangent(0.0), v = seg.tangent(seg.length());
    const Vec2 old_apex = a + (cross(b - a, v) / cross(u, v)) * u;
    const Vec2 chord = (b - a).normalized();
    const Vec2 apex = old_apex + 0.04 * (b - a).norm() * Vec2(-chord.y(), chord.x());
    std::string why;
    const std::optional<FitResult> s = withApexMoved(r, i, apex, FitOptions{}, &why);
    if (!s) continue;  // no G2 chain with those tangents: reported, not forced
    ++checked;
    const LaSegment& moved = s->curve.pieces[i].segment;
    const Vec2 to_apex = (apex - a).normalized(), from_apex = (b - apex).normalized();
    EXPECT_LT((moved.tangent(0.0) - to_apex).norm(), 1e-9) << "case " << index;
    EXPECT_LT((moved.tangent(moved.length()) - from_apex).norm(), 1e-9) << "case " << index;
    EXPECT_LT(s->quality.g2_gap, 1e-6) << "case " << index;
    EXPECT_LT(s->quality.g1_gap, 1e-9) << "case " << index;
    for (std::size_t k = 0; k < r.curve.pieces.size(); ++k) {
      const double moved_by = (s->curve.pieces[k].segment.start() - r.curve.pieces[k].segment.start()).norm();
      if (k == i || k == i + 1) EXPECT_LT(moved_by, 0.1 * r.quality.diagonal) << "case " << index << " joint " << k;
      else EXPECT_LT(moved_by, 1e-9 * r.quality.diagonal) << "case " << index << " joint " << k;
    }
  }
  EXPECT_GE(checked, 5);
}

// The open curve's end (joint n) and a corner can be dragged too: a corner moves both
// parts that meet there and stays a corner.
TEST(SegmentAlpha, MovedEndAndCornerKeepG2) {
  // A caret: two bowed arms meeting at a sharp corner.
  std::vector<Vec2> points;
  for (int k = 0; k <= 200; ++k) {
    const double t = k / 200.0;
    points.push_back({100.0 * t, 160.0 * t - 40.0 * t * t});
  }
  for (int k = 1; k <= 200; ++k) {
    const double t = k / 200.0;
    points.push_back({100.0 + 100.0 * t, 120.0 - 160.0 * t + 40.0 * t * t});
  }
  const FitResult r = fit(points);
  ASSERT_EQ(r.quality.corners, 1) << describeFit(r);
  const std::size_t n = r.curve.pieces.size();
  std::size_t corner = 0;
  for (std::size_t k = 1; k < n; ++k)
    if (r.curve.pieces[k].corner) corner = k;
  ASSERT_GT(corner, 0u);

  const Vec2 end_target = r.curve.pieces[n - 1].segment.end() + Vec2(-3.0, 4.0);
  const std::optional<FitResult> e = withJointMoved(r, n, end_target, FitOptions{});
  ASSERT_TRUE(e.has_value());
  EXPECT_LT((e->curve.pieces[n - 1].segment.end() - end_target).norm(), 1e-9 * r.quality.diagonal);
  EXPECT_LT(e->quality.g2_gap, 1e-6);

  const Vec2 corner_target = r.curve.pieces[corner].segment.start() + Vec2(2.0, 5.0);
  const std::optional<FitResult> c = withJointMoved(r, corner, corner_target, FitOptions{});
  ASSERT_TRUE(c.has_value());
  EXPECT_TRUE(c->curve.pieces[corner].corner);
  EXPECT_LT((c->curve.pieces[corner].segment.start() - corner_target).norm(), 1e-12 * r.quality.diagonal);
  EXPECT_LT((c->curve.pieces[corner - 1].segment.end() - corner_target).norm(), 1e-9 * r.quality.diagonal);
  EXPECT_LT(c->quality.g2_gap, 1e-6);
  EXPECT_LT(c->quality.g1_gap, 1e-9);
  EXPECT_FALSE(withJointMoved(r, n + 1, corner_target, FitOptions{}).has_value());
}

TEST(SegmentAlpha, InflectionPieceAlphaIsFixed) {
  const FitResult r = fit(truthCase(kRandomCases + 1).noisy);  // the clothoid through an inflection
  for (std::size_t i = 0; i < r.pieces.size(); ++i) {
    if (r.pieces[i].kind == PieceKind::kThreePoint) continue;
    std::string why;
    EXPECT_FALSE(withSegmentAlpha(r, i, -1.0, FitOptions{}, &why).has_value());
    EXPECT_NE(why.find("fixed"), std::string::npos) << why;
    return;
  }
  FAIL() << "the clothoid through an inflection was fitted without an inflection piece\n" << describeFit(r);
}

}  // namespace
}  // namespace la

namespace la {
namespace {

// A straight stroke is a line (alpha infinite), not an error; one drawn there and back
// along the same line is two lines meeting at a corner at the far end.
TEST(PipelineStraight, CollinearPointsAreOneLine) {
  std::vector<Vec2> points;
  for (int i = 0; i <= 40; ++i) points.push_back(Vec2(5.0, 2.0) + 1.5 * i * Vec2(0.8, -0.6));
  const FitResult r = fit(points);
  ASSERT_EQ(r.curve.pieces.size(), 1u);
  const LaSegment& line = r.curve.pieces[0].segment;
  EXPECT_TRUE(line.isStraight());
  EXPECT_TRUE(std::isinf(line.alpha()));
  EXPECT_NEAR(line.length(), 60.0, 1e-9);
  EXPECT_NEAR(line.theta0(), std::atan2(-0.6, 0.8), 1e-12);
  EXPECT_LT(r.quality.max_dev, 1e-9);
}

TEST(PipelineStraight, ThereAndBackIsTwoLinesWithACorner) {
  std::vector<Vec2> points;
  for (int i = 0; i <= 30; ++i) points.push_back(Vec2(i, 2.0 * i));
  for (int i = 29; i >= 10; --i) points.push_back(Vec2(i, 2.0 * i));
  const FitResult r = fit(points);
  ASSERT_EQ(r.curve.pieces.size(), 2u);
  EXPECT_TRUE(r.curve.pieces[1].corner);
  EXPECT_NEAR((r.curve.pieces[0].segment.end() - Vec2(30, 60)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((r.curve.pieces[1].segment.end() - Vec2(10, 20)).norm(), 0.0, 1e-9);
  EXPECT_EQ(r.quality.corners, 1);
  EXPECT_LT(r.quality.max_dev, 1e-9);
}

}  // namespace
}  // namespace la

namespace la {
namespace {

// The cap on curvature extrema (segmentation.max_extrema) holds per smooth part, as the
// quality figures count them, in both modes; without it the wave keeps its extrema (so
// the cap has work to do). The deviation it costs is reported, not hidden.
std::vector<Vec2> noisyWave(unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 0.05);
  std::vector<Vec2> points;
  for (int i = 0; i <= 300; ++i) {
    const double x = 0.6 * i;
    points.push_back(Vec2(x, 20.0 * std::sin(x / 15.0)) + Vec2(noise(rng), noise(rng)));
  }
  return points;
}

TEST(PipelineExtremaCap, HoldsPerPartInEveryMode) {
  const std::vector<Vec2> wave = noisyWave(3);
  ASSERT_GE(fit(wave).quality.max_extrema_per_part, 3) << "the wave has its extrema without a cap";
  for (bool paper : {false, true}) {
    for (int cap : {0, 1, 2}) {
      FitOptions options;
      options.polish = !paper;
      options.segmentation.max_extrema = cap;
      const FitResult r = fit(wave, options);
      EXPECT_LE(r.quality.max_extrema_per_part, cap) << (paper ? "paper-only" : "default") << ", cap " << cap << "\n"
                                                     << describeFit(r);
      EXPECT_LT(r.quality.g2_gap, 1e-6);
      const bool warned = std::any_of(r.warnings.begin(), r.warnings.end(),
                                      [](const std::string& w) { return w.find("misses the tolerance") != std::string::npos; });
      EXPECT_EQ(warned, r.quality.max_dev > r.tolerance) << "the cost of the cap is reported";
    }
  }
}

// A drawn circle with the cap under 4 (a closed curve other than a circle has at least
// 4 extrema) is the circle closest to its points: one closed arc.
TEST(PipelineExtremaCap, AClosedStrokeUnderFourExtremaIsACircle) {
  std::mt19937 rng(8);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::vector<Vec2> points;
  for (int i = 0; i < 120; ++i) {
    const double a = 2.0 * std::numbers::pi * i / 120.0;
    points.push_back(Vec2(40.0 * std::cos(a), 34.0 * std::sin(a)) + Vec2(noise(rng), noise(rng)));
  }
  points.push_back(points.front());
  FitOptions options;
  options.segmentation.max_extrema = 2;
  const FitResult r = fit(points, options);
  ASSERT_TRUE(r.curve.closed);
  ASSERT_EQ(r.curve.pieces.size(), 1u) << describeFit(r);
  const LaSegment& circle = r.curve.pieces[0].segment;
  EXPECT_TRUE(circle.isCircular());
  EXPECT_NEAR(1.0 / std::abs(circle.kappaStart()), 37.0, 1.5);  // between the half axes
  EXPECT_EQ(r.quality.max_extrema_per_part, 0);
}

}  // namespace
}  // namespace la

namespace la {
namespace {

// A time budget that has run out before stage 7 starts: the fit still returns a G2
// chain through the points (stages 1-6 and the first chain fit), says so, and its
// figures are those of the curve it returns. Without a budget it does not say so.
TEST(PipelineTimeBudget, ReturnsTheBestG2ChainSoFarWithTrueFigures) {
  const std::vector<Vec2> wave = noisyWave(5);
  FitOptions hurried;
  hurried.time_budget_ms = 1e-6;
  const FitResult r = fit(wave, hurried);
  EXPECT_TRUE(r.out_of_time);
  EXPECT_TRUE(std::any_of(r.warnings.begin(), r.warnings.end(),
                          [](const std::string& w) { return w.find("time budget") != std::string::npos; }));
  ASSERT_FALSE(r.curve.pieces.empty());
  EXPECT_LT(r.quality.g2_gap, 1e-6);
  EXPECT_LT(r.quality.g1_gap, 1e-9);
  const QualityFigures again = measureQuality(r.curve, r.cleaned.points);
  EXPECT_EQ(r.quality.max_dev, again.max_dev);
  EXPECT_EQ(r.quality.segments, static_cast<int>(r.curve.pieces.size()));
  EXPECT_FALSE(fit(wave).out_of_time);
}

}  // namespace
}  // namespace la

namespace la {
namespace {

// Points along a curve at equal arc-length steps, with Gaussian noise.
std::vector<Vec2> sampled(const std::function<Vec2(double)>& at, double length, int n, double noise, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, noise);
  std::vector<Vec2> points;
  for (int i = 0; i <= n; ++i) points.push_back(at(length * i / n) + (noise > 0.0 ? Vec2(g(rng), g(rng)) : Vec2::Zero()));
  return points;
}

std::vector<Vec2> sampledSegment(const LaSegment& s, int n, double noise = 0.0, unsigned seed = 1) {
  return sampled([&](double t) { return s.position(t); }, s.length(), n, noise, seed);
}

// The Archimedean spiral r = a theta from theta = 2 pi on, `turns` turns, at equal steps
// of arc length (its arc length, a theta sqrt(1 + theta^2)/2 + a asinh(theta)/2, is
// inverted by bisection).
std::vector<Vec2> archimedeanSpiral(double turns, int n, double noise, unsigned seed) {
  constexpr double a = 5.0;
  auto arc = [](double t) { return 0.5 * a * (t * std::sqrt(1.0 + t * t) + std::asinh(t)); };
  const double t0 = 2.0 * std::numbers::pi, t1 = t0 + 2.0 * std::numbers::pi * turns;
  auto at = [&](double s) {
    double lo = t0, hi = t1;
    for (int k = 0; k < 60; ++k) (arc(0.5 * (lo + hi)) - arc(t0) < s ? lo : hi) = 0.5 * (lo + hi);
    const double t = 0.5 * (lo + hi);
    return Vec2(a * t * std::cos(t), a * t * std::sin(t));
  };
  return sampled(at, arc(t1) - arc(t0), n, noise, seed);
}

// A stroke sampled from one LA segment comes back as that one segment, with its alpha
// (within 0.05): more than a half turn, more than a full turn, at several alphas.
TEST(PipelineOneSegment, OneLaSegmentSampledIsThatSegment) {
  const double pi = std::numbers::pi;
  struct Case {
    const char* name;
    LaSegment truth;
  };
  const Case cases[] = {
      {"clothoid, 1 turn", LaSegment::withTurning(-1.0, 2.0 * pi, {0, 0}, 0.0, 0.01, 0.1)},
      {"logarithmic spiral, 1 turn", LaSegment::withTurning(1.0, 2.0 * pi, {0, 0}, 0.3, 0.01, 0.05)},
      {"circle involute, 1 turn", LaSegment::withTurning(2.0, 2.0 * pi, {5, 5}, 1.0, 0.01, 0.06)},
      {"alpha 0.5, 1.5 turns", LaSegment::withTurning(0.5, 3.0 * pi, {0, 0}, 0.0, 0.01, 0.06)},
      {"clothoid, 2 turns, turning right", LaSegment::withTurning(-1.0, 4.0 * pi, {0, 0}, 0.0, -0.01, -0.1)},
  };
  for (const Case& c : cases) {
    const FitResult r = fit(sampledSegment(c.truth, 600));
    ASSERT_EQ(r.curve.pieces.size(), 1u) << c.name << "\n" << describeFit(r);
    const LaSegment& s = r.curve.pieces[0].segment;
    EXPECT_NEAR(s.alpha(), c.truth.alpha(), 0.05) << c.name;
    EXPECT_NEAR(s.turning(), c.truth.turning(), 1e-3) << c.name;
    EXPECT_LE(r.quality.max_dev, r.tolerance) << c.name;
  }
  // An arc of 115 degrees: one segment of constant curvature (any alpha draws it).
  const LaSegment arc = LaSegment::arc(200.0, {0, 0}, 0.0, 2.0071 / 200.0);
  const FitResult r = fit(sampledSegment(arc, 200));
  ASSERT_EQ(r.curve.pieces.size(), 1u) << describeFit(r);
  EXPECT_NEAR(r.curve.pieces[0].segment.kappaStart(), arc.kappaStart(), 1e-4 * arc.kappaStart());
  EXPECT_NEAR(r.curve.pieces[0].segment.kappaEnd(), arc.kappaStart(), 1e-4 * arc.kappaStart());
}

// Spirals of 1 to 5 turns, logarithmic, clothoid and Archimedean (200 + 360 points a
// turn), noise-free and with noise of a fifth of a unit, within the tolerance, G2, at most
// 2 segments a turn; the logarithmic and clothoid ones (one LA segment each) as that one
// segment, their alpha within 0.05. (The clean-up took the tight inner turns of a
// logarithmic spiral of 5 turns for corners, and from the end chords' curvatures alone a
// noisy spiral's one-segment fit set off onto the wrong turn: 19 to 46 tolerances off,
// seconds, or a crash.)
TEST(PipelineOneSegment, SpiralsOfUpToFiveTurnsFitWithFewSegments) {
  const double pi = std::numbers::pi;
  struct Case {
    std::string name;
    std::vector<Vec2> points;
    double turns;
    double alpha = NAN;  // of the one LA segment sampled, if one
  };
  std::vector<Case> cases;
  for (double turns : {1.0, 2.0, 3.0, 4.0, 5.0}) {
    const int n = static_cast<int>(200 + 360 * turns);
    const std::string t = std::to_string(static_cast<int>(turns)) + " turns";
    // (curvature 0.002 or 0.01 to 0.1, whatever the turns: the inner end stays wider than
    // the tolerance)
    const LaSegment logarithmic = LaSegment::withTurning(1.0, 2 * pi * turns, {0, 0}, 0, 0.002, 0.1);
    const LaSegment clothoid = LaSegment::withTurning(-1.0, 2 * pi * turns, {0, 0}, 0, 0.01, 0.1);
    for (double noise : {0.0, 0.2}) {
      const std::string how = noise > 0.0 ? ", noisy, " : ", ";
      cases.push_back({"logarithmic" + how + t, sampledSegment(logarithmic, n, noise), turns, 1.0});
      cases.push_back({"clothoid" + how + t, sampledSegment(clothoid, n, noise), turns, -1.0});
      cases.push_back({"Archimedean" + how + t, archimedeanSpiral(turns, n, noise, 3), turns});
    }
  }
  cases.push_back({"logarithmic, noisy, 1 turn", sampledSegment(LaSegment::withTurning(1.0, 2 * pi, {0, 0}, 0, 0.002, 0.02), 560, 0.2), 1.0, 1.0});
  for (const Case& c : cases) {
    const FitResult r = fit(c.points);
    EXPECT_LE(r.quality.max_dev, r.tolerance) << c.name << "\n" << describeFit(r);
    EXPECT_LT(r.quality.g2_gap, 1e-6) << c.name;
    EXPECT_LT(r.quality.g1_gap, 1e-9) << c.name;
    EXPECT_LE(static_cast<double>(r.curve.pieces.size()), 2.0 * c.turns) << c.name << "\n" << describeFit(r);
    if (std::isnan(c.alpha)) continue;
    ASSERT_EQ(r.curve.pieces.size(), 1u) << c.name << "\n" << describeFit(r);
    EXPECT_NEAR(r.curve.pieces[0].segment.alpha(), c.alpha, 0.05) << c.name;
  }
}

// Archimedean spirals drawn out from a tight centre, r = a + 60 theta / 2 pi, 1,000
// points at equal steps of the angle, so the centre is sampled ten times as densely as
// the outer turns or more. From r = 5 (3 turns): noise far below the outer steps is as
// large as the centre's, and the test of one segment read it as turning back there (the
// chords' noise judged by their mean length); stages 2-6 from the spline set off astray,
// 11-123 times the tolerance off, in seconds. From the very centre (a = 0, 5 turns): the
// one segment missed by 6% at the centre, where no split came (15% of its length from
// its ends), in 2 s. Each keeps the tolerance in 1 or 2 segments a turn.
TEST(PipelineOneSegment, AnArchimedeanSpiralFromATightCentreKeepsTheTolerance) {
  for (const double a : {5.0, 0.0})
    for (double noise : {0.0, 0.01, 0.1, 0.3}) {
      const double turns = a > 0.0 ? 3.0 : 5.0, b = 60.0 / (2.0 * std::numbers::pi);
      // (sampled at equal steps of the angle theta)
      auto at = [&](double theta) { return Vec2((a + b * theta) * std::cos(theta), (a + b * theta) * std::sin(theta)); };
      const FitResult r = fit(sampled(at, 2.0 * std::numbers::pi * turns, 1000, noise, 3));
      const std::string what = "r = " + std::to_string(a) + " + b theta, noise " + std::to_string(noise);
      EXPECT_LE(r.quality.max_dev, r.tolerance) << what << "\n" << describeFit(r);
      EXPECT_LE(static_cast<double>(r.curve.pieces.size()), 2.0 * turns) << what << "\n" << describeFit(r);
      EXPECT_LT(r.quality.g2_gap, 1e-6) << what;
    }
}

// A spiral of 4 turns (alpha -2) with noise larger than its sample step: the clean-up
// reads two corners in its tight inner turns, and the parts between them came out 17.5
// tolerances astray (16 segments, 1.9 s), where the whole stroke as one segment misses
// the tolerance by a little by the chain fit's own measure (and keeps it by the quality
// figures'). The stroke is that one segment, its alpha the truth's.
TEST(PipelineOneSegment, ANoisySpiralIsOneSegmentWhereItsPartsMissByMore) {
  const LaSegment truth = LaSegment::withTurning(-2.0, 8.0 * std::numbers::pi, {0, 0}, 0.3, 0.004, 0.08);
  const FitResult r = fit(sampledSegment(truth, 2000, 0.3, 1));
  ASSERT_EQ(r.curve.pieces.size(), 1u) << describeFit(r);
  EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
  EXPECT_NEAR(r.curve.pieces[0].segment.alpha(), -2.0, 0.05);
}

// A noisy spiral (alpha 0, 2.5 turns, 700 samples, noise 0.3) whose one segment misses
// the tolerance by 2% at its tight centre: fitStroke's refit with a corner at the
// farthest point keeps it, G2 and the bound, though it runs past its share of the work
// (twice the work before it), and is kept. It was refused for that, and the stroke left
// as the one segment, 1.02 tolerances off (seed 2; seed 1's one segment keeps it).
TEST(PipelineOneSegment, ANoisySpiralsCornerAtItsCentreIsKeptPastItsShareOfTheWork) {
  const LaSegment truth = LaSegment::withTurning(0.0, 5.0 * std::numbers::pi, {0, 0}, 0.3, 0.004, 0.08);
  for (unsigned seed : {1u, 2u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const FitResult r = fit(sampledSegment(truth, 700, 0.3, seed));
    EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
    EXPECT_LT(r.quality.g2_gap, 1e-6) << describeFit(r);
    EXPECT_GE(r.quality.min_radius, (1.0 - 1e-6) * r.tolerance) << describeFit(r);
    EXPECT_FALSE(r.out_of_time) << describeFit(r);
    EXPECT_TRUE(std::none_of(r.warnings.begin(), r.warnings.end(),
                             [](const std::string& w) { return w.find("time budget") != std::string::npos; }))
        << describeFit(r);
  }
}

// A logarithmic spiral of 2.5 turns into its centre (2,000 noisy samples) at a loose
// tolerance, 5% of its diagonal: its inner turn bends tighter than the tolerance and
// becomes a corner, and the outer turns, beside that corner, are the one LA segment they
// were sampled from (its alpha near the truth's: the bound on the radius holds its inner
// end to half the truth's curvature there). They were fitted as a chain: 18 segments,
// 1.3 tolerances off, in 0.8 s.
TEST(PipelineOneSegment, ALooseSpiralsOuterTurnsBesideItsCornerAreOneSegment) {
  const LaSegment truth = LaSegment::withTurning(1.0, 5.0 * std::numbers::pi, {0, 0}, 0.3, 0.004, 0.08);
  FitOptions loose;
  loose.tolerance_fraction = 0.05;
  for (unsigned seed : {1u, 2u}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const FitResult r = fitStroke(strokeOf(sampledSegment(truth, 2000, 0.3, seed)), loose);
    EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
    EXPECT_GE(r.quality.min_radius, (1.0 - 1e-6) * r.tolerance) << describeFit(r);
    ASSERT_EQ(r.cleaned.corners.size(), 1u) << describeFit(r);
    ASSERT_GE(r.curve.pieces.size(), 2u) << describeFit(r);
    EXPECT_LE(r.curve.pieces.size(), 3u) << describeFit(r);
    const LaSegment& outer = r.curve.pieces.front().segment;
    EXPECT_GT(std::abs(outer.turning()), 4.0 * std::numbers::pi) << describeFit(r);
    EXPECT_NEAR(outer.alpha(), 1.0, 0.15) << describeFit(r);
  }
}

}  // namespace
}  // namespace la

namespace la {
namespace {

// The library says which segments the user can steer (the app asks it): a segment
// turning by pi or more has no control triangle, so neither apex nor alpha steering.
TEST(SegmentAlpha, ASegmentTurningMoreThanPiHasNoControlTriangle) {
  const LaSegment half = LaSegment::withTurning(-1.0, 0.5 * std::numbers::pi, {0, 0}, 0.0, 0.01, 0.05);
  const std::optional<Vec2> apex = controlApex(half);
  ASSERT_TRUE(apex.has_value());
  // the apex is where the end tangents meet: on both tangent lines
  EXPECT_NEAR(cross(half.tangent(0.0), *apex - half.start()), 0.0, 1e-9);
  EXPECT_NEAR(cross(half.tangent(half.length()), *apex - half.end()), 0.0, 1e-9);
  EXPECT_FALSE(controlApex(LaSegment::withTurning(-1.0, 1.2 * std::numbers::pi, {0, 0}, 0.0, 0.01, 0.05)).has_value());
  EXPECT_FALSE(controlApex(LaSegment::arc(10.0, {0, 0}, 0.0, 0.0)).has_value());

  const FitResult spiral = fit(sampledSegment(LaSegment::withTurning(1.0, 2.0 * std::numbers::pi, {0, 0}, 0.0, 0.01, 0.05), 400));
  ASSERT_EQ(spiral.curve.pieces.size(), 1u);
  EXPECT_NE(whyAlphaIsFixed(spiral, 0).find("control triangle"), std::string::npos);
  std::string why;
  EXPECT_FALSE(withSegmentAlpha(spiral, 0, 0.5, FitOptions{}, &why).has_value());
  EXPECT_FALSE(withApexMoved(spiral, 0, {10, 10}, FitOptions{}, &why).has_value());
  EXPECT_NE(why.find("control triangle"), std::string::npos);
}

}  // namespace
}  // namespace la

namespace la {
namespace {

// Nothing is dropped silently: every sample the clean-up leaves out is listed with why,
// the fraction of the drawn length they span is measured (and warned above 5%), and the
// deviation is measured over all samples as well as over the kept ones.
TEST(PipelineLeftOut, EverySampleLeftOutIsListedWithWhy) {
  std::vector<Vec2> arc;
  for (int i = 0; i <= 60; ++i) arc.push_back(Vec2(100.0 * std::cos(0.02 * i), 100.0 * std::sin(0.02 * i)));
  Stroke stroke = strokeOf(arc);
  // a pen-down hook 4 units beside the stroke (its steps are 2: within a hook's worth),
  // a duplicate and a NaN
  stroke.samples.insert(stroke.samples.begin(), StrokeSample{arc.front() + Vec2(-4.0, 0.0)});
  stroke.samples.insert(stroke.samples.begin() + 10, stroke.samples[9]);
  stroke.samples.insert(stroke.samples.begin() + 20, StrokeSample{Vec2(NAN, 0.0)});
  const FitResult r = fitStroke(stroke);
  std::map<std::size_t, LeftOutReason> listed;
  for (const LeftOutPoint& l : r.cleaned.left_out) listed[l.sample] = l.why;
  ASSERT_EQ(listed.size(), 3u) << describeFit(r);
  EXPECT_EQ(listed[0], LeftOutReason::kStartHook);
  EXPECT_EQ(listed[10], LeftOutReason::kDuplicate);
  EXPECT_EQ(listed[20], LeftOutReason::kNonFinite);
  EXPECT_EQ(r.cleaned.points.size() + r.cleaned.left_out.size(), stroke.samples.size());
  // the hook's step is 4 of about 124 drawn
  EXPECT_NEAR(r.cleaned.left_out_fraction, 4.0 / (4.0 + 120.0), 0.005);
  EXPECT_FALSE(std::any_of(r.warnings.begin(), r.warnings.end(),
                           [](const std::string& w) { return w.find("leaves out") != std::string::npos; }))
      << describeFit(r);  // (3% of the drawn length: no warning)
  EXPECT_LE(r.quality.max_dev, r.tolerance);
  EXPECT_GT(r.max_dev_all_points, 3.0);  // the hook, 4 from the arc's start
}

// A long first step is a segment of the stroke, not an outlier: a first point 40 units
// before an arc drawn in steps of 2 (a digitizer's jump along the stroke) stays, and the
// curve follows it; 40 units at a sharp turn is more than a hook's worth, so it stays
// there too, the turn a corner.
TEST(PipelineLeftOut, ALongFirstStepIsASegment) {
  std::vector<Vec2> arc;
  for (int i = 0; i <= 60; ++i) arc.push_back(Vec2(100.0 * std::cos(0.02 * i), 100.0 * std::sin(0.02 * i)));
  for (const Vec2& jump : {Vec2(0.0, -40.0), Vec2(40.0, 0.0)}) {
    Stroke stroke = strokeOf(arc);
    stroke.samples.insert(stroke.samples.begin(), StrokeSample{arc.front() + jump});
    const FitResult r = fitStroke(stroke);
    EXPECT_TRUE(r.cleaned.left_out.empty()) << describeFit(r);
    EXPECT_EQ(r.cleaned.left_out_fraction, 0.0);
    EXPECT_LE(r.quality.max_dev, r.tolerance) << describeFit(r);
    EXPECT_LE(r.max_dev_all_points, r.tolerance) << describeFit(r);
  }
}

}  // namespace
}  // namespace la
