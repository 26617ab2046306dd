// The whole pipeline (fitting/pipeline.h, fitStroke) on every stroke of the shared data
// (../shared/data, see its SOURCES.md), per data set as tests/fit_data_test.cpp groups
// them (tests/shared_data_sets.h: glyph contours with assume_closed, everything else
// with the default options). Each data set is one Google Benchmark of one iteration that
// fits all its strokes once; after them a table, one row per data set and one for all,
// of the distribution over the fitted strokes (median / 90th / 99th percentile /
// maximum, nearest rank) of:
//  - time ms: FitResult::timings.total_ms, one stroke on one core;
//  - segments;
//  - extrema_dense: curvature reversals along the whole curve, a jump at a corner
//    included (fitting/quality.h, counted as ../shared/tools/lacheck.py counts them);
//  - max_dev/tol: the largest distance from a point over the tolerance the fit used
//    (FitResult::tolerance: raised to the noise floor where the fit raised it);
// and the tightest radius over the tolerance (min_radius / tolerance: its minimum over
// the strokes, and the strokes that bend tighter than the tolerance), the share of the
// drawn length the clean-up left out (CleanStroke::left_out_fraction, in %: p99, max, and
// the strokes over the 5% that draws a warning), and with a cap on
// extrema the smooth parts that have more (QualityFigures::extrema_per_part), of all
// parts. Strokes fitStroke rejects as degenerate (StrokeError) are counted, not measured.
// Below the table, per data set, the slowest stroke, the one furthest from its points and
// the one with the tightest bend, every stroke kinked at a joint that is no corner (not G2
// there: kKink), and with a cap, every stroke with a part over it.
//
//   build/tests/benchmarks/data_benchmark [--max-extrema=N] [--paper-only] [--time-budget=MS] [--variants=K]
//                                         [--repeats=R] [--handed-over=HOW] [--data=DIR] [--rows=FILE]
//
// --max-extrema=N  FitOptions::segmentation.max_extrema = N (fitting/segmentation.h),
//                  and the table counts the parts over N
// --paper-only     FitOptions::polish = false: stages 1-6, as the app's live preview
// --time-budget=MS FitOptions::time_budget_ms = MS (the app's pen-up fit uses 250)
// --variants=K     every stroke fitted K times (1 to 8): variant k scaled by 1 + k/10, moved by
//                  k (12.345, -6.789) and turned by k quarter turns. The fit is invariant
//                  to these (its tolerance follows the diagonal; a pixel grid stays a
//                  grid), so each is the same stroke up to rounding; but the model
//                  selection can take another path on rounding alone. The table then
//                  shows the distribution over all variants. (It moves little: the
//                  paths turn on thresholds that rounding seldom crosses, but a change of
//                  ~1e-6 of a segment's length in the chain fit's model moved the shared
//                  data's p99 anywhere between 83 and 230 ms.)
// --repeats=R      every stroke (and variant) fitted R times in a row (1 to 10), its time the
//                  fastest of them: on a shared machine one fit's time is up to half again
//                  its fastest (the load of the moment; over three runs of --variants=8,
//                  a stroke's first time was 8% above its fastest at the median, 47% at
//                  the 90th percentile). A fit is deterministic, so every repeat must give
//                  the same figures; a stroke whose figures differ is listed below the
//                  table (with a time budget they may: where it runs out depends on the load).
// --handed-over=HOW  every stroke's samples as a device or an importer may hand them over
//                  (test::handedOver): `smoothed` by a tablet driver's [1 2 1] / 4 filter,
//                  with the `midpoints` of its steps filled in, with its steps `filled`
//                  evenly a 300th of its diagonal apart, or `resampled` by arc length at
//                  that spacing; the same strokes, so the figures should stay near those of
//                  the strokes as drawn. Or `walked` pixel by pixel by a slow mouse at a
//                  diagonal of 800 pixels: the samples' wiggles become shape at the
//                  pixels' scale (more segments), the time and the guarantees are what
//                  to watch. Or `rounded` to the pixels of a diagonal of 150: a pointer's
//                  events, several pixels apart where it moves fast
// --data=DIR       the shared data folder (default: ../shared/data beside the sources)
// --rows=FILE      also every stroke's figures, one CSV row each (data set, stroke, time ms,
//                  segments, extrema_dense, max_dev/tol, min_radius/tol: data_rows.h), to
//                  compare two builds stroke by stroke with compare_rows: the model
//                  selection's paths move single strokes that the distributions hide
// Google Benchmark's own flags (--benchmark_filter=glyphs, ...) work as usual.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iterator>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "app/io/point_file.h"
#include "core/atomic_file.h"
#include "fitting/pipeline.h"
#include "tests/benchmarks/data_rows.h"
#include "tests/shared_data_sets.h"

