// `lafit alp`: one ALP curve (curvature an explicit Bezier function of arc length,
// seeds 000 and 004) by G1 or G2 Hermite interpolation; `lafit alp-region`: the map
// of end curvatures for which such a G2 curve has monotone curvature and no
// inflection (seed 000 section 5.3).

#include <cmath>
#include <iostream>
#include <numbers>

#include "app/lafit/cli_args.h"
#include "app/lafit/commands.h"
#include "app/lafit/outputs.h"
#include "core/alp_curve_json.h"
#include "core/alp_hermite.h"
#include "core/alp_region_map.h"
#include "core/atomic_file.h"

namespace la::cli {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

constexpr const char* kAlpHelp = R"(usage: lafit alp [--g2] [--degree N] [--p P] [--rational --w-e W --p-w PW]
                 X0,Y0,THETA0,KAPPA0 X1,Y1,THETA1,KAPPA1 [outputs]

Builds one ALP curve: its curvature is an explicit Bezier function of arc length of
degree N (Yoshida & Saito), through the two end points with the end tangent
directions THETA (degrees, the direction of travel) and, with --g2, the end
curvatures KAPPA (signed, left turn positive; ignored for G1, write 0). The total
turning is THETA1 - THETA0 exactly as given: add or subtract 360 for another winding.

  --g2             meet the end curvatures too (needs N >= 3); default G1 (N >= 1)
  --degree N       degree of the curvature function (default 3)
  --p P            shape of the free control curvatures (seed 000 eq. 12): 0 linear,
                   in [-1, 1] monotone between the two solved ones (default 0)
  --rational       rational curvature function, weights 1 .. W by eq. 12 with PW
  --w-e W          last weight (default 1: the polynomial)
  --p-w PW         shape of the interior weights, as --p (default 0)
  --samples N      samples in the CSV (default 201)
  -o FILE.json     the curve {"type": "alp", "degree", "control_kappa", "weights",
                   "length", "start", "theta0", "checks"} plus "solve"
  --svg FILE.svg   drawing (add --comb for the curvature comb)
  --csv FILE.csv   samples x,y,s,theta,kappa
  --dxf FILE.dxf   a SPLINE entity

Prints the solve status, the curve and its curvature checks: inflections (sign
changes of kappa) and interior curvature extrema, as arc lengths from the start.
Exit status: 0 solved, 1 no curve (why is printed), 2 usage.
)";

constexpr const char* kRegionHelp = R"(usage: lafit alp-region --theta0 DEG --theta1 DEG [--degree N] [--p P]
                        [--rational --w-e W --p-w PW] [--range K] [--size N]
                        [--svg map.svg] [--csv map.csv]

Maps the end curvatures (kappa_s, kappa_e) for which a G2 ALP curve from (0,0) to
(1,0) with tangent directions DEG (degrees) at its ends exists with monotone
curvature and no inflection (seed 000 section 5.3). Every cell is the individual G2
solve of its centre's curvatures; "no solution" means the solver found none.

  --theta0 DEG   tangent direction at (0,0) (required)
  --theta1 DEG   tangent direction at (1,0) (required); turning theta1 - theta0
  --degree N     degree of the curvature function, >= 3 (default 3)
  --p P          eq. 12 shape of the free control curvatures (default 0)
  --rational, --w-e W, --p-w PW   a rational curvature function, as in lafit alp
  --range K      both axes span [-K, K], curvature times chord (default 4)
  --size N       cells per axis (default 41)
  --svg FILE     the map as an image: grey cells are the region
  --csv FILE     one line per cell: kappa_s,kappa_e,cell,status

Exit status: 0 done, 1 bad request, 2 usage.
)";

AlpShape shapeFrom(const Args& args, int fallback_degree) {
  AlpShape shape;
  shape.degree = args.integer("--degree", fallback_degree);
  shape.p = args.number("--p", 0.0);
  shape.rational = args.has("--rational");
  if (!shape.rational && (args.has("--w-e") || args.has("--p-w")))
    throw UsageError("--w-e and --p-w need --rational");
  shape.w_e = args.number("--w-e", 1.0);
  shape.p_w = args.number("--p-w", 0.0);
  if (shape.rational && !(shape.w_e > 0.0)) throw UsageError("--w-e must be positive");
  return shape;
}

void printList(const char* name, const std::vector<double>& values) {
  std::cout << name;
  if (values.empty()) std::cout << " none";
  for (double v : values) std::cout << ' ' << v;
  std::cout << "\n";
}

}  // namespace

