// Speed of the ALP curves (core/alp_curve.h, core/alp_hermite.h, core/alp_region_map.h;
// seeds 000, 004: "interactive speed").
//
// Run (median of 5 repetitions is the figure to report):
//   ./tests/benchmarks/alp_benchmark --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true
// (one command line; from the build directory).
//
// Groups:
//   AlpSolve/G{1,2}/n:N/rational:R   one solveAlpHermite over a fixed set of 8 end
//                                    conditions (turning 0.4..2.2 rad, C and S shapes;
//                                    G2 curvatures near the circular arc's), p = 0.3,
//                                    rational: w_e = 2.5, p_w = -0.5. Time per solve.
//   AlpCurveBuild/n:N/rational:R     constructing an AlpCurve (its tables) of turning ~2
//   AlpSample200/rational:R          AlpCurve::sample(200)
//   AlpRegionMap/size:S              computeAlpRegionMap, n = 5, theta 40 / -20 deg, range +-4
//
// Every benchmark checks before its timed loop that what it times works (all solves
// converge) and reports SkipWithError otherwise. Inputs are deterministic grids.

#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "core/alp_curve.h"
#include "core/alp_hermite.h"
#include "core/alp_region_map.h"

namespace la {
namespace {

struct Condition {
  HermiteEnd a, b;
};

// Normalized-chord conditions: start tangent t0, end tangent t1 relative to the chord.
std::vector<Condition> conditions() {
  std::vector<Condition> out;
  const double t0s[] = {0.3, 0.6, 0.9, 1.1}, offsets[] = {-0.6, 0.25};
  for (double t0 : t0s)
    for (double off : offsets) {
      const double t1 = -t0 + off;  // near-symmetric C (and S for larger off)
      const double k = -2.0 * std::sin(0.5 * (t0 - t1));
      out.push_back({{Vec2(1, 2), t0 + 0.2, 0.8 * k}, {Vec2(1, 2) + unitVector(0.2) * 3.0, t1 + 0.2, 1.2 * k}});
      out.back().a.kappa /= 3.0;
      out.back().b.kappa /= 3.0;
    }
  return out;
}

AlpShape shapeOf(int n, bool rational) {
  AlpShape s;
  s.degree = n;
  s.p = 0.3;
  s.rational = rational;
  s.w_e = rational ? 2.5 : 1.0;
  s.p_w = rational ? -0.5 : 0.0;
  return s;
}

void AlpSolveBench(benchmark::State& state) {
  const int continuity = static_cast<int>(state.range(0)), n = static_cast<int>(state.range(1));
  const bool rational = state.range(2) != 0;
  const auto conds = conditions();
  const AlpShape shape = shapeOf(n, rational);
  int iterations = 0;
  for (const Condition& c : conds) {
    const AlpSolve s = solveAlpHermite(c.a, c.b, continuity, shape);
    if (!s.report.usable()) {
      state.SkipWithError(("solve failed: " + s.report.message).c_str());
      return;
    }
    iterations += s.report.iterations;
  }
  std::size_t i = 0;
  for (auto _ : state) {
    const Condition& c = conds[i++ % conds.size()];
    benchmark::DoNotOptimize(solveAlpHermite(c.a, c.b, continuity, shape));
  }
  state.counters["lm_iterations"] = double(iterations) / conds.size();
}
BENCHMARK(AlpSolveBench)
    ->Name("AlpSolve")
    ->ArgNames({"G", "n", "rational"})
    ->ArgsProduct({{1, 2}, {3, 5}, {0, 1}})
    ->Unit(benchmark::kMicrosecond);

void AlpCurveBuild(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const bool rational = state.range(1) != 0;
  std::vector<double> kappa(n + 1), weights;
  for (int i = 0; i <= n; ++i) kappa[i] = 1.0 + std::sin(1.3 * i);
  if (rational) weights = alpWeights(shapeOf(n, true));
  for (auto _ : state) benchmark::DoNotOptimize(AlpCurve(kappa, weights, 1.5, Vec2(0, 0), 0.0));
}
BENCHMARK(AlpCurveBuild)->ArgNames({"n", "rational"})->ArgsProduct({{3, 5}, {0, 1}})->Unit(benchmark::kMicrosecond);

void AlpSample200(benchmark::State& state) {
  const bool rational = state.range(0) != 0;
  std::vector<double> kappa = {1.0, -2.0, 3.0, 0.5, 1.5, -1.0};
  const AlpCurve c(kappa, rational ? alpWeights(shapeOf(5, true)) : std::vector<double>{}, 2.0, Vec2(0, 0), 0.0);
  CurveSamples smp;
  smp.reserve(200);
  for (auto _ : state) {
    smp.clear();
    c.sample(200, smp);
    benchmark::DoNotOptimize(smp.point.back());
  }
}
BENCHMARK(AlpSample200)->ArgName("rational")->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void AlpRegionMapBench(benchmark::State& state) {
  AlpRegionRequest r;
  r.theta_start = 40.0 * M_PI / 180.0;
  r.theta_end = -20.0 * M_PI / 180.0;
  r.shape.degree = 5;
  r.size = static_cast<int>(state.range(0));
  const AlpRegionMap check = computeAlpRegionMap(r);
  if (check.count(AlpRegionCell::kMonotone) == 0) {
    state.SkipWithError("the map has no monotone cell");
    return;
  }
  for (auto _ : state) benchmark::DoNotOptimize(computeAlpRegionMap(r));
  state.counters["cells"] = double(r.size) * r.size;
  state.counters["no_solution"] = check.count(AlpRegionCell::kNoSolution);
}
BENCHMARK(AlpRegionMapBench)->Name("AlpRegionMap")->ArgName("size")->Arg(41)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace la
