// The shared small least-squares solver (core/least_squares.h) against problems with
// known solutions: Rosenbrock's valley, two curves' intersection in closed form, a
// bound, the edge of a domain, and each way a solve can end.

#include "core/least_squares.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace la {
namespace {

// Residuals with a Jacobian in closed form.
LeastSquaresProblem analytic(std::function<Eigen::VectorXd(const Eigen::VectorXd&)> f,
                             std::function<Eigen::MatrixXd(const Eigen::VectorXd&)> j) {
  LeastSquaresProblem p;
  p.residual = [f](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    r = f(x);
    return true;
  };
  p.jacobian = [j](const Eigen::VectorXd& x, Eigen::VectorXd&, Eigen::MatrixXd& jac) {
    jac = j(x);
    return true;
  };
  return p;
}

// r = (10 (y - x^2), 1 - x): the minimum, and zero, at (1, 1) at the end of a curved valley.
LeastSquaresProblem rosenbrock() {
  return analytic([](const Eigen::VectorXd& x) { return Eigen::Vector2d(10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]).eval(); },
                  [](const Eigen::VectorXd& x) {
                    Eigen::Matrix2d j;
                    j << -20.0 * x[0], 10.0, -1.0, 0.0;
                    return Eigen::MatrixXd(j);
                  });
}

LeastSquaresOptions levenbergMarquardt() {
  LeastSquaresOptions o;
  o.tolerance = 1e-12;
  o.initial_damping = 1e-4;
  o.min_damping = 1e-12;
  o.max_damping = 1e14;
  return o;
}

TEST(LeastSquares, LevenbergMarquardtFollowsRosenbrocksValleyToItsEnd) {
  Eigen::VectorXd x = Eigen::Vector2d(-1.2, 1.0), r;
  const LeastSquaresSummary s = solveLeastSquares(rosenbrock(), x, r, levenbergMarquardt());
  EXPECT_EQ(s.end, LeastSquaresEnd::kConverged) << s.message;
  EXPECT_TRUE(s.report().usable());
  EXPECT_NEAR(x[0], 1.0, 1e-12);
  EXPECT_NEAR(x[1], 1.0, 1e-12);
  EXPECT_LE(r.norm(), 1e-12);
  EXPECT_DOUBLE_EQ(s.initial_cost, Eigen::Vector2d(10.0 * (1.0 - 1.44), 2.2).norm());
  EXPECT_EQ(s.final_cost, r.norm());
  EXPECT_GE(s.residual_evaluations, s.successful_steps + 1);
  EXPECT_EQ(s.jacobian_evaluations, s.successful_steps);
}

// x^2 + y^2 = 4 and x y = 1 meet where x^2 = 2 + sqrt(3), y = 1 / x.
TEST(LeastSquares, NewtonStepsFindTwoCurvesIntersectionQuadratically) {
  const LeastSquaresProblem p = analytic(
      [](const Eigen::VectorXd& x) { return Eigen::Vector2d(x.squaredNorm() - 4.0, x[0] * x[1] - 1.0).eval(); },
      [](const Eigen::VectorXd& x) {
        Eigen::Matrix2d j;
        j << 2.0 * x[0], 2.0 * x[1], x[1], x[0];
        return Eigen::MatrixXd(j);
      });
  LeastSquaresOptions o;
  o.tolerance = 1e-13;
  o.cost = LeastSquaresCost::kLargest;
  Eigen::VectorXd x = Eigen::Vector2d(2.0, 0.4), r;
  const LeastSquaresSummary s = solveLeastSquares(p, x, r, o);
  ASSERT_EQ(s.end, LeastSquaresEnd::kConverged) << s.message;
  const double truth = std::sqrt(2.0 + std::sqrt(3.0));
  EXPECT_NEAR(x[0], truth, 1e-13);
  EXPECT_NEAR(x[1], 1.0 / truth, 1e-13);
  EXPECT_LE(s.successful_steps, 6);  // quadratic convergence from a tenth off
  EXPECT_EQ(s.unsuccessful_steps, 0);
}

// A residual that exists only for x > 0: a full Newton step leaves the domain, a halved
// one comes back into it.
TEST(LeastSquares, AStepOutsideTheDomainIsHalvedBackIntoIt) {
  LeastSquaresProblem p;
  p.residual = [](const Eigen::VectorXd& x, Eigen::VectorXd& r) {
    if (!(x[0] > 0.0)) return false;
    r = Eigen::VectorXd::Constant(1, std::log(x[0] / 0.01));
    return true;
  };
  p.jacobian = [](const Eigen::VectorXd& x, Eigen::VectorXd&, Eigen::MatrixXd& j) {
    j = Eigen::MatrixXd::Constant(1, 1, 1.0 / x[0]);
    return true;
  };
  LeastSquaresOptions o;
  o.tolerance = 1e-14;
  o.max_halvings = 8;
  Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 1.0), r;
  const LeastSquaresSummary s = solveLeastSquares(p, x, r, o);
  ASSERT_EQ(s.end, LeastSquaresEnd::kConverged) << s.message;
  EXPECT_NEAR(x[0], 0.01, 1e-15);
  EXPECT_GT(s.unsuccessful_steps, 0);
}

