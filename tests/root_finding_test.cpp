// Tests of the safeguarded Newton solver (core/root_finding.h): the predicted last
// Newton step (newton_finish_tol) against closed-form roots, and its guards.

#include "core/root_finding.h"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

namespace la {
namespace {

// f(x) = x^3 - c, increasing on [0, 3]; root cbrt(c), f'' = 6x.
auto cubic(double c, int& evaluations) {
  return [c, &evaluations](double x) {
    ++evaluations;
    return std::pair{x * x * x - c, 3.0 * x * x};
  };
}

TEST(RootFinding, PredictedLastStepLandsOnTheRoot) {
  int saved = 0;  // evaluations saved over the four roots
  for (double c : {0.5, 2.0, 7.0, 20.0}) {
    int plain_evaluations = 0, predicted_evaluations = 0;
    RootOptions plain;
    plain.f_tol = 1e-14;
    plain.x_tol = 1e-16;
    const RootResult a = solveMonotone(cubic(c, plain_evaluations), 0.0, 3.0, 1.5, true, plain);
    RootOptions predicted = plain;
    predicted.newton_finish_tol = 1e-14;
    const RootResult b = solveMonotone(cubic(c, predicted_evaluations), 0.0, 3.0, 1.5, true, predicted);
    ASSERT_TRUE(a.report.usable()) << a.report.message;
    ASSERT_TRUE(b.report.usable()) << b.report.message;
    const double root = std::cbrt(c);
    EXPECT_NEAR(a.x + a.newton_step, root, 1e-14) << "c " << c;
    EXPECT_EQ(a.newton_step, 0.0) << "off by default";
    // the predicted step is one Newton step from b.x, itself accurate to ~f'' d^2
    EXPECT_NEAR(b.x + b.newton_step, root, 1e-14) << "c " << c << " x " << b.x << " step " << b.newton_step;
    EXPECT_LE(std::abs(b.newton_step), predicted.newton_finish_max_step) << "c " << c;
    EXPECT_LE(predicted_evaluations, plain_evaluations) << "c " << c;
    saved += plain_evaluations - predicted_evaluations;
    EXPECT_EQ(b.report.iterations, predicted_evaluations);
  }
  EXPECT_GE(saved, 2) << "the confirming evaluation is saved for most roots";
}

TEST(RootFinding, PredictedStepRespectsItsCap) {
  // With the cap at 0 a step is never predicted: the result is the plain one.
  int evaluations = 0;
  RootOptions options;
  options.f_tol = 1e-14;
  options.newton_finish_tol = 1e-14;
  options.newton_finish_max_step = 0.0;
  const RootResult r = solveMonotone(cubic(2.0, evaluations), 0.0, 3.0, 1.5, true, options);
  ASSERT_TRUE(r.report.usable()) << r.report.message;
  EXPECT_EQ(r.newton_step, 0.0);
  EXPECT_NEAR(r.x, std::cbrt(2.0), 1e-14);
}

TEST(RootFinding, NoRootInsideTheBracketIsInfeasibleAlsoWithPrediction) {
  int evaluations = 0;
  RootOptions options;
  options.f_tol = 1e-14;
  options.newton_finish_tol = 1e-14;
  const RootResult r = solveMonotone(cubic(50.0, evaluations), 0.0, 3.0, 1.5, true, options);  // root 3.68
  EXPECT_EQ(r.report.status, SolveStatus::kInfeasible) << r.report.message;
  EXPECT_EQ(r.newton_step, 0.0);
}

}  // namespace
}  // namespace la
