#pragma once
// Small dense nonlinear least squares: the unknowns x (a handful) that make a residual
// r(x) smallest, or zero. The project's multi-unknown shape solves share this one
// iteration, as its scalar ones share core/root_finding.h: the G2 joint angles of
// stage 6 (fitting/g2_joints.cpp), the end curvature and alpha of a segment shot at a
// point (fitting/spline_chain.cpp), the ALP Hermite solve (core/alp_hermite.cpp) and
// the triple-LA solve's start (core/triple_la_hermite.cpp, lawStart).
//
// Each step solves (J^T J + lambda d I) dx = -J^T r, d = max(trace(J^T J), a floor)
// (Levenberg-Marquardt; lambda = 0 and a square J: the Newton step J dx = -r by
// full-pivot LU). The step is limited (no |dx_i| above its max_step: the whole step
// scaled down, or each entry clamped), x + dx is clamped to the bounds, and the step is
// halved up to max_halvings times while the cost (|r|, or its largest entry) does not
// fall; where no halving helps, lambda grows (up to max_damping, then the solve stops:
// a local minimum of the cost, or the edge of the problem's domain). An accepted step
// shrinks lambda again.
//
// Why not ceres::Solver (the project's least-squares library, used where it serves:
// fitting/one_segment.cpp): on these problems each residual is a whole curve solve, so
// the evaluations are the cost. Stage 5's shot segment solved both ways to 1e-12 of its
// length (tests/benchmarks/least_squares_benchmark.cpp): Ceres 35 evaluations a solve
// and 2.6 times the time, this solver 15. Ceres evaluates the residual again with every
// Jacobian and stops on relative changes, not on a residual target; and G2's rule that
// every joint's gap improve (the largest) is no sum of squares.
// The chain fit of stage 7 (fitting/chain_fit.h) and the triple-LA Hermite solve
// (core/triple_la_hermite.cpp) iterate on their own, and say why where they do: the
// first has equality constraints in every step (Ceres has bounds only), the second
// takes a predicted last step without evaluating it.
//
// The summary follows ceres::Solver::Summary: how the solve ended, the costs, the step
// counts; its report is the project's SolveReport (core/solve_report.h).

#include <Eigen/Core>
#include <functional>
#include <string>

#include "core/solve_report.h"

namespace la {

struct LeastSquaresProblem {
  /// r(x); false where x is outside the problem's domain (or r is not finite).
  std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd& r)> residual;
  /// J(x) at an accepted x whose residual is r (the callee may refresh r there); false:
  /// no Jacobian there, the solve stops.
  std::function<bool(const Eigen::VectorXd& x, Eigen::VectorXd& r, Eigen::MatrixXd& jacobian)> jacobian;
  /// Done at x (unset: the cost at most LeastSquaresOptions::tolerance).
  std::function<bool(const Eigen::VectorXd& x, const Eigen::VectorXd& r)> converged;
  /// The largest step of each unknown from x (unset: LeastSquaresOptions::max_step).
  std::function<Eigen::VectorXd(const Eigen::VectorXd& x)> max_step;
};

enum class LeastSquaresCost {
  kNorm,     // |r|
  kLargest,  // max |r_i|: every equation must improve on the worst
};

struct LeastSquaresOptions {
  int max_iterations = 50;
  double tolerance = 0.0;  // the cost at which the solve has converged (unless the problem says)
  LeastSquaresCost cost = LeastSquaresCost::kNorm;
  /// Levenberg-Marquardt's lambda, relative to the trace of J^T J (at least
  /// damping_floor): its start, its growth on a step that does not lower the cost, its
  /// shrink on one that does, and its range. initial_damping = max_damping = 0: Newton
  /// steps.
  double initial_damping = 0.0, damping_growth = 10.0, damping_shrink = 0.1;
  double min_damping = 0.0, max_damping = 0.0, damping_floor = 1e-300;
  /// Halvings of a step that does not lower the cost, before lambda grows.
  int max_halvings = 0;
  /// |dx_i| <= max_step_i for every i (empty: no limit; an entry may be infinite), the
  /// whole step scaled down (its direction kept) or, with clamp_step, each entry clamped.
  Eigen::VectorXd max_step;
  bool clamp_step = false;
  /// Bounds on x (empty: none).
  Eigen::VectorXd lower, upper;
};

enum class LeastSquaresEnd {
  kConverged,
  kIterationLimit,
  kNoDescent,     // no step (damped or halved) lowers the cost: a local minimum, or a singular J
  kNoJacobian,    // the problem had no Jacobian at an accepted x
  kStartInvalid,  // no residual at the start
};

struct LeastSquaresSummary {
  LeastSquaresEnd end = LeastSquaresEnd::kStartInvalid;
  double initial_cost = INFINITY, final_cost = INFINITY;  // in the options' cost
  int successful_steps = 0, unsuccessful_steps = 0;       // unsuccessful: a trial the cost rejected
  int residual_evaluations = 0, jacobian_evaluations = 0;
  std::string message;
  /// status kConverged, kIterationLimit, kInfeasible (no descent, no Jacobian) or
  /// kBadInput (no residual at the start); residual = final_cost.
  SolveReport report() const;
};

/// Minimizes the cost from x (replaced by the best point reached); the problem's
/// residual at that point is `r` on return.
LeastSquaresSummary solveLeastSquares(const LeastSquaresProblem& problem, Eigen::VectorXd& x, Eigen::VectorXd& r,
                                      const LeastSquaresOptions& options);

}  // namespace la
