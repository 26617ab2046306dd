// Reads the rows of data_benchmark runs (--rows=FILE, data_rows.h) of one build, or of two
// builds, and prints per data set what the README and the engine journal quote: the fit
// time per stroke as the fastest of its runs (median / p90 / p99 / max, nearest rank, and
// the sum), the segments and `extrema_dense` summed, the strokes at 2 extrema or fewer
// (issue 16's pen-stroke figure), the largest max_dev/tol and the strokes over 1, the
// tightest min_radius/tol and the strokes under 1. With two builds, also every stroke
// whose figures changed from the first to the second, and the strokes only one has.
//
//   build/tests/benchmarks/compare_rows A1.csv [A2.csv ...] [--vs B1.csv [B2.csv ...]]
//
// The machine's speed drifts by 10-40% from one run to the next, so two builds are timed
// by runs interleaved (A, B, A, B, ...), each with --repeats=3, and compared here. A fit is
// deterministic: the strokes whose figures differ between runs of one build are listed.
// Exit status 0; 2 on a bad argument or a file that cannot be read (which file, which
// line, what is wrong).

#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "tests/benchmarks/data_rows.h"

namespace la::test {
namespace {

struct Build {
  std::vector<std::string> files;
  FastestRows fastest;
};

Build readBuild(const std::vector<std::string>& files) {
  std::vector<std::vector<StrokeRow>> runs;
  for (const std::string& file : files) {
    std::ifstream in(file, std::ios::binary);
    if (!in) throw std::runtime_error(file + ": cannot be read");
    std::ostringstream text;
    text << in.rdbuf();
    runs.push_back(readRows(text.str(), file));
  }
  return {files, fastestOf(runs)};
}

// The data sets in the order the rows have them (the first build's, then the second's).
std::vector<std::string> dataSetsOf(const std::vector<const Build*>& builds) {
  std::vector<std::string> sets;
  for (const Build* b : builds)
    for (const StrokeRow& r : b->fastest.rows)
      if (std::find(sets.begin(), sets.end(), r.data_set) == sets.end()) sets.push_back(r.data_set);
  return sets;
}

void printHeader() {
  std::printf("%-12s %-2s %7s | %-42s | %8s | %-18s | %-16s | %-16s\n", "", "", "", "time ms (per stroke the fastest of its runs)",
              "segments", "extrema_dense", "max_dev/tol", "min_radius/tol");
  std::printf("%-12s %-2s %7s | %7s %7s %7s %7s %9s | %8s | %8s %9s | %7s %8s | %7s %8s\n", "data set", "", "strokes", "med",
              "p90", "p99", "max", "sum s", "sum", "sum", "at <= 2", "max", "over 1", "min", "under 1");
}

// One build's row of data set `set` ("all": every stroke), under `label`.
void printRow(const std::string& label, const std::string& set, const char* build, const std::vector<StrokeRow>& all) {
  std::vector<double> ms;
  double sum_ms = 0.0, worst = 0.0, tightest = INFINITY;
  int segments = 0, extrema = 0, fair = 0, over = 0, under = 0;
  for (const StrokeRow& r : all) {
    if (set != "all" && r.data_set != set) continue;
    ms.push_back(r.ms);
    sum_ms += r.ms;
    segments += r.segments, extrema += r.extrema_dense;
    if (r.extrema_dense <= 2) ++fair;
    worst = std::max(worst, r.deviation), tightest = std::min(tightest, r.radius);
    if (r.deviation > 1.0) ++over;
    if (r.radius < 1.0) ++under;
  }
  if (ms.empty()) {
    std::printf("%-12s %-2s %7d | (no strokes)\n", label.c_str(), build, 0);
    return;
  }
  std::printf("%-12s %-2s %7zu | %7.2f %7.1f %7.1f %7.1f %9.3f | %8d | %8d %9d | %7.3f %8d | %7.3g %8d\n", label.c_str(), build,
              ms.size(), percentile(ms, 0.5), percentile(ms, 0.9), percentile(ms, 0.99), percentile(ms, 1.0), sum_ms / 1000.0,
              segments, extrema, fair, worst, over, tightest, under);
}

void printBuildFiles(const char* name, const Build& b) {
  std::printf("%s: %zu run%s (", name, b.files.size(), b.files.size() == 1 ? "" : "s");
  for (std::size_t i = 0; i < b.files.size(); ++i) std::printf("%s%s", i ? ", " : "", b.files[i].c_str());
  std::printf("), %zu strokes\n", b.fastest.rows.size());
}

void printDiffering(const char* name, const Build& b) {
  if (!b.fastest.differing.empty()) std::printf("\n");
  for (const std::string& stroke : b.fastest.differing)
    std::printf("%s: other figures in another run (a fit is deterministic): %s\n", name, stroke.c_str());
}

// Every stroke whose figures changed from a to b, the totals of those changes, and the
// strokes only one build has.
void printChanges(const Build& a, const Build& b) {
  std::map<std::pair<std::string, std::string>, const StrokeRow*> after;
  for (const StrokeRow& r : b.fastest.rows) after[{r.data_set, r.stroke}] = &r;
  std::set<std::pair<std::string, std::string>> seen;
  int common = 0, changed = 0, d_segments = 0, d_extrema = 0;
  std::string lines, only_a;
  char line[512];
  for (const StrokeRow& r : a.fastest.rows) {
    const auto it = after.find({r.data_set, r.stroke});
    if (it == after.end()) {
      only_a += "  only in A: " + r.data_set + " " + r.stroke + "\n";
      continue;
    }
    seen.insert(it->first);
    ++common;
    const StrokeRow& s = *it->second;
    if (sameFigures(r, s)) continue;
    ++changed;
    d_segments += s.segments - r.segments, d_extrema += s.extrema_dense - r.extrema_dense;
    std::snprintf(line, sizeof line,
                  "  %s %s: segments %d -> %d, extrema_dense %d -> %d, max_dev/tol %.6g -> %.6g, min_radius/tol %.6g -> %.6g\n",
                  r.data_set.c_str(), r.stroke.c_str(), r.segments, s.segments, r.extrema_dense, s.extrema_dense, r.deviation,
                  s.deviation, r.radius, s.radius);
    lines += line;
  }
  std::printf("\nStrokes whose figures changed from A to B: %d of the %d in both (segments %+d, extrema_dense %+d)\n%s%s", changed,
              common, d_segments, d_extrema, lines.c_str(), only_a.c_str());
  for (const StrokeRow& s : b.fastest.rows)
    if (!seen.count({s.data_set, s.stroke})) std::printf("  only in B: %s %s\n", s.data_set.c_str(), s.stroke.c_str());
}

int run(int argc, char** argv) {
  std::vector<std::string> files_a, files_b;
  bool vs = false;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--vs") {
      if (vs) return -1;
      vs = true;
    } else if (arg.starts_with("-")) {
      return -1;
    } else {
      (vs ? files_b : files_a).emplace_back(arg);
    }
  }
  if (files_a.empty() || (vs && files_b.empty())) return -1;
  const Build a = readBuild(files_a);
  const Build b = vs ? readBuild(files_b) : Build{};
  printBuildFiles("A", a);
  if (vs) printBuildFiles("B", b);
  std::vector<const Build*> builds{&a};
  if (vs) builds.push_back(&b);
  std::printf("\n");
  printHeader();
  std::vector<std::string> sets = dataSetsOf(builds);
  sets.push_back("all");
  for (const std::string& set : sets) {
    printRow(set, set, "A", a.fastest.rows);
    if (vs) printRow("", set, "B", b.fastest.rows);
  }
  printDiffering("A", a);
  if (vs) {
    printDiffering("B", b);
    printChanges(a, b);
  }
  return 0;
}

}  // namespace
}  // namespace la::test

int main(int argc, char** argv) {
  try {
    if (la::test::run(argc, argv) == 0) return 0;
  } catch (const std::runtime_error& e) {
    std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
    return 2;
  }
  std::fprintf(stderr, "usage: %s A1.csv [A2.csv ...] [--vs B1.csv [B2.csv ...]]  (data_benchmark --rows files)\n", argv[0]);
  return 2;
}