int alpCommand(const std::vector<std::string>& argv) {
  const std::optional<Args> parsed = producingCommandArgs(argv, {"--degree", "--p", "--w-e", "--p-w", "--samples"}, {"--g2", "--rational"}, kAlpHelp);
  if (!parsed) return 0;
  const Args& args = *parsed;
  if (args.positional().size() != 2) throw UsageError("alp needs two end conditions X,Y,THETA,KAPPA");
  const int continuity = args.has("--g2") ? 2 : 1;
  const AlpShape shape = shapeFrom(args, 3);
  if (shape.degree < 2 * continuity - 1)
    throw UsageError("G" + std::to_string(continuity) + " needs --degree " + std::to_string(2 * continuity - 1) +
                     " or more");
  const int samples = args.integer("--samples", 201);
  if (samples < 2) throw UsageError("--samples needs at least 2");
  HermiteEnd ends[2];
  for (int i = 0; i < 2; ++i) {
    const std::vector<double> v = parseNumbers(args.positional()[i], 4);
    ends[i] = {Vec2(v[0], v[1]), v[2] * kDegree, v[3]};
  }
  const AlpSolve solve = solveAlpHermite(ends[0], ends[1], continuity, shape);
  std::cout << "status " << toString(solve.report.status) << "\niterations " << solve.report.iterations << "\n";
  if (!solve.report.usable()) {
    std::cerr << "lafit alp: " << toString(solve.report.status) << ": " << solve.report.message << "\n";
    return 1;
  }
  const AlpCurve& curve = *solve.curve;
  const AlpCurvatureCheck& check = solve.check;
  std::cout << "end_gap " << solve.report.residual << " (of the chord)\ndegree " << curve.degree()
            << (curve.isRational() ? " rational" : " polynomial") << "\nlength " << curve.length() << "\nturning "
            << curve.turning() << "\nkappa_start " << curve.kappa(0.0) << "\nkappa_end " << curve.kappa(curve.length())
            << "\n";
  printList("control_kappa", curve.controlKappa());
  if (curve.isRational()) printList("weights", curve.weights());
  std::cout << "inflection " << (check.has_inflection ? "yes" : "no") << "\n";
  printList("inflections_at_s", check.inflections);
  std::cout << "monotone " << (check.monotone ? "yes" : "no") << "\n";
  printList("extrema_at_s", check.extrema);
  nlohmann::json doc = alpCurveToJson(curve, check);
  doc["solve"] = {{"status", toString(solve.report.status)},
                  {"iterations", solve.report.iterations},
                  {"residual", solve.report.residual},
                  {"continuity", continuity},
                  {"p", shape.p},
                  {"w_e", shape.w_e},
                  {"p_w", shape.p_w},
                  {"ends",
                   {{{"point", {ends[0].point.x(), ends[0].point.y()}}, {"theta", ends[0].theta}, {"kappa", ends[0].kappa}},
                    {{"point", {ends[1].point.x(), ends[1].point.y()}}, {"theta", ends[1].theta}, {"kappa", ends[1].kappa}}}}};
  writeAlpOutputs(args, doc, {curve}, {{ends[0].point, ends[1].point}}, samples);
  return 0;
}

int alpRegionCommand(const std::vector<std::string>& argv) {
  const std::set<std::string> valued = {"--theta0", "--theta1", "--degree", "--p", "--w-e", "--p-w",
                                        "--range",  "--size",   "--svg",    "--csv"};
  const Args args(argv, valued, {"--help", "--rational"});
  if (args.has("--help")) {
    std::cout << kRegionHelp;
    return 0;
  }
  if (!args.positional().empty()) throw UsageError("alp-region takes no positional arguments");
  if (!args.has("--theta0") || !args.has("--theta1")) throw UsageError("alp-region needs --theta0 and --theta1");
  AlpRegionRequest request;
  request.theta_start = args.number("--theta0", 0.0) * kDegree;
  request.theta_end = args.number("--theta1", 0.0) * kDegree;
  request.shape = shapeFrom(args, 3);
  if (request.shape.degree < 3) throw UsageError("the G2 region needs --degree 3 or more");
  const double range = args.number("--range", 4.0);
  if (!(range > 0.0) || !std::isfinite(range)) throw UsageError("--range must be positive");
  request.kappa_min = -range;
  request.kappa_max = range;
  request.size = args.integer("--size", 41);
  if (request.size < 1 || request.size > 1000) throw UsageError("--size must be in [1, 1000]");
  const AlpRegionMap map = computeAlpRegionMap(request);
  std::cout << "cells " << map.cells.size() << "\n";
  for (AlpRegionCell c : {AlpRegionCell::kMonotone, AlpRegionCell::kInflection, AlpRegionCell::kNotMonotone,
                          AlpRegionCell::kInflectionAndExtremum, AlpRegionCell::kNoSolution})
    std::cout << toString(c) << ' ' << map.count(c) << "\n";
  if (auto path = args.get("--svg")) {
    writeFileAtomically(*path, alpRegionMapToSvg(map));
    std::cerr << "wrote " << *path << "\n";
  }
  if (auto path = args.get("--csv")) {
    writeFileAtomically(*path, alpRegionMapToCsv(map));
    std::cerr << "wrote " << *path << "\n";
  }
  return 0;
}

}  // namespace la::cli
