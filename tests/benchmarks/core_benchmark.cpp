// Speed of the LA curve engine in core/ (issue "Core: the LA curve engine"; STYLE.md
// convention 9: speed targets are checked here, never in timed tests).
//
// Run (median of 5 repetitions is the figure compared with the targets):
//   ./tests/benchmarks/core_benchmark --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true --benchmark_min_time=0.2
// (one command line; from the build directory).
// Add --benchmark_filter=ThreePoint (a regex on the names below) to run one group.
//
// Groups and targets:
//   PointEval/{kappa,theta,position}/alpha:A   one evaluation of LaSegment at varying s
//   Sample1000/alpha:A                        LaSegment::sample(1000) into a reused
//                                             CurveSamples; target <= 50 us per call
//   ThreePointSolve/alpha:A                   solveThreePointSegment over the 16 control
//                                             triangles of LA segments with turning
//                                             0.2..2.8 rad and end curvature ratio 4..20;
//                                             target <= 5 us median per solve, every alpha
//   ThreePointSolveNearStraight/alpha:A       the same, turning 1e-3..1e-6 rad; target:
//                                             no slower than ThreePointSolve
//   ThreePointSolveChordGrid/alpha:A          chord angle 25%..75% of turning 0.2..2.8,
//                                             the reachable ones only: near the edge of
//                                             the reachable range (huge curvature ratios)
//   InflectionSolve/start                     solveInflectionSegment(kStart) over 16
//                                             triangles, chord angle 10%..45% of the
//                                             turning angle
//   LcgFit200/{derivative,samples}            fitLcg of the LCG of 200 samples
//
// Every benchmark checks, before its timed loop, that what it times works (the solves
// converge, the samples end at the segment's end, the fit recovers alpha) and reports
// SkipWithError otherwise, so a fast failure cannot pass as a fast success.
// The inputs are deterministic (no random numbers): grids of angles written below.
// "Library was built as DEBUG" in the output refers to Debian's libbenchmark itself,
// not to this program (built with CMAKE_BUILD_TYPE=Release).

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "core/inflection_segment.h"
#include "core/la_segment.h"
#include "core/lcg.h"
#include "core/three_point_segment.h"

