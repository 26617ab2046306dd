// `lafit hermite`: the triple-LA G2 Hermite curve (seed 002) between two ends given by
// point, tangent angle and curvature.

#include <cmath>
#include <iostream>
#include <numbers>

#include "app/lafit/cli_args.h"
#include "app/lafit/commands.h"
#include "app/lafit/outputs.h"
#include "core/triple_la_hermite.h"

namespace la::cli {
namespace {

constexpr const char* kHelp = R"(usage: lafit hermite --alpha A X0,Y0,THETA0,KAPPA0 X1,Y1,THETA1,KAPPA1 [outputs]

G2 Hermite interpolation by a triple log-aesthetic curve (seed 002): three LA pieces
with one alpha, joints at 0.25 and 0.75 of the length, curvature continuous, from
the start point (tangent angle THETA0, curvature KAPPA0) to the end point (THETA1,
KAPPA1). Angles in degrees; curvature signed, left turn positive. The total turning
is THETA1 - THETA0 exactly as given (not wrapped): add or subtract 360 to choose the
winding. For alpha >= 0 the curvature keeps one sign (no inflection); for alpha < 0 a
piece may change sign and is then written as two segments joined at the inflection.

  --alpha A       slope of the LCG of all three pieces (-1: a triple clothoid; inf: circle)
  -o FILE.json    the curve in the shared curve format, plus a "solve" object
  --svg FILE.svg  drawing (add --comb for the curvature comb)
  --csv FILE.csv  samples x,y,s,theta,kappa
  --dxf FILE.dxf  SPLINE entities

Prints the length, the joint curvatures and the solve report.
Exit status: 0 solved, 1 infeasible, not converged or bad input (message on stderr), 2 usage.
)";

constexpr double kDegree = std::numbers::pi / 180.0;

HermiteEnd parseEnd(const std::string& text) {
  const std::vector<double> v = parseNumbers(text, 4);
  return {Vec2(v[0], v[1]), v[2] * kDegree, v[3]};
}

nlohmann::json endJson(const HermiteEnd& e) {
  return {{"point", {e.point.x(), e.point.y()}}, {"theta", e.theta}, {"kappa", e.kappa}};
}

}  // namespace

int hermiteCommand(const std::vector<std::string>& argv) {
  const std::optional<Args> parsed = producingCommandArgs(argv, {"--alpha"}, {}, kHelp);
  if (!parsed) return 0;
  const Args& args = *parsed;
  if (!args.has("--alpha")) throw UsageError("hermite needs --alpha A");
  if (args.positional().size() != 2) throw UsageError("hermite needs two ends X,Y,THETA,KAPPA (THETA in degrees)");
  const double alpha = args.number("--alpha", -1.0);
  const HermiteEnd start = parseEnd(args.positional()[0]), end = parseEnd(args.positional()[1]);
  const TripleLaHermiteSolve solve = solveTripleLaHermite(alpha, start, end);
  if (!solve.report.usable()) {
    std::cerr << "lafit hermite: " << toString(solve.report.status) << ": " << solve.report.message << "\n";
    return 1;
  }
  const Curve& curve = *solve.curve;
  std::cout << "alpha " << alpha << "\nlength " << solve.length << "\nkappa_joint1 " << solve.kappa1
            << "\nkappa_joint2 " << solve.kappa2 << "\nsegments " << curve.pieces.size() << "\niterations "
            << solve.report.iterations << "\nresidual " << solve.report.residual << "\n";
  nlohmann::json doc = curveToJson(curve);
  stampCurvesFormat(doc);
  doc["solve"] = {{"status", toString(solve.report.status)},
                  {"iterations", solve.report.iterations},
                  {"residual", solve.report.residual},
                  {"message", solve.report.message},
                  {"alpha", std::isinf(alpha) ? nlohmann::json(alpha > 0 ? "inf" : "-inf") : nlohmann::json(alpha)},
                  {"start", endJson(start)},
                  {"end", endJson(end)},
                  {"length", solve.length},
                  {"kappa_joints", {solve.kappa1, solve.kappa2}}};
  writeOutputs(args, doc, {curve}, {{start.point, end.point}});
  return 0;
}

}  // namespace la::cli
