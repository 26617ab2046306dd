// `lafit segment`: one LA segment from a control triangle (the 3-point construction,
// or the inflection-end construction that solves for alpha).

#include <iostream>

#include "app/lafit/cli_args.h"
#include "app/lafit/commands.h"
#include "app/lafit/outputs.h"
#include "core/inflection_segment.h"
#include "core/three_point_segment.h"

namespace la::cli {
namespace {

constexpr const char* kHelp = R"(usage: lafit segment [--alpha A | --inflection start|end] X0,Y0 X1,Y1 X2,Y2 [outputs]

Builds one log-aesthetic curve segment from its control triangle: Q0 the start, Q1
the intersection of the end tangents, Q2 the end (Yoshida & Saito's construction).

  --alpha A               slope of the LCG (default -1, a clothoid); inf for a circle
  --inflection start|end  zero curvature at that end instead; alpha is solved for
  -o FILE.json            the segment in the shared curve format
  --svg FILE.svg          drawing (add --comb for the curvature comb)
  --csv FILE.csv          samples x,y,s,theta,kappa
  --dxf FILE.dxf          a SPLINE entity

Exit status: 0 solved, 1 infeasible or bad input (the reachable range is printed), 2 usage.
)";

}  // namespace

int segmentCommand(const std::vector<std::string>& argv) {
  const std::optional<Args> parsed = producingCommandArgs(argv, {"--alpha", "--inflection"}, {}, kHelp);
  if (!parsed) return 0;
  const Args& args = *parsed;
  if (args.positional().size() != 3) throw UsageError("segment needs three control points X,Y");
  const Vec2 q0 = parsePoint(args.positional()[0]), q1 = parsePoint(args.positional()[1]),
             q2 = parsePoint(args.positional()[2]);
  SegmentSolve solve;
  if (auto end = args.get("--inflection")) {
    if (*end != "start" && *end != "end") throw UsageError("--inflection takes start or end");
    if (args.has("--alpha")) throw UsageError("--inflection solves for alpha; do not give --alpha");
    solve = solveInflectionSegment(q0, q1, q2, *end == "start" ? InflectionEnd::kStart : InflectionEnd::kEnd);
  } else {
    solve = solveThreePointSegment(args.number("--alpha", -1.0), q0, q1, q2);
  }
  if (!solve.report.usable()) {
    std::cerr << "lafit segment: " << toString(solve.report.status) << ": " << solve.report.message << "\n";
    return 1;
  }
  const LaSegment& seg = *solve.segment;
  std::cout << "alpha " << seg.alpha() << "\nlength " << seg.length() << "\nkappa_start " << seg.kappaStart()
            << "\nkappa_end " << seg.kappaEnd() << "\nturning " << seg.turning() << "\niterations "
            << solve.report.iterations << "\n";
  Curve curve;
  curve.pieces.push_back({seg, false});
  nlohmann::json doc = curveToJson(curve);
  stampCurvesFormat(doc);
  doc["solve"] = {{"status", toString(solve.report.status)},
                  {"iterations", solve.report.iterations},
                  {"residual", solve.report.residual},
                  {"control_points", {{q0.x(), q0.y()}, {q1.x(), q1.y()}, {q2.x(), q2.y()}}}};
  writeOutputs(args, doc, {curve}, {{q0, q1, q2}});
  return 0;
}

}  // namespace la::cli
