// Tests of the Gauss-Legendre rules and the adaptive integrator (core/quadrature.h)
// against closed-form integrals: rule structure, exactness up to degree 2N-1 and the
// known error term at degree 2N, and adaptive integration of smooth, singular-
// derivative and vector-valued integrands to the requested tolerance.

#include "core/quadrature.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <numbers>

namespace la {
namespace {

// Integral over [0, 1] of (2x - 1)^k: 1/(k+1) for even k, 0 for odd k.
double centeredMonomialIntegral(int k) { return k % 2 ? 0.0 : 1.0 / (k + 1); }

// Deterministic coefficients in [-1, 1] for a test polynomial.
double coefficient(int k) { return std::sin(1.0 + 2.3 * k); }

template <int N>
void checkRule() {
  const auto& rule = gaussLegendre<N>();
  // Structure: nodes strictly ascending inside (0, 1), symmetric about 1/2, positive
  // weights symmetric and summing to 1 (to 1e-15).
  double sum = 0.0;
  for (int i = 0; i < N; ++i) {
    EXPECT_GT(rule.node[i], 0.0) << "N=" << N << " i=" << i;
    EXPECT_LT(rule.node[i], 1.0) << "N=" << N << " i=" << i;
    if (i > 0) {
      EXPECT_GT(rule.node[i], rule.node[i - 1]) << "N=" << N << " i=" << i;
    }
    EXPECT_NEAR(rule.node[i] + rule.node[N - 1 - i], 1.0, 1e-15) << "N=" << N << " i=" << i;
    EXPECT_GT(rule.weight[i], 0.0) << "N=" << N << " i=" << i;
    EXPECT_NEAR(rule.weight[i], rule.weight[N - 1 - i], 1e-15) << "N=" << N << " i=" << i;
    sum += rule.weight[i];
  }
  EXPECT_NEAR(sum, 1.0, 1e-15) << "N=" << N << ": weights sum to " << sum;

  // Exact for every polynomial of degree <= 2N-1: each centered monomial to 1e-15,
  // and a polynomial with all 2N coefficients to 1e-14 * sum |c_k|.
  double poly_rule = 0.0, poly_exact = 0.0, poly_scale = 0.0;
  for (int k = 0; k <= 2 * N - 1; ++k) {
    double q = 0.0;
    for (int i = 0; i < N; ++i) q += rule.weight[i] * std::pow(2.0 * rule.node[i] - 1.0, k);
    EXPECT_NEAR(q, centeredMonomialIntegral(k), 1e-15)
        << "N=" << N << " degree " << k << ": rule " << q << " exact " << centeredMonomialIntegral(k);
    poly_rule += coefficient(k) * q;
    poly_exact += coefficient(k) * centeredMonomialIntegral(k);
    poly_scale += std::abs(coefficient(k));
  }
  EXPECT_NEAR(poly_rule, poly_exact, 1e-14 * poly_scale) << "N=" << N << " degree 2N-1 polynomial";

  // ... but not for degree 2N: the error of x^{2N} on [0, 1] is the classical
  // E = (N!)^4 / ((2N+1) ((2N)!)^2) (Abramowitz & Stegun 25.4.30 with f^(2N) = (2N)!).
  // Checked where E is large enough to resolve in doubles.
  double q = 0.0;
  for (int i = 0; i < N; ++i) q += rule.weight[i] * std::pow(rule.node[i], 2 * N);
  const double err = 1.0 / (2 * N + 1) - q;
  const double expected_err =
      std::exp(4 * std::lgamma(N + 1.0) - std::log(2.0 * N + 1) - 2 * std::lgamma(2.0 * N + 1));
  if (expected_err > 1e-9) {
    EXPECT_NEAR(err, expected_err, 1e-6 * expected_err)
        << "N=" << N << " degree 2N error: got " << err << " expected " << expected_err;
  }
}

TEST(GaussLegendreTest, RulesHaveStructureAndPolynomialExactness) {
  checkRule<1>();
  checkRule<2>();
  checkRule<3>();
  checkRule<4>();
  checkRule<5>();
  checkRule<10>();
  checkRule<24>();
  checkRule<64>();
}

TEST(GaussLegendreTest, SmallRulesMatchTabulatedNodes) {
  // N = 2: 1/2 -+ 1/(2 sqrt 3), weights 1/2. N = 3: 1/2 -+ sqrt(3/5)/2, weights 5/18,
  // 8/18, 5/18. To 4e-16 (two ulps of 1/2).
  const auto& r2 = gaussLegendre<2>();
  EXPECT_NEAR(r2.node[0], 0.5 - 0.5 / std::sqrt(3.0), 4e-16);
  EXPECT_NEAR(r2.node[1], 0.5 + 0.5 / std::sqrt(3.0), 4e-16);
  EXPECT_NEAR(r2.weight[0], 0.5, 4e-16);
  const auto& r3 = gaussLegendre<3>();
  EXPECT_NEAR(r3.node[0], 0.5 - 0.5 * std::sqrt(0.6), 4e-16);
  EXPECT_NEAR(r3.node[1], 0.5, 4e-16);
  EXPECT_NEAR(r3.weight[0], 5.0 / 18.0, 4e-16);
  EXPECT_NEAR(r3.weight[1], 8.0 / 18.0, 4e-16);
}

TEST(GaussLegendreTest, IntegrateFixedMapsTheInterval) {
  // integrateFixed<10> on [a, b]: a cubic exactly (1e-14 relative), exp to 1e-14.
  const double cubic = integrateFixed<10>([](double x) { return 3 * x * x * x - x + 2; }, -1.0, 3.0);
  const double cubic_exact = 3.0 / 4 * (81.0 - 1.0) - 0.5 * (9.0 - 1.0) + 2 * 4.0;
  EXPECT_NEAR(cubic, cubic_exact, 1e-14 * std::abs(cubic_exact));
  const double e = integrateFixed<10>([](double x) { return std::exp(x); }, 0.5, 1.5);
  EXPECT_NEAR(e, std::exp(1.5) - std::exp(0.5), 1e-14 * e);
}

TEST(AdaptiveQuadratureTest, SmoothIntegrandsReachTolerance) {
  // |value - exact| <= tol, the estimate <= tol, converged, for several tolerances.
  struct Case {
    const char* name;
    double (*f)(double);
    double a, b, exact;
  };
  const Case cases[] = {
      {"exp", [](double x) { return std::exp(x); }, 0.0, 1.0, std::exp(1.0) - 1.0},
      {"cos(10x)", [](double x) { return std::cos(10 * x); }, 0.0, 3.0, std::sin(30.0) / 10},
      {"runge", [](double x) { return 1.0 / (1.0 + 25 * x * x); }, -1.0, 1.0, 0.4 * std::atan(5.0)},
      {"oscillating", [](double x) { return std::sin(x * x); }, 0.0, 0.0 + 1.0, 0.3102683017233811},
  };
  for (const Case& c : cases) {
    for (double tol : {1e-6, 1e-10, 1e-13}) {
      const auto r = integrateAdaptive(c.f, c.a, c.b, tol);
      const double err = std::abs(r.value - c.exact);
      EXPECT_LE(err, tol) << c.name << " tol " << tol << ": got " << r.value << " exact "
                          << c.exact << " error " << err;
      EXPECT_TRUE(r.converged) << c.name << " tol " << tol;
      EXPECT_LE(r.error_estimate, tol) << c.name << " tol " << tol;
      EXPECT_GE(r.panels, 1) << c.name;
    }
  }
}

TEST(AdaptiveQuadratureTest, SqrtWithSingularDerivativeReachesTolerance) {
  // sqrt(x) on [0, 1] = 2/3: the derivative is infinite at 0, so one rule cannot be
  // exact; the integrator must split towards 0. Error <= tol, more panels for a
  // tighter tolerance.
  int previous_panels = 0;
  for (double tol : {1e-4, 1e-8, 1e-12}) {
    const auto r = integrateAdaptive([](double x) { return std::sqrt(x); }, 0.0, 1.0, tol);
    const double err = std::abs(r.value - 2.0 / 3.0);
    EXPECT_LE(err, tol) << "tol " << tol << ": got " << r.value << " error " << err;
    EXPECT_TRUE(r.converged) << "tol " << tol;
    EXPECT_LE(r.error_estimate, tol) << "tol " << tol;
    EXPECT_GT(r.panels, previous_panels) << "tol " << tol;
    previous_panels = r.panels;
  }
  // Without splitting the 10-point rule alone is far off, so the test can fail.
  const double single = integrateFixed<10>([](double x) { return std::sqrt(x); }, 0.0, 1.0);
  EXPECT_GT(std::abs(single - 2.0 / 3.0), 1e-6) << "single rule " << single;
}

TEST(AdaptiveQuadratureTest, NearlySingularEndWhoseRoundingIsNoise) {
  // 1/sqrt(c - x) on [0, 1], c = 1 + d just past the end: near x = 1 the rounding of
  // c - x, times the huge derivative there, is noise above each small panel's share of
  // the tolerance, so the rule that asks every panel for the same relative accuracy
  // bisected until its 20,000-panel cap and returned 1e-7 to 1e-5 off. Within the
  // tolerance, converged, with a few tens of panels. (The truth is taken at c as
  // rounded: c - 1 is exact.)
  for (double d : {1e-9, 1e-12}) {
    const double c = 1.0 + d;
    const double exact = 2.0 * (std::sqrt(c) - std::sqrt(c - 1.0));
    for (double tol : {1e-8, 1e-10, 1e-12}) {
      const auto r = integrateAdaptive([c](double x) { return 1.0 / std::sqrt(c - x); }, 0.0, 1.0, tol);
      EXPECT_LE(std::abs(r.value - exact), tol) << "d " << d << " tol " << tol;
      EXPECT_TRUE(r.converged) << "d " << d << " tol " << tol;
      EXPECT_LE(r.panels, 200) << "d " << d << " tol " << tol;
    }
  }
}

TEST(AdaptiveQuadratureTest, VectorIntegrand) {
  // Eigen::Vector2d integrands: (cos t, sin t) on [0, 2.5] = (sin 2.5, 1 - cos 2.5),
  // and (sqrt t, t^2) on [0, 2] = (2^{3/2} 2/3, 8/3); max-abs error <= tol.
  for (double tol : {1e-8, 1e-12}) {
    const auto circle = integrateAdaptive(
        [](double t) -> Eigen::Vector2d { return {std::cos(t), std::sin(t)}; }, 0.0, 2.5, tol);
    const Eigen::Vector2d circle_exact(std::sin(2.5), 1.0 - std::cos(2.5));
    EXPECT_LE((circle.value - circle_exact).cwiseAbs().maxCoeff(), tol)
        << "got " << circle.value.transpose() << " exact " << circle_exact.transpose();
    EXPECT_TRUE(circle.converged);

    const auto mixed = integrateAdaptive(
        [](double t) -> Eigen::Vector2d { return {std::sqrt(t), t * t}; }, 0.0, 2.0, tol);
    const Eigen::Vector2d mixed_exact(2.0 / 3.0 * std::pow(2.0, 1.5), 8.0 / 3.0);
    EXPECT_LE((mixed.value - mixed_exact).cwiseAbs().maxCoeff(), tol)
        << "got " << mixed.value.transpose() << " exact " << mixed_exact.transpose();
    EXPECT_TRUE(mixed.converged);
  }
}

TEST(AdaptiveQuadratureTest, EmptyIntervalAndDepthLimit) {
  // [a, a] integrates to 0. An integrable singularity 1/sqrt(x) with a tiny tolerance
  // and max_depth 4 cannot converge: converged must be false, the value still close.
  const auto empty = integrateAdaptive([](double x) { return x; }, 1.0, 1.0, 1e-12);
  EXPECT_EQ(empty.value, 0.0);
  const auto limited =
      integrateAdaptive([](double x) { return 1.0 / std::sqrt(x); }, 0.0, 1.0, 1e-14, 4);
  EXPECT_FALSE(limited.converged);
  EXPECT_NEAR(limited.value, 2.0, 0.1);
  EXPECT_GT(limited.error_estimate, 1e-14);
}

TEST(AdaptiveQuadratureTest, UnattainableToleranceStopsAtDepthLimit) {
  // A tolerance below rounding noise (1e-16 absolute on a vector integral of size ~1,
  // the unit tangent of a log spiral) cannot be met: with max_depth 12 the integrator
  // must stop, report converged = false, and still return the value to 1e-13. The
  // work is bounded by the depth: at most 2^12 accepted panels.
  // (With the default max_depth = 60 the same call does not return in practice: the
  // number of panels grows ~2^depth, about 2.7e5 panels at depth 20.)
  int calls = 0;
  auto tangent = [&calls](double s) -> Eigen::Vector2d {
    ++calls;
    const double theta = 0.4 + std::log1p(0.2 * s) / 0.2;
    return {std::cos(theta), std::sin(theta)};
  };
  const auto r = integrateAdaptive(tangent, 0.0, 10.0, 1e-16, 12);
  // Closed form: rho = 1 + 0.2 s, integral = (e^{(c+i) phi} - 1)/(c+i) e^{0.4 i}, c = 0.2.
  const double c = 0.2, phi = std::log(3.0) / c;
  const double ex = std::exp(c * phi);
  // (e^{c phi} (cos phi + i sin phi) - 1) / (c + i), rotated by 0.4.
  const double re = ex * std::cos(phi) - 1.0, im = ex * std::sin(phi);
  const double den = c * c + 1.0;
  const double qx = (re * c + im) / den, qy = (im * c - re) / den;
  const Eigen::Vector2d exact(std::cos(0.4) * qx - std::sin(0.4) * qy,
                              std::sin(0.4) * qx + std::cos(0.4) * qy);
  EXPECT_FALSE(r.converged);
  EXPECT_LE(r.panels, 1 << 12);
  EXPECT_LE((r.value - exact).cwiseAbs().maxCoeff(), 1e-13)
      << "got " << r.value.transpose() << " exact " << exact.transpose();
  EXPECT_GT(calls, 0);
}

}  // namespace
}  // namespace la
