// `lafit fit`: one input file (one or several strokes) to fair curves.

#include <algorithm>
#include <cstdio>
#include <iostream>
#include <thread>

#include "app/lafit/commands.h"
#include "app/lafit/fit_file.h"
#include "app/lafit/fit_options.h"
#include "app/lafit/outputs.h"

namespace la::cli {
namespace {

constexpr const char* kHelp = R"(usage: lafit fit INPUT [options]

Fairs every stroke of INPUT into a curve of log-aesthetic segments with continuous
curvature, and prints its quality figures. INPUT is a point file (.csv/.txt: x,y[,t[,p]]
per line, a blank line between strokes; airfoil .dat), the project's stroke .json, or
an .svg (path, polyline and polygon elements). An airfoil .dat is a profile: its only
corner is its trailing edge (its first and last points), its nose is round.

outputs:
  -o FILE.json    the curves (shared format) with quality figures and timings
  --svg FILE.svg  input points and fitted curves (add --comb for the curvature comb,
                  --y-up for data whose y axis points up: profiles, font outlines)
  --csv FILE.csv  samples x,y,s,theta,kappa (a blank line between curves)
  --dxf FILE.dxf  one SPLINE per curve

  --jobs N        strokes fitted in parallel (default: all cores; the curves do not
                  depend on it)

A stroke that cannot be fitted (a dot: fewer than two distinct points) gets
{"error": "why"} in the JSON and the others are still fitted; if none can be, no output
file is written (an existing one is left as it was). Every output is replaced atomically.

exit status: 0 every stroke fitted, 1 the input could not be read or a stroke could
not be fitted (message on stderr), 2 usage error

)";

void printFigures(const FileFit& fit) {
  std::printf("%-6s %5s %6s %10s %11s %10s %9s %9s %7s %7s %7s %9s\n", "stroke", "segs", "closed", "max_dev",
              "tolerance", "rms_dev", "g1_gap", "g2_gap", "extrema", "inflect", "corners", "time_ms");
  bool raised = false;
  for (std::size_t i = 0; i < fit.strokes.size(); ++i) {
    if (!fit.results[i]) {
      std::printf("%-6zu error: %s\n", i + 1, fit.errors[i].c_str());
      continue;
    }
    const FitResult& r = *fit.results[i];
    const QualityFigures& q = r.quality;
    const bool noisy = r.tolerance > r.requested_tolerance;
    raised |= noisy;
    std::printf("%-6zu %5d %6s %10.4g %10.4g%s %10.4g %9.2g %9.2g %7d %7d %7d %9.3f\n", i + 1, q.segments,
                r.curve.closed ? "yes" : "no", q.max_dev, r.tolerance, noisy ? "*" : " ", q.rms_dev, q.g1_gap, q.g2_gap,
                q.extrema, q.inflections, q.corners, r.timings.total_ms);
    for (const std::string& w : r.warnings) std::printf("       warning: %s\n", w.c_str());
  }
  if (raised) std::printf("* the tolerance asked for, raised to the noise floor of the points (their noise and pixel grid)\n");
}

}  // namespace

int fitCommand(const std::vector<std::string>& argv) {
  std::set<std::string> valued = kOutputOptions, flags = kOutputFlags;
  valued.insert(kFitValued.begin(), kFitValued.end());
  valued.insert("--jobs");
  flags.insert(kFitFlags.begin(), kFitFlags.end());
  flags.insert("--help");
  const Args args(argv, valued, flags);
  if (args.has("--help")) {
    std::cout << kHelp << kFitOptionsHelp;
    return 0;
  }
  if (args.positional().size() != 1) throw UsageError("fit needs exactly one INPUT file");
  const FitOptions options = fitOptionsFrom(args);
  const int jobs = args.integer("--jobs", static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
  if (jobs < 1) throw UsageError("--jobs must be at least 1");
  const FileFit fit = fitFile(args.positional()[0], options, readLimitsFrom(args), args.has("--stages"), jobs);
  printFigures(fit);
  for (const std::string& error : fit.errors)
    if (!error.empty()) std::cerr << "lafit fit: " << error << "\n";
  // Nothing fitted is a failed run: it must not replace an earlier run's outputs.
  if (fit.failed() == static_cast<int>(fit.strokes.size())) {
    std::cerr << "lafit fit: no stroke could be fitted; no output written\n";
    return 1;
  }
  writeOutputs(args, fit.document, fit.curves(), fit.points());
  return fit.failed() > 0 ? 1 : 0;
}

}  // namespace la::cli
