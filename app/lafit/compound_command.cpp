// `lafit compound`: a compound-rhythm LA curve (two LA segments joined G3) from four
// control points, like a cubic Bezier polygon (seed 001, core/compound_rhythm.h).

#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>

#include "app/lafit/cli_args.h"
#include "app/lafit/commands.h"
#include "app/lafit/outputs.h"
#include "core/compound_rhythm.h"

namespace la::cli {
namespace {

constexpr const char* kHelp = R"(usage: lafit compound --alpha0 A --alpha1 B [--joint-angle DEG] X0,Y0 X1,Y1 X2,Y2 X3,Y3 [outputs]

Builds a compound-rhythm log-aesthetic curve: two LA segments, the first with LCG slope
A and the second with slope B, joined with continuous curvature and continuous
derivative of the radius of curvature (G3). The four points are read like the control
polygon of a cubic Bezier curve: the curve starts at Q0 heading towards Q1 and ends at
Q3 arriving from the direction of Q2. The polygon must turn one way (no S shape).

  --alpha0 A          LCG slope of the first segment (any finite number; -1 clothoid,
                      0 Nielsen's spiral, 1 logarithmic spiral, 2 circle involute)
  --alpha1 B          LCG slope of the second segment
  --joint-angle DEG   tangent direction at the joint, degrees from the +x axis; it must
                      lie between the start and end directions. Default: the direction
                      from the midpoint of Q0Q1 to the midpoint of Q2Q3
  -o FILE.json        the curve in the shared format, plus a "solve" object (status,
                      iterations, residual, control_points, alphas, joint_theta in radians)
  --svg FILE.svg      drawing (add --comb for the curvature comb, --y-up to flip)
  --csv FILE.csv      samples x,y,s,theta,kappa
  --dxf FILE.dxf      SPLINE entities

Exit status: 0 solved, 1 infeasible or bad input (the message says why, with the
reachable range when Q3 is out of reach), 2 usage.
)";

constexpr double kDegree = std::numbers::pi / 180.0;

}  // namespace

int compoundCommand(const std::vector<std::string>& argv) {
  const std::optional<Args> parsed = producingCommandArgs(argv, {"--alpha0", "--alpha1", "--joint-angle"}, {}, kHelp);
  if (!parsed) return 0;
  const Args& args = *parsed;
  if (!args.has("--alpha0") || !args.has("--alpha1")) throw UsageError("compound needs --alpha0 and --alpha1");
  if (args.positional().size() != 4) throw UsageError("compound needs four control points X,Y");
  std::array<Vec2, 4> q;
  for (int i = 0; i < 4; ++i) q[i] = parsePoint(args.positional()[i]);
  const double alpha0 = args.number("--alpha0", 0.0), alpha1 = args.number("--alpha1", 0.0);
  const double joint = args.has("--joint-angle") ? args.number("--joint-angle", 0.0) * kDegree
                                                 : std::numeric_limits<double>::quiet_NaN();
  const CompoundRhythmSolve solve = solveCompoundRhythm(alpha0, alpha1, q, joint);
  if (!solve.report.usable()) {
    std::cerr << "lafit compound: " << toString(solve.report.status) << ": " << solve.report.message << "\n";
    return 1;
  }
  const Curve& curve = *solve.curve;
  const LaSegment& p0 = curve.pieces[0].segment;
  const LaSegment& p1 = curve.pieces[1].segment;
  std::cout << "alphas " << p0.alpha() << " " << p1.alpha() << "\nlengths " << p0.length() << " " << p1.length()
            << "\nkappa " << p0.kappaStart() << " " << p0.kappaEnd() << " " << p1.kappaEnd() << "\njoint "
            << p1.start().x() << "," << p1.start().y() << " at " << solve.joint_theta / kDegree << " degrees"
            << "\niterations " << solve.report.iterations << "\nresidual " << solve.report.residual << "\n";
  nlohmann::json doc = curveToJson(curve);
  stampCurvesFormat(doc);
  nlohmann::json points = nlohmann::json::array();
  for (const Vec2& p : q) points.push_back({p.x(), p.y()});
  doc["solve"] = {{"status", toString(solve.report.status)},
                  {"iterations", solve.report.iterations},
                  {"residual", solve.report.residual},
                  {"control_points", points},
                  {"alphas", {alpha0, alpha1}},
                  {"joint_theta", solve.joint_theta}};
  writeOutputs(args, doc, {curve}, {std::vector<Vec2>(q.begin(), q.end())});
  return 0;
}

}  // namespace la::cli
