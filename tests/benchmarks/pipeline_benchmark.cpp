// Benchmarks of the fitting pipeline (fitting/pipeline.h): the whole fit of a stroke of
// 100, 1,000 and 10,000 points, and each stage alone on the 1,000-point stroke.
// Target (issue 3): a 1,000-point stroke in at most 2 ms median on one core, cost
// growing linearly with the number of points.
//
//   build/tests/benchmarks/pipeline_benchmark --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
//
// Also the bundled samples as lafit fits them: the two pen strokes of samples/
// question_mark.csv and the Clark Y profile of samples/clark-y.dat (a closed curve with
// its leading-edge turn, where a solver astray once cost 340 ms).
//
// The stroke is a G2 chain of four LA segments (alphas -1, 2, 0.5, -0.5; curvature
// extrema at the joints) sampled at unit spacing with Gaussian noise of 0.1% of its
// bounding-box diagonal (std::mt19937, seed 5), scaled so that it has N points.

#include <benchmark/benchmark.h>

#include <random>

#include "app/io/point_file.h"
#include "fitting/chain_fit.h"
#include "fitting/pipeline.h"

namespace la {
namespace {

Stroke chainStroke(int points) {
  const double scale = points / 1000.0;
  std::vector<LaSegment> segs;
  segs.emplace_back(-1.0, 250 * scale, Vec2(0, 0), 0.0, 0.002 / scale, 0.008 / scale);
  auto next = [&](double alpha, double length, double kappa_end) {
    const LaSegment& p = segs.back();
    segs.emplace_back(alpha, length * scale, p.end(1e-13), p.theta(p.length()), p.kappaEnd(), kappa_end / scale);
  };
  next(2.0, 250, 0.001);
  next(0.5, 250, 0.009);
  next(-0.5, 250, 0.002);
  std::vector<Vec2> clean;
  for (const LaSegment& s : segs) {
    const CurveSamples smp = s.sample(std::max(2, static_cast<int>(std::round(s.length()))));
    for (std::size_t i = clean.empty() ? 0 : 1; i < smp.size(); ++i) clean.push_back(smp.point[i]);
  }
  Vec2 lo = clean[0], hi = clean[0];
  for (const Vec2& p : clean) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  std::mt19937 rng(5);
  std::normal_distribution<double> noise(0.0, 0.001 * (hi - lo).norm());
  Stroke stroke;
  for (const Vec2& p : clean) stroke.samples.push_back({p + Vec2(noise(rng), noise(rng))});
  return stroke;
}

void BM_FitStroke(benchmark::State& state) {
  const Stroke stroke = chainStroke(static_cast<int>(state.range(0)));
  const FitResult check = fitStroke(stroke);
  if (check.curve.pieces.empty()) state.SkipWithError("the stroke does not fit");
  for (auto _ : state) benchmark::DoNotOptimize(fitStroke(stroke));
  state.counters["points"] = static_cast<double>(stroke.samples.size());
  state.counters["segments"] = check.quality.segments;
  state.SetComplexityN(state.range(0));
}
BENCHMARK(BM_FitStroke)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond)->Complexity();

void BM_FitSample(benchmark::State& state) {
  const char* names[] = {"question_mark.csv", "clark-y.dat"};
  const std::vector<Stroke> strokes = readStrokes(std::string(LAFAIR_SOURCE_DIR) + "/samples/" + names[state.range(0)]);
  for (auto _ : state)
    for (const Stroke& s : strokes) benchmark::DoNotOptimize(fitStroke(s));
  state.SetLabel(names[state.range(0)]);
  state.counters["strokes"] = static_cast<double>(strokes.size());
}
BENCHMARK(BM_FitSample)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

// The paper's pipeline alone (FitOptions::polish off: stages 1-6, as the app's live
// preview runs it while the pen moves).
void BM_FitStrokePaperOnly(benchmark::State& state) {
  const Stroke stroke = chainStroke(static_cast<int>(state.range(0)));
  FitOptions options;
  options.polish = false;
  const FitResult check = fitStroke(stroke, options);
  if (check.curve.pieces.empty()) state.SkipWithError("the stroke does not fit");
  for (auto _ : state) benchmark::DoNotOptimize(fitStroke(stroke, options));
  state.counters["points"] = static_cast<double>(stroke.samples.size());
  state.counters["segments"] = check.quality.segments;
}
BENCHMARK(BM_FitStrokePaperOnly)->Arg(100)->Arg(1000)->Arg(10000)->Unit(benchmark::kMillisecond);

void BM_StageCleanup(benchmark::State& state) {
  const Stroke stroke = chainStroke(1000);
  for (auto _ : state) benchmark::DoNotOptimize(cleanStroke(stroke));
}
BENCHMARK(BM_StageCleanup)->Unit(benchmark::kMicrosecond);

// The pipeline's defaults for this stroke: 0.5% tolerance, the noise it was made with.
SmoothingOptions smoothingOptions(const CleanStroke& clean) {
  SmoothingOptions options;
  options.tolerance = 0.005 * clean.diagonal;
  options.noise_sigma = 0.001 * clean.diagonal;
  return options;
}

void BM_StageSmoothing(benchmark::State& state) {
  const CleanStroke clean = cleanStroke(chainStroke(1000));
  const SmoothingOptions options = smoothingOptions(clean);
  for (auto _ : state) benchmark::DoNotOptimize(smoothWithBSpline(clean.points, false, options));
}
BENCHMARK(BM_StageSmoothing)->Unit(benchmark::kMicrosecond);

void BM_StageSegmentation(benchmark::State& state) {
  const CleanStroke clean = cleanStroke(chainStroke(1000));
  const SmoothingResult smooth = smoothWithBSpline(clean.points, false, smoothingOptions(clean));
  for (auto _ : state) benchmark::DoNotOptimize(segmentSpline(smooth.spline));
}
BENCHMARK(BM_StageSegmentation)->Unit(benchmark::kMicrosecond);

void BM_StageG2(benchmark::State& state) {
  // The chain as the pipeline builds it: joints and tangents of the fitted curve,
  // with the tangents disturbed so the gaps are open again.
  const FitResult fit = fitStroke(chainStroke(1000));
  Chain base;
  for (std::size_t i = 0; i < fit.curve.pieces.size(); ++i) {
    const LaSegment& s = fit.curve.pieces[i].segment;
    base.joints.push_back(s.start());
    base.angles.push_back(s.theta0() + (i == 0 ? 0.0 : (i % 2 ? 0.003 : -0.003)));
    base.pieces.push_back({fit.pieces[i].kind, s.alpha()});
  }
  const LaSegment& last = fit.curve.pieces.back().segment;
  base.joints.push_back(last.end());
  base.angles.push_back(last.theta(last.length()));
  G2Options options;
  options.diagonal = fit.quality.diagonal;
  Chain probe = base;
  if (!makeG2(probe, options).report.usable()) state.SkipWithError("G2 does not converge on this chain");
  for (auto _ : state) {
    Chain chain = base;
    benchmark::DoNotOptimize(makeG2(chain, options));
  }
}
BENCHMARK(BM_StageG2)->Unit(benchmark::kMicrosecond);

void BM_StageChainFit(benchmark::State& state) {
  // Stage 7's least-squares fit alone, as the pipeline calls it (300 bins of the points,
  // 8 steps), from the chain stages 1-6 make.
  FitOptions paper;
  paper.polish = false;
  const FitResult start = fitStroke(chainStroke(1000), paper);
  std::vector<LaSegment> chain;
  for (const CurvePiece& p : start.curve.pieces) chain.push_back(p.segment);
  std::vector<ChainFoot> feet;
  std::vector<double> distance;
  projectOnChain(chain, false, start.cleaned.points, feet, distance);
  ChainFitOptions options;
  options.max_points = 300;
  options.max_iterations = 8;
  options.noise = 0.001 * start.quality.diagonal;
  if (!fitChain(chain, start.cleaned.points, feet, options).improved) state.SkipWithError("the fit does not improve");
  for (auto _ : state) benchmark::DoNotOptimize(fitChain(chain, start.cleaned.points, feet, options));
}
BENCHMARK(BM_StageChainFit)->Unit(benchmark::kMicrosecond);

void BM_StageQuality(benchmark::State& state) {
  const FitResult fit = fitStroke(chainStroke(1000));
  for (auto _ : state) benchmark::DoNotOptimize(measureQuality(fit.curve, fit.cleaned.points));
}
BENCHMARK(BM_StageQuality)->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace la
