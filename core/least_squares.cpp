#include "core/least_squares.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace la {

SolveReport LeastSquaresSummary::report() const {
  SolveStatus status = SolveStatus::kInfeasible;
  switch (end) {
    case LeastSquaresEnd::kConverged: status = SolveStatus::kConverged; break;
    case LeastSquaresEnd::kIterationLimit: status = SolveStatus::kIterationLimit; break;
    case LeastSquaresEnd::kNoDescent:
    case LeastSquaresEnd::kNoJacobian: status = SolveStatus::kInfeasible; break;
    case LeastSquaresEnd::kStartInvalid: status = SolveStatus::kBadInput; break;
  }
  return {status, successful_steps, final_cost, message};
}

LeastSquaresSummary solveLeastSquares(const LeastSquaresProblem& problem, Eigen::VectorXd& x, Eigen::VectorXd& r,
                                      const LeastSquaresOptions& options) {
  LeastSquaresSummary out;
  auto costOf = [&](const Eigen::VectorXd& v) {
    return options.cost == LeastSquaresCost::kLargest ? (v.size() ? v.cwiseAbs().maxCoeff() : 0.0) : v.norm();
  };
  auto evaluate = [&](const Eigen::VectorXd& at, Eigen::VectorXd& res) {
    ++out.residual_evaluations;
    return problem.residual(at, res) && res.allFinite();
  };
  auto done = [&] {
    return problem.converged ? problem.converged(x, r) : costOf(r) <= options.tolerance;
  };
  auto stop = [&](LeastSquaresEnd end, std::string message) {
    out.end = end;
    out.message = std::move(message);
    out.final_cost = costOf(r);
    return out;
  };
  if (!evaluate(x, r)) return stop(LeastSquaresEnd::kStartInvalid, "no residual at the start");
  out.initial_cost = costOf(r);
  const bool bounded = options.lower.size() == x.size() && options.upper.size() == x.size();
  double lambda = options.initial_damping;
  Eigen::MatrixXd jacobian;
  Eigen::VectorXd trial, trial_r;
  for (int iteration = 0;; ++iteration) {
    if (done()) return stop(LeastSquaresEnd::kConverged, "converged");
    if (iteration == options.max_iterations) return stop(LeastSquaresEnd::kIterationLimit, "iteration limit");
    ++out.jacobian_evaluations;
    if (!problem.jacobian(x, r, jacobian) || !r.allFinite()) return stop(LeastSquaresEnd::kNoJacobian, "no Jacobian");
    const double cost = costOf(r);
    // (Newton steps, lambda 0 throughout, need no normal equations)
    const bool newton = lambda == 0.0 && jacobian.rows() == jacobian.cols();
    Eigen::MatrixXd jtj;
    Eigen::VectorXd gradient;
    if (!newton) jtj = jacobian.transpose() * jacobian, gradient = jacobian.transpose() * r;
    const double scale = newton ? 0.0 : std::max(jtj.trace(), options.damping_floor);
    const Eigen::VectorXd limit = problem.max_step ? problem.max_step(x) : options.max_step;
    // (a larger lambda, where one is allowed: the step got no lower cost)
    auto damper = [&] {
      const double next = lambda * options.damping_growth;
      if (!(lambda > 0.0) || !(next <= options.max_damping)) return false;
      lambda = next;
      return true;
    };
    bool accepted = false;
    while (!accepted) {
      Eigen::VectorXd step;
      if (newton) {
        step = jacobian.fullPivLu().solve(-r);
      } else {
        Eigen::MatrixXd a = jtj;
        a.diagonal().array() += lambda * scale;
        step = -a.ldlt().solve(gradient);
      }
      if (!step.allFinite()) {
        if (damper()) continue;
        return stop(LeastSquaresEnd::kNoDescent, "singular Jacobian");
      }
      if (limit.size() == step.size()) {
        double shrink = 1.0;
        for (Eigen::Index i = 0; i < step.size(); ++i) {
          if (!(std::abs(step[i]) > limit[i])) continue;
          if (options.clamp_step) step[i] = std::copysign(limit[i], step[i]);
          else shrink = std::min(shrink, limit[i] / std::abs(step[i]));
        }
        if (shrink < 1.0) step *= shrink;
      }
      double t = 1.0;
      for (int halving = 0; halving <= options.max_halvings && !accepted; ++halving, t *= 0.5) {
        trial = x + t * step;
        if (bounded) trial = trial.cwiseMax(options.lower).cwiseMin(options.upper);
        accepted = evaluate(trial, trial_r) && costOf(trial_r) < cost;
        if (!accepted) ++out.unsuccessful_steps;
      }
      if (!accepted && !damper()) return stop(LeastSquaresEnd::kNoDescent, "no step lowers the cost");
    }
    x = trial;
    r = trial_r;
    ++out.successful_steps;
    lambda = std::max(lambda * options.damping_shrink, options.min_damping);
  }
}

}  // namespace la
