#include "core/solve_report.h"

namespace la {

const char* toString(SolveStatus status) {
  switch (status) {
    case SolveStatus::kConverged: return "converged";
    case SolveStatus::kIterationLimit: return "iteration_limit";
    case SolveStatus::kInfeasible: return "infeasible";
    case SolveStatus::kBadInput: return "bad_input";
  }
  return "unknown";
}

}  // namespace la
