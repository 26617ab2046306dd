// The whole pipeline (fitStroke, default options) on strokes sampled from one LA segment
// of several turns: the spirals a fitter of LA curves must fit with one or a few segments
// (issue 16). Each benchmark is one alpha; one iteration fits all its spirals once:
// 1, 2.5, 4 and 5 turns (curvature 0.004 to 0.08), 200, 700 and 2,000 points at equal arc
// length, noise-free and with Gaussian noise of 0.1 and 0.3 units (seeds 1 and 2). Its
// counters: the spirals fitted, those that miss the tolerance, those of them whose true
// spiral keeps it (truth_kept_missed: the true curve is within the tolerance of every
// sample, the fit is not; where the noise puts some sample further than the tolerance
// from the truth itself, no fair curve need keep it), those with more than 2 segments a
// turn and those of them whose true spiral keeps the tolerance (truth_kept_over_2: where
// it does not, the chain that keeps the tolerance follows the noise), those fitted as one
// segment, those bending tighter than the tolerance anywhere,
// and the fit time per spiral (median, p90, max; one core).
//
// Also Archimedean spirals drawn out from a tight centre (r = 5 + 60 theta / 2 pi: no LA
// curve), the same turns, points and noise, the points at equal steps of the angle, so
// their centre is sampled ten times as densely as their outer turns (BM_Archimedean);
// and the logarithmic spirals at the loose tolerances a user sets with the app's slider,
// 2, 5 and 8% of the diagonal (BM_LogSpiralsLoose), where their inner turns bend tighter
// than the tolerance and become corners.
//
//   build/tests/benchmarks/spiral_benchmark

#include <benchmark/benchmark.h>

#include <algorithm>
#include <numbers>
#include <random>
#include <vector>

#include "fitting/parts.h"
#include "fitting/pipeline.h"