namespace la {
namespace {

// "Typical segment" of the issue: length 1, curvature 1 -> 3, starting at the origin
// heading +x (left turn).
constexpr double kTypicalLength = 1.0;
constexpr double kTypicalKappaStart = 1.0;
constexpr double kTypicalKappaEnd = 3.0;

// Point evaluation cycles through this many arc lengths spread over [0, L], so that
// neither the branch predictor nor the compiler sees one constant s.
constexpr int kPointEvalArcLengths = 64;  // power of two: the index wraps with a mask

constexpr int kSamplesPerCall = 1000;  // Sample1000: the "1000 points"
constexpr int kLcgSamples = 200;       // LcgFit200: the "200 samples"

// A number in benchmark names and messages, shortest general form: "-0.5", "2", "1e-08".
std::string text(double x) {
  std::ostringstream out;
  out << x;
  return out.str();
}

LaSegment typicalSegment(double alpha, double kappa_start = kTypicalKappaStart) {
  return LaSegment(alpha, kTypicalLength, Vec2::Zero(), 0.0, kappa_start, kTypicalKappaEnd);
}

// ---------------------------------------------------------------------------------
// 1. Point evaluation: kappa(s), theta(s), position(s) at the default tolerance.

enum class PointQuery { kKappa, kTheta, kPosition };

void pointEval(benchmark::State& state, double alpha, PointQuery query) {
  const LaSegment seg = typicalSegment(alpha);
  std::array<double, kPointEvalArcLengths> arc;
  for (int i = 0; i < kPointEvalArcLengths; ++i) {
    // a stride coprime to the count visits [0, L] out of order (s = L included)
    arc[i] = seg.length() * ((i * 37) % kPointEvalArcLengths) / (kPointEvalArcLengths - 1);
  }
  // Works: end curvatures as constructed, and position(L) is the end of a dense sampling
  // (the two are computed by different quadratures: adaptive vs. series panels).
  const double kappa_gap = std::max(std::abs(seg.kappa(0.0) - kTypicalKappaStart),
                                    std::abs(seg.kappa(seg.length()) - kTypicalKappaEnd));
  const double end_gap = (seg.position(seg.length()) - seg.sample(kSamplesPerCall).point.back()).norm();
  constexpr double kCheckTolerance = 1e-9;  // relative to L = 1 and kappa ~ 1
  if (!(kappa_gap <= kCheckTolerance && end_gap <= kCheckTolerance)) {
    state.SkipWithError(("segment check failed: kappa gap " + text(kappa_gap) +
                         ", end gap " + text(end_gap))
                            .c_str());
    return;
  }
  unsigned i = 0;
  for (auto _ : state) {
    const double s = arc[i];
    i = (i + 1) & (kPointEvalArcLengths - 1);
    switch (query) {
      case PointQuery::kKappa:
        benchmark::DoNotOptimize(seg.kappa(s));
        break;
      case PointQuery::kTheta:
        benchmark::DoNotOptimize(seg.theta(s));
        break;
      case PointQuery::kPosition: {
        Vec2 p = seg.position(s);
        benchmark::DoNotOptimize(p);
        break;
      }
    }
  }
  state.SetItemsProcessed(state.iterations());
}

// ---------------------------------------------------------------------------------
// 2. Dense sampling: 1000 points into a reused CurveSamples (no allocation in the loop).

void sample1000(benchmark::State& state, double alpha, double kappa_start) {
  const LaSegment seg = typicalSegment(alpha, kappa_start);
  CurveSamples out;
  out.reserve(kSamplesPerCall);
  // Works: 1000 samples, the last at s = L and at the segment's end point.
  seg.sample(kSamplesPerCall, out);
  const double end_gap = (out.point.back() - seg.end()).norm();
  constexpr double kEndTolerance = 1e-9;  // relative to L = 1; requested accuracy is 1e-10
  if (out.size() != kSamplesPerCall || out.s.back() != seg.length() || !(end_gap <= kEndTolerance)) {
    state.SkipWithError(("sampling check failed: " + std::to_string(out.size()) +
                         " samples, end gap " + text(end_gap))
                            .c_str());
    return;
  }
  const std::size_t capacity = out.point.capacity();
  for (auto _ : state) {
    out.clear();
    seg.sample(kSamplesPerCall, out);
    benchmark::DoNotOptimize(out.point.data());
    benchmark::ClobberMemory();
  }
  if (out.point.capacity() != capacity) state.SkipWithError("CurveSamples reallocated in the loop");
  state.SetItemsProcessed(state.iterations() * kSamplesPerCall);
}

// ---------------------------------------------------------------------------------
// 3. and 4. Segment solves over fixed sets of control triangles.

struct Triangle {
  Vec2 q0, q1, q2;
};

// A control triangle in the standard form: turning angle theta_d, chord angle phi at Q0
// (between Q1 - Q0 and Q2 - Q0), 0 < phi < theta_d.
struct TriangleShape {
  double theta_d, phi;
};

// The control triangle of `shape` with chord length `chord`, mirrored (right turn) if
// asked, rotated by `heading` and moved to `origin`. In the standard form
// Q2 = chord (cos phi, sin phi) and Q1 = (|Q0 Q1|, 0) with, by the law of sines
// (angles phi at Q0, pi - theta_d at Q1, theta_d - phi at Q2),
// |Q0 Q1| = chord sin(theta_d - phi) / sin(theta_d).
Triangle makeTriangle(const TriangleShape& shape, double chord, bool mirror, double heading,
                      const Vec2& origin) {
  const double flip = mirror ? -1.0 : 1.0;
  const Vec2 q1(chord * std::sin(shape.theta_d - shape.phi) / std::sin(shape.theta_d), 0.0);
  const Vec2 q2(chord * std::cos(shape.phi), flip * chord * std::sin(shape.phi));
  const double c = std::cos(heading), s = std::sin(heading);
  auto place = [&](const Vec2& p) {
    return Vec2(origin.x() + c * p.x() - s * p.y(), origin.y() + s * p.x() + c * p.y());
  };
  return {place(Vec2::Zero()), place(q1), place(q2)};
}

// The shapes placed in the plane: mirrored every other one, rotated, moved and scaled,
// so that the timing covers the whole solve, not only the standard form.
std::vector<Triangle> placeTriangles(const std::vector<TriangleShape>& shapes) {
  std::vector<Triangle> out;
  for (std::size_t k = 0; k < shapes.size(); ++k) {
    const double heading = 0.7 * k - 2.0;
    const Vec2 origin(0.3 * k - 1.0, 2.0 - 0.1 * k);
    const double chord = 0.5 + 0.25 * (k % 5);
    out.push_back(makeTriangle(shapes[k], chord, k % 2 == 1, heading, origin));
  }
  return out;
}

// The triangle shape of the LA segment with this alpha, turning angle theta_d and end
// curvature ratio kappa_end / kappa_start: made from a segment of length 1 whose
// curvatures are scaled to give theta_d (for a fixed length the turning is linear in
// the curvature scale), its chord angle from its end point.
TriangleShape segmentShape(double alpha, double theta_d, double kappa_ratio) {
  const LaSegment unit(alpha, 1.0, Vec2::Zero(), 0.0, 1.0, kappa_ratio);
  const double k0 = theta_d / unit.turning();
  const LaSegment seg(alpha, 1.0, Vec2::Zero(), 0.0, k0, k0 * kappa_ratio);
  constexpr double kEndAccuracy = 1e-14;  // relative to the length
  const Vec2 e = seg.end(kEndAccuracy);
  return {seg.turning(), std::atan2(e.y(), e.x())};
}

// Issue: turning angles 0.2..2.8 rad; near straight 1e-3..1e-6 rad.
constexpr std::array<double, 4> kTurningAngles = {0.2, 1.0, 1.9, 2.8};
constexpr std::array<double, 4> kNearStraightTurningAngles = {1e-3, 1e-4, 1e-5, 1e-6};
// Issue: "curvature ratios of a few up to ~20", growing and shrinking curvature.
constexpr std::array<double, 4> kCurvatureRatios = {1.0 / 20.0, 1.0 / 4.0, 4.0, 20.0};
// Issue: chord angles between 25% and 75% of the turning angle. For many alphas most of
// this range is out of reach (alpha = 2: about 33%..67%; alpha = -3: 43%..57%), and
// near the edge of the reachable range the curvature ratio goes to 1e13, so these
// triangles time a different thing (ThreePointSolveChordGrid) from the typical solve.
constexpr std::array<double, 4> kChordFractions = {0.25, 0.4, 0.6, 0.75};

// Times `solve` cycling through `triangles`. Before timing, each is solved once and
// must be usable with its segment ending at Q2, else the benchmark is an error.
// Counters: the number of triangles, the range of chord angle / turning angle and of
// `shape_value` (counters `shape_name`_min/_max) over them, and the mean iterations.
template <class Solve, class ShapeValue>
void timeSolves(benchmark::State& state, const std::vector<Triangle>& triangles, Solve solve,
                const std::string& shape_name, ShapeValue shape_value) {
  if (triangles.empty()) {
    state.SkipWithError("no triangle to solve");
    return;
  }
  constexpr double kEndTolerance = 1e-8;  // relative to the chord |Q2 - Q0|
  constexpr double kInf = std::numeric_limits<double>::infinity();
  double shape_min = kInf, shape_max = -kInf, fraction_min = kInf, fraction_max = -kInf;
  double iterations = 0.0;
  for (std::size_t k = 0; k < triangles.size(); ++k) {
    const Triangle& t = triangles[k];
    const SegmentSolve result = solve(t);
    if (!result.report.usable() || !result.segment) {
      state.SkipWithError(("triangle " + std::to_string(k) + " not solved: " + result.report.message).c_str());
      return;
    }
    const double end_gap = (result.segment->end() - t.q2).norm() / (t.q2 - t.q0).norm();
    if (!(end_gap <= kEndTolerance)) {
      state.SkipWithError(("triangle " + std::to_string(k) + ": segment misses Q2 by " +
                           text(end_gap) + " of the chord")
                              .c_str());
      return;
    }
    shape_min = std::min(shape_min, shape_value(result));
    shape_max = std::max(shape_max, shape_value(result));
    fraction_min = std::min(fraction_min, result.chord_angle / result.theta_d);
    fraction_max = std::max(fraction_max, result.chord_angle / result.theta_d);
    iterations += result.report.iterations;
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const Triangle& t = triangles[i];
    i = (i + 1 == triangles.size()) ? 0 : i + 1;
    SegmentSolve result = solve(t);
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["triangles"] = static_cast<double>(triangles.size());
  state.counters["chord_fraction_min"] = fraction_min;
  state.counters["chord_fraction_max"] = fraction_max;
  state.counters[shape_name + "_min"] = shape_min;
  state.counters[shape_name + "_max"] = shape_max;
  state.counters["mean_iterations"] = iterations / triangles.size();
}

void timeThreePointSolves(benchmark::State& state, double alpha, const std::vector<Triangle>& triangles) {
  timeSolves(
      state, triangles, [alpha](const Triangle& t) { return solveThreePointSegment(alpha, t.q0, t.q1, t.q2); },
      "kappa_ratio", [](const SegmentSolve& s) { return std::exp(std::abs(s.shape)); });
}

// 3. The 3-point solve of the control triangles of LA segments with this alpha:
// `turning` x kCurvatureRatios, 16 triangles, all reachable by construction.
void threePointSolve(benchmark::State& state, double alpha, std::span<const double> turning) {
  std::vector<TriangleShape> shapes;
  for (const double theta_d : turning)
    for (const double ratio : kCurvatureRatios) shapes.push_back(segmentShape(alpha, theta_d, ratio));
  timeThreePointSolves(state, alpha, placeTriangles(shapes));
}

// 3'. The literal grid: kTurningAngles x kChordFractions, keeping the triangles
// inside reachableChordAngles for this alpha (none for alpha = -3: not registered).
std::vector<TriangleShape> chordGridShapes(double alpha) {
  std::vector<TriangleShape> shapes;
  for (const double theta_d : kTurningAngles) {
    const ChordAngleRange range = reachableChordAngles(alpha, theta_d);
    for (const double fraction : kChordFractions)
      if (range.contains(fraction * theta_d)) shapes.push_back({theta_d, fraction * theta_d});
  }
  return shapes;
}

void threePointSolveChordGrid(benchmark::State& state, double alpha) {
  const std::vector<TriangleShape> shapes = chordGridShapes(alpha);
  timeThreePointSolves(state, alpha, placeTriangles(shapes));
}

// 4. The inflection-end solve (inflection at Q0) over kTurningAngles x chord angles of
// 10%..45% of the turning angle (the construction reaches (0, theta_d / 2), narrowed
// by reachableInflectionChordAngles; triangles outside it are left out). The shape
// counter is the solved alpha.
constexpr std::array<double, 4> kInflectionChordFractions = {0.1, 0.2, 0.3, 0.45};

void inflectionSolve(benchmark::State& state) {
  std::vector<TriangleShape> shapes;
  for (const double theta_d : kTurningAngles) {
    const ChordAngleRange range = reachableInflectionChordAngles(theta_d);
    for (const double fraction : kInflectionChordFractions)
      if (range.contains(fraction * theta_d)) shapes.push_back({theta_d, fraction * theta_d});
  }
  timeSolves(
      state, placeTriangles(shapes),
      [](const Triangle& t) { return solveInflectionSegment(t.q0, t.q1, t.q2, InflectionEnd::kStart); },
      "alpha", [](const SegmentSolve& s) { return s.shape; });
}

// ---------------------------------------------------------------------------------
// 5. LCG regression of 200 samples of the typical segment.

struct LcgData {
  std::vector<double> s, kappa, dkappa;
};

constexpr double kLcgAlpha = 2.0;  // the slope the fit must recover

LcgData lcgData() {
  const LaSegment seg = typicalSegment(kLcgAlpha);
  LcgData d;
  for (int i = 0; i < kLcgSamples; ++i) {
    const double s = seg.length() * i / (kLcgSamples - 1);
    d.s.push_back(s);
    d.kappa.push_back(seg.kappa(s));
    d.dkappa.push_back(seg.dkappa(s));
  }
  return d;
}

// Works: the fit is usable and its slope is alpha, to rounding for the analytic
// derivative and to the O(h^2) finite-difference error for samples.
template <class Fit>
void lcgFit(benchmark::State& state, Fit fit, double alpha_tolerance) {
  const LcgFit check = fit();
  if (!check.report.usable() || !(std::abs(check.alpha - kLcgAlpha) <= alpha_tolerance)) {
    state.SkipWithError(("LCG fit check failed: alpha " + text(check.alpha) + ", " +
                         check.report.message)
                            .c_str());
    return;
  }
  for (auto _ : state) {
    LcgFit result = fit();
    benchmark::DoNotOptimize(result);
  }
  state.SetItemsProcessed(state.iterations() * kLcgSamples);
}

// ---------------------------------------------------------------------------------

bool registerAll() {
  for (const double alpha : {-1.0, 0.0, 1.0, 2.0, 0.5}) {
    const std::string a = "/alpha:" + text(alpha);
    benchmark::RegisterBenchmark(("PointEval/kappa" + a).c_str(), pointEval, alpha, PointQuery::kKappa);
    benchmark::RegisterBenchmark(("PointEval/theta" + a).c_str(), pointEval, alpha, PointQuery::kTheta);
    benchmark::RegisterBenchmark(("PointEval/position" + a).c_str(), pointEval, alpha,
                                 PointQuery::kPosition);
  }

  // alpha = -2 with kappa_start = 0: an inflection at the start.
  benchmark::RegisterBenchmark("Sample1000/alpha:-2/inflection_start", sample1000, -2.0, 0.0)
      ->Unit(benchmark::kMicrosecond);
  for (const double alpha : {-1.0, 0.0, 0.5, 1.0, 2.0, 3.0}) {
    benchmark::RegisterBenchmark(("Sample1000/alpha:" + text(alpha)).c_str(), sample1000, alpha,
                                 kTypicalKappaStart)
        ->Unit(benchmark::kMicrosecond);
  }

  constexpr std::array<double, 10> kSolveAlphas = {-3, -2, -1, -0.5, 0, 0.5, 1, 1.5, 2, 3};
  for (const double alpha : kSolveAlphas) {
    benchmark::RegisterBenchmark(("ThreePointSolve/alpha:" + text(alpha)).c_str(), threePointSolve,
                                 alpha, std::span<const double>(kTurningAngles))
        ->Unit(benchmark::kMicrosecond);
  }
  for (const double alpha : kSolveAlphas) {
    benchmark::RegisterBenchmark(("ThreePointSolveNearStraight/alpha:" + text(alpha)).c_str(),
                                 threePointSolve, alpha, std::span<const double>(kNearStraightTurningAngles))
        ->Unit(benchmark::kMicrosecond);
  }
  for (const double alpha : kSolveAlphas) {
    // e.g. alpha = -3 reaches none of the grid (chord fractions 0.42..0.58 only)
    if (chordGridShapes(alpha).empty()) continue;
    benchmark::RegisterBenchmark(("ThreePointSolveChordGrid/alpha:" + text(alpha)).c_str(),
                                 threePointSolveChordGrid, alpha)
        ->Unit(benchmark::kMicrosecond);
  }

  benchmark::RegisterBenchmark("InflectionSolve/start", inflectionSolve)->Unit(benchmark::kMicrosecond);

  static const LcgData data = lcgData();
  constexpr double kDerivativeAlphaTolerance = 1e-9;  // rounding only
  constexpr double kSamplesAlphaTolerance = 1e-2;     // O(h^2) differences, h = 1/199
  benchmark::RegisterBenchmark(
      "LcgFit200/derivative",
      [](benchmark::State& state) {
        lcgFit(state, [] { return fitLcg(lcgFromDerivative(data.kappa, data.dkappa)); },
               kDerivativeAlphaTolerance);
      })
      ->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark(
      "LcgFit200/samples",
      [](benchmark::State& state) {
        lcgFit(state, [] { return fitLcg(lcgFromSamples(data.s, data.kappa)); }, kSamplesAlphaTolerance);
      })
      ->Unit(benchmark::kMicrosecond);
  return true;
}

[[maybe_unused]] const bool kRegistered = registerAll();

}  // namespace
}  // namespace la