// |x - 3| with x <= 2: the solve stops on the bound, with no descent left, and says so.
TEST(LeastSquares, ABoundStopsTheSolveWhereItIsClosest) {
  const LeastSquaresProblem p = analytic([](const Eigen::VectorXd& x) { return (x.array() - 3.0).matrix().eval(); },
                                         [](const Eigen::VectorXd&) { return Eigen::MatrixXd::Identity(1, 1).eval(); });
  LeastSquaresOptions o = levenbergMarquardt();
  o.lower = Eigen::VectorXd::Constant(1, -10.0);
  o.upper = Eigen::VectorXd::Constant(1, 2.0);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(1), r;
  const LeastSquaresSummary s = solveLeastSquares(p, x, r, o);
  EXPECT_EQ(s.end, LeastSquaresEnd::kNoDescent);
  EXPECT_EQ(s.report().status, SolveStatus::kInfeasible);
  EXPECT_EQ(x[0], 2.0);
  EXPECT_EQ(s.final_cost, 1.0);
}

// The step limit: scaled, a step keeps its direction; clamped, each unknown moves by at
// most the limit on its own. r = x - (3, 1) from the origin, limit 0.5.
TEST(LeastSquares, AStepLimitScalesTheStepOrClampsEachUnknown) {
  for (const bool clamp : {false, true}) {
    std::vector<Eigen::VectorXd> path;
    LeastSquaresProblem p = analytic([](const Eigen::VectorXd& x) { return (x - Eigen::Vector2d(3.0, 1.0)).eval(); },
                                     [](const Eigen::VectorXd&) { return Eigen::MatrixXd::Identity(2, 2).eval(); });
    p.converged = [&](const Eigen::VectorXd& x, const Eigen::VectorXd& r) {
      path.push_back(x);
      return r.norm() <= 1e-12;
    };
    LeastSquaresOptions o;
    o.max_step = Eigen::Vector2d::Constant(0.5);
    o.clamp_step = clamp;
    Eigen::VectorXd x = Eigen::Vector2d::Zero(), r;
    const LeastSquaresSummary s = solveLeastSquares(p, x, r, o);
    ASSERT_EQ(s.end, LeastSquaresEnd::kConverged) << s.message;
    EXPECT_EQ(s.successful_steps, 6) << clamp;  // 3 / 0.5 steps in x
    ASSERT_EQ(path.size(), 7u);
    // after the first step: along (3, 1) scaled, or 0.5 in each
    EXPECT_NEAR(path[1][0], 0.5, 1e-15);
    EXPECT_NEAR(path[1][1], clamp ? 0.5 : 0.5 / 3.0, 1e-15);
  }
}

TEST(LeastSquares, EachWayASolveEndsIsReported) {
  {  // out of iterations
    LeastSquaresOptions o = levenbergMarquardt();
    o.max_iterations = 2;
    Eigen::VectorXd x = Eigen::Vector2d(-1.2, 1.0), r;
    const LeastSquaresSummary s = solveLeastSquares(rosenbrock(), x, r, o);
    EXPECT_EQ(s.end, LeastSquaresEnd::kIterationLimit);
    EXPECT_EQ(s.report().status, SolveStatus::kIterationLimit);
    EXPECT_LT(s.final_cost, s.initial_cost);  // the best point so far
  }
  {  // no residual at the start
    LeastSquaresProblem p = rosenbrock();
    p.residual = [](const Eigen::VectorXd&, Eigen::VectorXd&) { return false; };
    Eigen::VectorXd x = Eigen::Vector2d(0.0, 0.0), r;
    const LeastSquaresSummary s = solveLeastSquares(p, x, r, levenbergMarquardt());
    EXPECT_EQ(s.end, LeastSquaresEnd::kStartInvalid);
    EXPECT_EQ(s.report().status, SolveStatus::kBadInput);
    EXPECT_FALSE(s.report().usable());
  }
  {  // no Jacobian
    LeastSquaresProblem p = rosenbrock();
    p.jacobian = [](const Eigen::VectorXd&, Eigen::VectorXd&, Eigen::MatrixXd&) { return false; };
    Eigen::VectorXd x = Eigen::Vector2d(0.0, 0.0), r;
    const LeastSquaresSummary s = solveLeastSquares(p, x, r, levenbergMarquardt());
    EXPECT_EQ(s.end, LeastSquaresEnd::kNoJacobian);
    EXPECT_EQ(s.report().status, SolveStatus::kInfeasible);
    EXPECT_EQ(x, Eigen::VectorXd(Eigen::Vector2d(0.0, 0.0)));
  }
  {  // a minimum that is not a zero: r = (x, 1)
    const LeastSquaresProblem p = analytic([](const Eigen::VectorXd& x) { return Eigen::Vector2d(x[0], 1.0).eval(); },
                                           [](const Eigen::VectorXd&) { return Eigen::MatrixXd(Eigen::Vector2d(1.0, 0.0)); });
    Eigen::VectorXd x = Eigen::VectorXd::Constant(1, 5.0), r;
    const LeastSquaresSummary s = solveLeastSquares(p, x, r, levenbergMarquardt());
    EXPECT_EQ(s.end, LeastSquaresEnd::kNoDescent);
    EXPECT_NEAR(x[0], 0.0, 1e-6);  // (where x^2 no longer changes 1 + x^2)
    EXPECT_NEAR(s.final_cost, 1.0, 1e-12);
  }
}

}  // namespace
}  // namespace la
