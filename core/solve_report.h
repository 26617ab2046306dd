#pragma once
// The result every iterative solver in the project returns (STYLE.md, convention 3).
// Like ceres::Solver::Summary, the defaults assume failure: a report is only
// usable once a solver has said it converged.

#include <limits>
#include <string>

namespace la {

enum class SolveStatus {
  kConverged,       // residual below the requested tolerance
  kIterationLimit,  // ran out of iterations; the result is the best seen, not trusted
  kInfeasible,      // the request has no solution (message says why, with the reachable range)
  kBadInput,        // NaN, coincident or collinear points, angles out of range
};

const char* toString(SolveStatus status);

struct SolveReport {
  SolveStatus status = SolveStatus::kBadInput;
  int iterations = 0;
  double residual = std::numeric_limits<double>::infinity();
  std::string message = "not solved";

  bool usable() const { return status == SolveStatus::kConverged; }
};

}  // namespace la
