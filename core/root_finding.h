#pragma once
// Scalar root finding for monotone functions: Newton's method kept inside a bracket,
// falling back to bisection whenever a Newton step would leave it. Every shape
// solve in the project (3-point segment, inflection segment, G2 joint rotation)
// reduces to one monotone equation, so this is the one place that iterates.

#include <cmath>
#include <string>
#include <utility>

#include "core/solve_report.h"

namespace la {

struct RootResult {
  double x = std::nan("");
  double value = std::nan("");  // f(x)
  SolveReport report;
};

struct RootOptions {
  double x_tol = 1e-14;  // relative: stop when the bracket is below x_tol * (1 + |x|)
  double f_tol = 0.0;    // absolute: stop when |f(x)| <= f_tol
  int max_iterations = 100;
};

/// Solves f(x) = 0 on [lo, hi] for f monotone (increasing or decreasing as told).
/// f returns {value, derivative}; a derivative of 0 or NaN just forces bisection.
/// If the root is not inside the bracket the result is kInfeasible, with x at the
/// end that came closest.
template <class F>
RootResult solveMonotone(F&& f, double lo, double hi, double x0, bool increasing,
                         const RootOptions& options = {}) {
  RootResult result;
  if (!(lo <= x0 && x0 <= hi) || !std::isfinite(lo) || !std::isfinite(hi)) {
    result.report.message = "solveMonotone: start outside a finite bracket";
    return result;
  }
  bool below_seen = false, above_seen = false;  // f < 0 and f > 0 both observed
  bool lo_tried = false, hi_tried = false;
  double x = x0;
  for (int iter = 1; iter <= options.max_iterations; ++iter) {
    const auto [v, d] = f(x);
    result.x = x;
    result.value = v;
    result.report.iterations = iter;
    result.report.residual = std::abs(v);
    if (!std::isfinite(v)) {
      result.report.status = SolveStatus::kBadInput;
      result.report.message = "function is not finite at x = " + std::to_string(x);
      return result;
    }
    if (std::abs(v) <= options.f_tol) {
      result.report.status = SolveStatus::kConverged;
      result.report.message = "converged: |f| below tolerance";
      return result;
    }
    if ((v < 0.0) == increasing) {
      lo = x;
      below_seen = true;
    } else {
      hi = x;
      above_seen = true;
    }
    if (hi - lo <= options.x_tol * (1.0 + std::abs(x))) {
      const bool bracketed = below_seen && above_seen;
      result.report.status = bracketed ? SolveStatus::kConverged : SolveStatus::kInfeasible;
      result.report.message = bracketed ? "converged: bracket collapsed"
                                        : "no root inside the bracket";
      return result;
    }
    double next = x - v / d;
    // A Newton step past an end that was never evaluated tries that end once: if the
    // sign does not change there, the root is outside and the next pass says so,
    // instead of bisecting all the way to the end.
    if (std::isfinite(next) && next >= hi && !above_seen && !hi_tried) {
      next = hi;
      hi_tried = true;
    } else if (std::isfinite(next) && next <= lo && !below_seen && !lo_tried) {
      next = lo;
      lo_tried = true;
    } else if (!std::isfinite(next) || next <= lo || next >= hi) {
      next = 0.5 * (lo + hi);
    }
    x = next;
  }
  result.report.status = SolveStatus::kIterationLimit;
  result.report.message = "iteration limit reached";
  return result;
}

}  // namespace la
