#pragma once
// Stage 6 (DESIGN.md section 3; seed 003 sections 3.2-3.3): make curvature continuous
// at every joint by rotating the joints' common tangents, joint positions fixed.
//
// Rotating the tangent at joint j changes the end curvature of the piece before it
// and the start curvature of the piece after it in opposite directions, so the gap
//   g_j = kappa_end(piece j-1) - kappa_start(piece j)
// is monotone in that angle. Two solvers:
//  - kBisection, the paper's: take the joint with the largest gap, bisect its angle
//    until its gap vanishes, repeat until every gap is below the threshold;
//  - kNewton, the default: all joint angles at once. g_j depends only on the angles at
//    joints j-1, j, j+1, so the Jacobian is tridiagonal (cyclic for a closed chain);
//    it is built by finite differences (two piece solves per joint) and each step is
//    halved until no piece becomes infeasible and the gaps shrink.
// A sliding joint (Chain::sliding) keeps its angle and moves along its tangent line
// instead; that shapes the same two pieces, so the system stays square and tridiagonal.
// A joint between two inflection ends has kappa = 0 on both sides by construction:
// its angle stays put and it has no equation.

#include <vector>

#include "core/la_segment.h"
#include "core/solve_report.h"
#include "fitting/chain.h"

namespace la {

enum class G2Method { kNewton, kBisection, kOff };
const char* toString(G2Method method);

struct G2Options {
  G2Method method = G2Method::kNewton;
  double threshold = 1e-6;  // relative gap, DESIGN.md section 6 (g2_gap)
  int max_iterations = 60;  // Newton steps, or joint bisections per joint for kBisection
  double diagonal = 1.0;    // drawing scale for the relative gap: 1/diagonal floors |kappa|
};

struct G2Result {
  std::vector<LaSegment> segments;  // one per piece, in the final joint angles
  std::vector<double> gaps;         // relative curvature gap per joint (DESIGN.md 6)
  double max_gap = 0.0;
  SolveReport report;
};

/// Builds every piece of the chain and, unless method is kOff, moves the joint angles
/// (in `chain`) until every relative gap is below the threshold. If a piece cannot be
/// built at the start the result has status kInfeasible and no segments.
G2Result makeG2(Chain& chain, const G2Options& options);

/// Relative curvature gap of DESIGN.md section 6.
double relativeGap(double kappa_left, double kappa_right, double diagonal);

}  // namespace la
