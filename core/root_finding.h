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
  double value = std::nan("");       // f(x)
  double derivative = std::nan("");  // f'(x) as returned by f
  /// Nonzero only when the solve stopped on `newton_finish_tol`: the root is x +
  /// newton_step, one Newton step that was predicted, not evaluated (the caller moves
  /// what it computed at x along by first order; |step| <= newton_finish_max_step).
  double newton_step = 0.0;
  SolveReport report;
};

struct RootOptions {
  double x_tol = 1e-14;  // relative: stop when the bracket is below x_tol * (1 + |x|)
  double f_tol = 0.0;    // absolute: stop when |f(x)| <= f_tol
  /// Absolute, in units of f; 0 = off. Also stop when one more Newton step d = -f/f'
  /// is predicted to land within this: |f''| d^2 / 2 <= newton_finish_tol, with f''
  /// estimated from f' at the last two iterates (so never at the first). Saves the
  /// evaluation that would only confirm the root.
  double newton_finish_tol = 0.0;
  /// ... and only when that step is at most this (absolute, in x): the caller's
  /// first-order update of what it computed at x must stay exact.
  double newton_finish_max_step = 1e-8;
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
  double prev_x = std::nan(""), prev_d = std::nan("");
  for (int iter = 1; iter <= options.max_iterations; ++iter) {
    const auto [v, d] = f(x);
    result.x = x;
    result.value = v;
    result.derivative = d;
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
    if (options.newton_finish_tol > 0.0 && std::isfinite(next) && lo < next && next < hi) {
      // secant estimate of f'' from the last two iterates
      const double curvature =
          (std::isfinite(prev_d) && x != prev_x) ? std::abs((d - prev_d) / (x - prev_x)) : std::nan("");
      const double step = next - x;
      if (std::isfinite(curvature) && std::abs(step) <= options.newton_finish_max_step &&
          0.5 * curvature * step * step <= options.newton_finish_tol) {
        result.newton_step = step;
        result.report.residual = 0.5 * curvature * step * step;
        result.report.status = SolveStatus::kConverged;
        result.report.message = "converged: last Newton step predicted";
        return result;
      }
    }
    prev_x = x;
    prev_d = d;
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