namespace la {
namespace {

struct Spiral {
  Stroke stroke;
  double turns;
  double truth_deviation = 0.0;  // of the samples from the true spiral
};

// The Archimedean spiral r = 5 + b theta, b = 60 / 2 pi, and the distance of p from it,
// from its nearest point's angle near theta (Newton on (P - p) . P' = 0).
constexpr double kArchimedeanStart = 5.0, kArchimedeanGrowth = 60.0 / (2.0 * std::numbers::pi);
Vec2 archimedean(double theta) {
  const double r = kArchimedeanStart + kArchimedeanGrowth * theta;
  return {r * std::cos(theta), r * std::sin(theta)};
}
double distanceFromArchimedean(const Vec2& p, double theta, double turns) {
  const double b = kArchimedeanGrowth;
  for (int step = 0; step < 20; ++step) {
    const double r = kArchimedeanStart + b * theta, c = std::cos(theta), s = std::sin(theta);
    const Vec2 d = archimedean(theta) - p;
    const Vec2 d1(b * c - r * s, b * s + r * c), d2(-2.0 * b * s - r * c, 2.0 * b * c - r * s);
    const double f = d.dot(d1), df = d1.dot(d1) + d.dot(d2);
    const double next = std::clamp(theta - f / std::max(df, 1e-300), 0.0, 2.0 * std::numbers::pi * turns);
    if (std::abs(next - theta) < 1e-14) break;
    theta = next;
  }
  return (archimedean(theta) - p).norm();
}

std::vector<Spiral> archimedeanSpirals() {
  std::vector<Spiral> out;
  for (double turns : {1.0, 2.5, 4.0, 5.0})
    for (int n : {200, 700, 2000})
      for (double noise : {0.0, 0.1, 0.3})
        for (unsigned seed : {1u, 2u}) {
          if (noise == 0.0 && seed > 1u) continue;
          std::mt19937 rng(seed);
          std::normal_distribution<double> g(0.0, noise);
          Spiral s{{}, turns};
          for (int i = 0; i <= n; ++i) {
            const double theta = 2.0 * std::numbers::pi * turns * i / n;
            const Vec2 p = archimedean(theta);
            s.stroke.samples.push_back({noise > 0.0 ? Vec2(p + Vec2(g(rng), g(rng))) : p});
            s.truth_deviation = std::max(s.truth_deviation, distanceFromArchimedean(s.stroke.samples.back().p, theta, turns));
          }
          out.push_back(std::move(s));
        }
  return out;
}

std::vector<Spiral> spiralsOf(double alpha) {
  std::vector<Spiral> out;
  for (double turns : {1.0, 2.5, 4.0, 5.0}) {
    const LaSegment truth = LaSegment::withTurning(alpha, 2.0 * std::numbers::pi * turns, {0, 0}, 0.3, 0.004, 0.08);
    for (int n : {200, 700, 2000})
      for (double noise : {0.0, 0.1, 0.3})
        for (unsigned seed : {1u, 2u}) {
          if (noise == 0.0 && seed > 1u) continue;  // (noise-free: one is enough)
          std::mt19937 rng(seed);
          std::normal_distribution<double> g(0.0, noise);
          Spiral s{{}, turns};
          std::vector<Vec2> points;
          for (int i = 0; i <= n; ++i) {
            const Vec2 p = truth.position(truth.length() * i / n);
            points.push_back(noise > 0.0 ? Vec2(p + Vec2(g(rng), g(rng))) : p);
            s.stroke.samples.push_back({points.back()});
          }
          // (measured as the fit's own deviation is)
          s.truth_deviation = maxDeviationOf({truth}, points, boundingBoxDiagonal(points));
          out.push_back(std::move(s));
        }
  }
  return out;
}

void fitAll(benchmark::State& state, const std::vector<Spiral>& spirals, const FitOptions& options = {}) {
  int missed = 0, truth_kept_missed = 0, too_many = 0, truth_kept_too_many = 0, one = 0, tighter = 0;
  std::vector<double> ms;
  for (auto _ : state) {
    missed = truth_kept_missed = too_many = truth_kept_too_many = one = tighter = 0;
    ms.clear();
    for (const Spiral& s : spirals) {
      const FitResult r = fitStroke(s.stroke, options);
      ms.push_back(r.timings.total_ms);
      missed += r.quality.max_dev > r.tolerance;
      truth_kept_missed += r.quality.max_dev > r.tolerance && s.truth_deviation <= r.tolerance;
      const bool over_2_a_turn = static_cast<double>(r.curve.pieces.size()) > 2.0 * s.turns;
      too_many += over_2_a_turn;
      truth_kept_too_many += over_2_a_turn && s.truth_deviation <= r.tolerance;
      one += r.curve.pieces.size() == 1;
      tighter += r.quality.min_radius * (1.0 + 1e-6) < r.tolerance;
    }
  }
  std::sort(ms.begin(), ms.end());
  state.counters["spirals"] = static_cast<double>(spirals.size());
  state.counters["missed"] = missed;
  state.counters["truth_kept_missed"] = truth_kept_missed;
  state.counters["over_2_a_turn"] = too_many;
  state.counters["truth_kept_over_2"] = truth_kept_too_many;
  state.counters["one_segment"] = one;
  state.counters["bends_tighter"] = tighter;
  state.counters["ms_median"] = ms[ms.size() / 2];
  state.counters["ms_p90"] = ms[ms.size() * 9 / 10];
  state.counters["ms_max"] = ms.back();
}
void BM_Spirals(benchmark::State& state) { fitAll(state, spiralsOf(static_cast<double>(state.range(0)) / 4.0)); }
void BM_Archimedean(benchmark::State& state) { fitAll(state, archimedeanSpirals()); }
// alpha = range / 4: -2, -1, 0, 0.5, 1, 2
BENCHMARK(BM_Spirals)->Arg(-8)->Arg(-4)->Arg(0)->Arg(2)->Arg(4)->Arg(8)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Archimedean)->Iterations(1)->Unit(benchmark::kMillisecond);
// The logarithmic spirals (alpha 1) at a loose tolerance, range % of the diagonal: their
// inner turns then bend tighter than the tolerance, and become corners.
void BM_LogSpiralsLoose(benchmark::State& state) {
  FitOptions options;
  options.tolerance_fraction = static_cast<double>(state.range(0)) / 100.0;
  fitAll(state, spiralsOf(1.0), options);
}
BENCHMARK(BM_LogSpiralsLoose)->Arg(2)->Arg(5)->Arg(8)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace la