namespace la {
namespace {

namespace fs = std::filesystem;
using test::DataSet;
using test::kDataSets;
using test::percentile;

struct Settings {
  FitOptions options;  // the defaults, with the flags applied
  int variants = 1;
  int repeats = 1;
  test::HandedOver handed_over = test::HandedOver::kAsDrawn;
  fs::path data = LAFAIR_SHARED_DATA_DIR;
  fs::path rows;  // (empty: none written)
};
Settings g_settings;

// What the table reads off one fitted stroke.
struct StrokeFigures {
  std::string where;  // file (relative to the data folder) and stroke index
  double ms = 0.0;
  int segments = 0;
  int extrema_dense = 0;
  double deviation = 0.0;  // max_dev / tolerance
  double radius = 0.0;     // min_radius / tolerance
  int parts = 0;
  int parts_over_cap = 0;
  double left_out = 0.0;  // CleanStroke::left_out_fraction: drawn length the curve leaves out
  bool kinked = false;    // a joint that is no corner breaks G1 or G2 (kKink)
};

// A tangent (radians) or relative curvature gap above this at a joint that is no corner
// breaks the promise of G2 (issue 16's figure, lacheck's).
constexpr double kKink = 1e-9;

// A curve that leaves out more of the drawn length than this says so (fitting/pipeline.cpp).
constexpr double kLeftOutWarning = 0.05;

struct SetFigures {
  bool ran = false;
  int files = 0, strokes = 0, rejected = 0;
  std::vector<StrokeFigures> fitted;
  std::vector<std::string> nondeterministic;  // strokes whose repeats gave other figures
};
std::vector<SetFigures> g_results(std::size(kDataSets));

StrokeFigures figuresOf(std::string where, const FitResult& r, int cap) {
  const QualityFigures& q = r.quality;
  StrokeFigures f{std::move(where), r.timings.total_ms, q.segments, q.extrema_dense, q.max_dev / r.tolerance,
                  q.min_radius / r.tolerance, static_cast<int>(q.extrema_per_part.size()), 0,
                  r.cleaned.left_out_fraction, q.g1_gap > kKink || q.g2_gap > kKink};
  if (cap >= 0)
    f.parts_over_cap = static_cast<int>(std::count_if(q.extrema_per_part.begin(), q.extrema_per_part.end(),
                                                      [cap](int extrema) { return extrema > cap; }));
  return f;
}

// A stroke's row of the --rows file (data_rows.h).
test::StrokeRow rowOf(const char* data_set, const StrokeFigures& s) {
  return {data_set, s.where, s.ms, s.segments, s.extrema_dense, s.deviation, s.radius};
}

void BM_FitDataSet(benchmark::State& state, std::size_t index) {
  const DataSet& set = kDataSets[index];
  const std::vector<fs::path> files = test::filesOf(g_settings.data / set.folder, set.extension);
  std::vector<Stroke> strokes;
  std::vector<std::string> where;
  for (const fs::path& file : files) {
    std::vector<Stroke> some = readStrokes(file);
    for (int v = 0; v < g_settings.variants; ++v)
      for (std::size_t k = 0; k < some.size(); ++k) {
        where.push_back(fs::relative(file, g_settings.data).string() + " #" + std::to_string(k) +
                        (v > 0 ? " variant " + std::to_string(v) : ""));
        strokes.push_back(test::variantOf(test::handedOver(some[k], g_settings.handed_over), v));
      }
  }
  if (strokes.empty()) {
    state.SkipWithError(("no strokes under " + (g_settings.data / set.folder).string()).c_str());
    return;
  }
  const FitOptions options = test::fitOptionsFor(set, g_settings.options);
  SetFigures figures;
  for (auto _ : state) {
    figures = {true, static_cast<int>(files.size()), static_cast<int>(strokes.size()), 0, {}, {}};
    for (std::size_t i = 0; i < strokes.size(); ++i) {
      try {
        StrokeFigures fastest = figuresOf(where[i], fitStroke(strokes[i], options), options.segmentation.max_extrema);
        bool differs = false;  // (the figures of a repeat from the first fit's)
        for (int repeat = 1; repeat < g_settings.repeats; ++repeat) {
          const StrokeFigures again = figuresOf(where[i], fitStroke(strokes[i], options), options.segmentation.max_extrema);
          differs = differs || !test::sameFigures(rowOf(set.name, again), rowOf(set.name, fastest));
          fastest.ms = std::min(fastest.ms, again.ms);
        }
        if (differs) figures.nondeterministic.push_back(where[i]);
        figures.fitted.push_back(std::move(fastest));
      } catch (const StrokeError&) {
        ++figures.rejected;
      }
    }
  }
  state.counters["strokes"] = figures.strokes;
  state.counters["rejected"] = figures.rejected;
  g_results[index] = std::move(figures);
}

// "median p90 p99 max" of one figure of the strokes, each in `format`.
template <typename Figure>
std::string distribution(const std::vector<StrokeFigures>& strokes, Figure figure, const char* format) {
  std::vector<double> values;
  for (const StrokeFigures& s : strokes) values.push_back(figure(s));
  std::string out;
  char cell[32];
  for (double p : {0.5, 0.9, 0.99, 1.0}) {
    std::snprintf(cell, sizeof cell, format, percentile(values, p));
    out += cell;
  }
  return out;
}

void printRow(const char* name, const SetFigures& set, int cap) {
  std::printf("%-12s %5d %7d %4d", name, set.files, set.strokes, set.rejected);
  const std::vector<StrokeFigures>& f = set.fitted;
  if (f.empty()) {
    std::printf("  (nothing fitted)\n");
    return;
  }
  double tightest = INFINITY;
  int tight = 0, parts = 0, over = 0, left_out = 0;
  for (const StrokeFigures& s : f) {
    tightest = std::min(tightest, s.radius);
    if (s.radius < 1.0) ++tight;
    if (s.left_out > kLeftOutWarning) ++left_out;
    parts += s.parts, over += s.parts_over_cap;
  }
  std::printf(" |%s |%s |%s |%s | %8.3g %5d %5.1f%%", distribution(f, [](auto& s) { return s.ms; }, "%7.2f").c_str(),
              distribution(f, [](auto& s) { return s.segments; }, "%4.0f").c_str(),
              distribution(f, [](auto& s) { return s.extrema_dense; }, "%4.0f").c_str(),
              distribution(f, [](auto& s) { return s.deviation; }, "%6.3f").c_str(), tightest, tight,
              100.0 * tight / f.size());
  std::vector<double> left;
  for (const StrokeFigures& s : f) left.push_back(100.0 * s.left_out);
  std::printf(" | %5.1f %5.1f %4d", percentile(left, 0.99), percentile(left, 1.0), left_out);
  if (cap >= 0) std::printf(" | %5d of %5d", over, parts);
  std::printf("\n");
}

void printTable() {
  const FitOptions& o = g_settings.options;
  const int cap = o.segmentation.max_extrema;
  const test::HandedOver how = g_settings.handed_over;
  std::printf("\nShared data %s%s; options: %s, max_extrema %d, time budget %g ms\n",
              g_settings.data.lexically_normal().string().c_str(),
              how == test::HandedOver::kSmoothed    ? " (smoothed [1 2 1] / 4)"
              : how == test::HandedOver::kMidpoints ? " (midpoints filled in)"
              : how == test::HandedOver::kFilled    ? " (steps filled at diagonal / 300)"
              : how == test::HandedOver::kResampled ? " (resampled by arc length at diagonal / 300)"
              : how == test::HandedOver::kWalked    ? " (walked pixel by pixel at a diagonal of 800 pixels)"
              : how == test::HandedOver::kRounded   ? " (rounded to the pixels of a diagonal of 150)"
                                                    : "",
              o.polish ? "defaults (stage 7 on)" : "paper only (stages 1-6)", cap, o.time_budget_ms);
  std::printf("%-12s %5s %7s %4s | %-28s | %-16s | %-16s | %-24s | %-21s | %-16s%s\n", "", "", "", "", "time ms", "segments",
              "extrema_dense", "max_dev/tol", "min_radius/tol", "left out %", cap >= 0 ? " | parts over the cap" : "");
  std::printf("%-12s %5s %7s %4s |%7s%7s%7s%7s |%4s%4s%4s%4s |%4s%4s%4s%4s |%6s%6s%6s%6s | %8s %5s %6s | %5s %5s %4s\n",
              "data set", "files", "strokes", "rej", "med", "p90", "p99", "max", "med", "p90", "p99", "max", "med", "p90",
              "p99", "max", "med", "p90", "p99", "max", "min", "< 1", "%", "p99", "max", ">5%");
  SetFigures all;
  for (std::size_t i = 0; i < g_results.size(); ++i) {
    const SetFigures& set = g_results[i];
    if (!set.ran) continue;
    printRow(kDataSets[i].name, set, cap);
    all.files += set.files, all.strokes += set.strokes, all.rejected += set.rejected;
    all.fitted.insert(all.fitted.end(), set.fitted.begin(), set.fitted.end());
  }
  printRow("all", all, cap);
  std::printf("\n");
  for (std::size_t i = 0; i < g_results.size(); ++i) {
    const std::vector<StrokeFigures>& f = g_results[i].fitted;
    if (f.empty()) continue;
    const auto slowest = std::max_element(f.begin(), f.end(), [](auto& a, auto& b) { return a.ms < b.ms; });
    const auto furthest = std::max_element(f.begin(), f.end(), [](auto& a, auto& b) { return a.deviation < b.deviation; });
    const auto tightest = std::min_element(f.begin(), f.end(), [](auto& a, auto& b) { return a.radius < b.radius; });
    std::printf("%-12s slowest %s (%.1f ms); furthest %s (max_dev/tol %.3g); tightest bend %s (min_radius/tol %.3g)\n",
                kDataSets[i].name, slowest->where.c_str(), slowest->ms, furthest->where.c_str(), furthest->deviation,
                tightest->where.c_str(), tightest->radius);
    for (const StrokeFigures& s : f)
      if (s.kinked) std::printf("%-12s kinked at a joint that is no corner: %s\n", kDataSets[i].name, s.where.c_str());
    for (const StrokeFigures& s : f)
      if (s.parts_over_cap > 0) std::printf("%-12s over the cap: %s (%d parts)\n", kDataSets[i].name, s.where.c_str(), s.parts_over_cap);
    for (const std::string& where : g_results[i].nondeterministic)
      std::printf("%-12s other figures on a repeat: %s\n", kDataSets[i].name, where.c_str());
  }
}

// The --rows file: every fitted stroke's figures (written atomically).
void writeRows() {
  std::string csv = std::string(test::kRowsHeader) + "\n";
  for (std::size_t i = 0; i < g_results.size(); ++i)
    for (const StrokeFigures& s : g_results[i].fitted)
      csv += test::rowCsv(rowOf(kDataSets[i].name, s));
  writeFileAtomically(g_settings.rows, csv);
}

// A numeric flag "NAME=VALUE" (an int or a double) with VALUE in [lo, hi] into `out`;
// false if malformed (NaN included).
template <typename T>
bool numberFlag(std::string_view arg, std::string_view name, T lo, T hi, T& out) {
  return test::wholeNumber(std::string(arg.substr(name.size())), out) && out >= lo && out <= hi;
}

// Takes this program's flags out of argv (Google Benchmark rejects flags it does not
// know); false on a malformed one.
bool takeFlags(int& argc, char** argv) {
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.starts_with("--max-extrema=")) {
      if (!numberFlag(arg, "--max-extrema=", -1, INT_MAX, g_settings.options.segmentation.max_extrema)) return false;
    } else if (arg.starts_with("--time-budget=")) {
      if (!numberFlag(arg, "--time-budget=", 0.0, HUGE_VAL, g_settings.options.time_budget_ms)) return false;
    } else if (arg.starts_with("--variants=")) {
      if (!numberFlag(arg, "--variants=", 1, 8, g_settings.variants)) return false;
    } else if (arg.starts_with("--repeats=")) {
      if (!numberFlag(arg, "--repeats=", 1, 10, g_settings.repeats)) return false;
    } else if (arg == "--handed-over=smoothed") {
      g_settings.handed_over = test::HandedOver::kSmoothed;
    } else if (arg == "--handed-over=midpoints") {
      g_settings.handed_over = test::HandedOver::kMidpoints;
    } else if (arg == "--handed-over=filled") {
      g_settings.handed_over = test::HandedOver::kFilled;
    } else if (arg == "--handed-over=resampled") {
      g_settings.handed_over = test::HandedOver::kResampled;
    } else if (arg == "--handed-over=walked") {
      g_settings.handed_over = test::HandedOver::kWalked;
    } else if (arg == "--handed-over=rounded") {
      g_settings.handed_over = test::HandedOver::kRounded;
    } else if (arg.starts_with("--handed-over=")) {
      return false;
    } else if (arg == "--paper-only") {
      g_settings.options.polish = false;
    } else if (arg.starts_with("--data=")) {
      g_settings.data = arg.substr(std::string_view("--data=").size());
    } else if (arg.starts_with("--rows=")) {
      g_settings.rows = arg.substr(std::string_view("--rows=").size());
      if (g_settings.rows.empty()) return false;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  return true;
}

}  // namespace
}  // namespace la

int main(int argc, char** argv) {
  if (!la::takeFlags(argc, argv)) {
    std::fprintf(stderr,
                 "usage: %s [--max-extrema=N] [--paper-only] [--time-budget=MS] [--variants=K] [--repeats=R] "
                 "[--handed-over=smoothed|midpoints|filled|resampled|walked|rounded] [--data=DIR] [--rows=FILE] [benchmark flags]\n",
                 argv[0]);
    return 2;
  }
  for (std::size_t i = 0; i < std::size(la::test::kDataSets); ++i)
    benchmark::RegisterBenchmark((std::string("BM_FitDataSet/") + la::test::kDataSets[i].name).c_str(), la::BM_FitDataSet, i)
        ->Iterations(1)
        ->Unit(benchmark::kMillisecond);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  la::printTable();
  try {
    if (!la::g_settings.rows.empty()) la::writeRows();
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
    return 1;
  }
  return 0;
}
